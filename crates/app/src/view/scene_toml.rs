//! The view's current settings as a scene-settings file (`crates/core/src/settings.rs`) that
//! `slc render` accepts as its scene: the scene file, the fly camera, the (moved) lights and
//! the material overrides of the settings file the view was opened with; the render options
//! (strategy, δ, K, ...) go in a comment as the `slc render` command line.
use glam::Vec3;
use slc_core::settings_tables::{camera_table, light_table};
use slc_core::{Camera, Light, MaterialOverride, Scene, Settings};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where the view's scene came from, as a settings file can name it.
#[derive(Clone, Debug)]
pub struct SceneOrigin {
    /// The .gltf/.glb/.obj file (absolute).
    pub file: PathBuf,
    /// The material overrides of the settings file the scene was opened with, if any.
    pub materials: Vec<MaterialOverride>,
}

impl SceneOrigin {
    /// The origin of `scene` opened from `spec` (a scene file or a settings file); a built-in
    /// scene has no file a settings file could name, which is an error.
    pub fn of(spec: &str, scene: &Scene) -> Result<Self, String> {
        let Some(file) = &scene.source else {
            return Err(format!(
                "the built-in scene '{}' has no scene file for a settings file to name; open a \
                 .gltf, .glb, .obj or .toml scene to save settings",
                scene.name
            ));
        };
        let file = std::fs::canonicalize(file)
            .or_else(|_| std::path::absolute(file))
            .map_err(|e| format!("{}: {e}", file.display()))?;
        let materials = if Path::new(spec)
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        {
            Settings::read(Path::new(spec))
                .map_err(|e| e.to_string())?
                .materials
        } else {
            Vec::new()
        };
        Ok(Self { file, materials })
    }
}

/// The settings file text; `command` is the `slc render` command line of its header comment.
pub fn settings_toml(
    origin: &SceneOrigin,
    camera: &Camera,
    lights: &[Light],
    command: &str,
) -> Result<String, String> {
    let mut t = String::new();
    let _ = writeln!(t, "# Saved by slc view. Render it with:");
    let _ = writeln!(t, "#   {command}");
    let _ = writeln!(t, "scene = {}", quoted(&origin.file.display().to_string()));
    let _ = writeln!(t, "replace_lights = true\n");
    // The camera and lights as the settings file's own tables (slc_core::settings_tables).
    let tables = toml::Table::from_iter([
        (
            "camera".to_string(),
            toml::Value::Table(camera_table(camera)),
        ),
        (
            "lights".to_string(),
            toml::Value::Array(
                lights
                    .iter()
                    .map(|l| toml::Value::Table(light_table(l)))
                    .collect(),
            ),
        ),
    ]);
    t.push_str(&toml::to_string(&tables).map_err(|e| e.to_string())?);
    for m in &origin.materials {
        let _ = writeln!(t, "\n[[materials]]\nname = {}", quoted(&m.pattern));
        if let Some(kd) = m.kd {
            let _ = writeln!(t, "kd = {}", vec3(kd));
        }
        if let Some(f0) = m.f0 {
            let _ = writeln!(t, "f0 = {}", vec3(f0));
        }
        if let Some(alpha) = m.alpha {
            let _ = writeln!(t, "alpha = {alpha:?}");
        }
        if let Some(eta) = m.eta {
            let _ = writeln!(t, "eta = {eta:?}");
        }
        if let Some(double_sided) = m.double_sided {
            let _ = writeln!(t, "double_sided = {double_sided}");
        }
        if let Some(a) = m.anisotropy {
            let _ = writeln!(t, "anisotropy_strength = {:?}", a.strength);
            let _ = writeln!(t, "anisotropy_rotation = {:?}", a.rotation);
        }
    }
    Ok(t)
}

/// A TOML array of three floats, each written so that it reads back to the same f32.
fn vec3(v: Vec3) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// A TOML basic string.
fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_read_back_to_the_same_camera_lights_and_materials() {
        let mut scene = slc_core::builtin("default").expect("built-in scene");
        let camera = Camera::look_at(
            Vec3::new(0.1, 1.2, 3.0),
            Vec3::new(-0.3, 0.9, 0.0),
            Vec3::Y,
            0.7,
        )
        .unwrap();
        scene.lights.push(Light::Directional {
            direction: Vec3::new(0.3, -1.0, 0.1).normalize(),
            irradiance: Vec3::new(1.0, 2.0, 3.0),
        });
        let dir = std::env::temp_dir();
        let origin = SceneOrigin {
            file: dir.join("room \"a\".obj"),
            materials: vec![MaterialOverride {
                pattern: "wh*".into(),
                kd: Some(Vec3::splat(0.5)),
                f0: None,
                alpha: Some(0.2),
                eta: Some(1.5),
                double_sided: Some(true),
                anisotropy: Some(slc_core::MaterialAnisotropy {
                    strength: 0.7,
                    rotation: -0.3,
                }),
            }],
        };
        let text = settings_toml(&origin, &camera, &scene.lights, "slc render saved.toml").unwrap();
        let read = Settings::parse(&text, &dir.join("saved.toml")).expect(&text);
        assert_eq!(read.scene, origin.file);
        assert!(read.replace_lights);
        assert_eq!(read.materials, origin.materials);
        let c = read.camera.expect("a camera");
        assert!((c.position - camera.position).length() < 1e-6);
        assert!((c.forward - camera.forward).length() < 1e-6);
        assert!((c.yfov - camera.yfov).abs() < 1e-6);
        assert_eq!(read.lights.len(), scene.lights.len());
        for (a, b) in read.lights.iter().zip(&scene.lights) {
            assert_eq!(a.kind(), b.kind());
            let (Light::Spot { position: pa, .. } | Light::Point { position: pa, .. }) = a else {
                continue;
            };
            let (Light::Spot { position: pb, .. } | Light::Point { position: pb, .. }) = b else {
                panic!("{b:?}");
            };
            assert!((*pa - *pb).length() < 1e-6);
        }
    }

    #[test]
    fn a_built_in_scene_cannot_be_named() {
        let scene = slc_core::builtin("default").unwrap();
        assert!(SceneOrigin::of("default", &scene).is_err());
    }
}
