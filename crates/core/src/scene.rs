//! The scene: meshes, materials, textures, lights and an optional camera.
use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::Light;
use crate::material::Material;
use crate::mesh::{DefectCounts, Mesh};
use crate::texture::Texture;
use glam::Vec3;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// What a loader skipped, fixed or could not find, for the user to read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadReport {
    /// Triangles left out, by defect (degenerate, non-finite, bad index).
    pub skipped: DefectCounts,
    /// Human-readable warnings: missing textures (the factor is used instead), clamped
    /// roughness, unsupported features that were ignored.
    pub warnings: Vec<String>,
    /// Features of the file that slc does not model and ignored (emission, alpha blending,
    /// glTF extensions such as `KHR_materials_clearcoat`, OBJ bump maps), each with the
    /// materials that use it ("the file" for file-wide ones). [`LoadReport::summarize_ignored`]
    /// turns them into one warning.
    pub ignored: BTreeMap<String, Vec<String>>,
    /// Every file the scene was read from, in the order first read, each once: the settings
    /// file, the scene file, its material libraries, buffers and textures. Empty for built-in
    /// and hand-made scenes.
    pub files: Vec<PathBuf>,
}

impl LoadReport {
    /// Records that `by` (a material's name, or "the file") uses `feature`, which is ignored.
    pub fn ignore(&mut self, feature: &str, by: &str) {
        let users = self.ignored.entry(feature.to_string()).or_default();
        if !users.iter().any(|u| u == by) {
            users.push(by.to_string());
        }
    }

    /// Adds one warning naming every ignored feature and how many materials use it (nothing
    /// when none was ignored).
    pub fn summarize_ignored(&mut self) {
        if self.ignored.is_empty() {
            return;
        }
        let list: Vec<String> = self
            .ignored
            .iter()
            .map(|(feature, users)| match users.as_slice() {
                [one] => format!("{feature} ({one})"),
                many => format!("{feature} ({} materials)", many.len()),
            })
            .collect();
        self.warnings.push(format!(
            "not modelled by slc, ignored: {} (the list is in report.json)",
            list.join(", ")
        ));
    }
}

/// A scene in world space (right-handed, +y up by convention of the loaders' sources).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    pub name: String,
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub lights: Vec<Light>,
    pub camera: Option<Camera>,
    pub report: LoadReport,
    /// The file the scene was loaded from (`None` for built-in and hand-made scenes).
    pub source: Option<PathBuf>,
}

impl Scene {
    /// The scene's file path where it came from one, else its name: what messages name.
    pub fn label(&self) -> String {
        self.source
            .as_ref()
            .map_or_else(|| self.name.clone(), |p| p.display().to_string())
    }

    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }

    /// Axis-aligned bounds of every vertex used by a triangle; `None` for an empty scene.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for m in &self.meshes {
            for t in &m.triangles {
                for &i in t {
                    let p = m.positions[i as usize];
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
        }
        (lo.x <= hi.x).then_some((lo, hi))
    }

    /// The offset a ray takes to leave a surface of this scene, on every backend: 2e-5 of the
    /// largest coordinate's magnitude (at least 1).
    pub fn ray_epsilon(&self) -> f32 {
        let extent = self.bounds().map_or(1.0, |(lo, hi)| {
            lo.abs().max(hi.abs()).max_element().max(1.0)
        });
        2e-5 * extent
    }

    /// Whether any material has a specular layer (else no glossy VPL is generated).
    pub fn has_specular(&self) -> bool {
        self.meshes
            .iter()
            .any(|m| self.materials[m.material].has_specular())
    }

    /// Checks what rendering needs: triangles, at least one valid light, valid material indices.
    pub fn validate_for_render(&self) -> Result<(), SceneError> {
        if self.triangle_count() == 0 {
            return Err(SceneError::NoGeometry {
                scene: self.label(),
            });
        }
        if self.lights.is_empty() {
            return Err(SceneError::NoLight {
                scene: self.label(),
            });
        }
        if let Some((i, problem)) = self
            .lights
            .iter()
            .enumerate()
            .find_map(|(i, l)| l.problem().map(|p| (i, p)))
        {
            return Err(SceneError::Invalid {
                scene: self.label(),
                message: format!("light {i} ({}): {problem}", self.lights[i].kind()),
            });
        }
        if let Some(m) = self
            .meshes
            .iter()
            .find(|m| m.material >= self.materials.len())
        {
            return Err(SceneError::Invalid {
                scene: self.label(),
                message: format!(
                    "mesh '{}' refers to material {} of {}",
                    m.name,
                    m.material,
                    self.materials.len()
                ),
            });
        }
        Ok(())
    }

    /// The scene's camera, or one that frames its bounds: placed in front of the +z face of
    /// the bounding box, looking at its centre along -z with +y up and a 45 degree vertical
    /// field of view.
    pub fn camera_or_default(&self) -> Camera {
        if let Some(c) = &self.camera {
            return c.clone();
        }
        let (lo, hi) = self.bounds().unwrap_or((Vec3::splat(-1.0), Vec3::ONE));
        let centre = 0.5 * (lo + hi);
        let half = 0.5 * (hi - lo);
        let yfov = 45f32.to_radians();
        let dist = half.x.max(half.y) / (0.5 * yfov).tan() + half.z;
        let eye = centre + Vec3::Z * dist.max(1e-3);
        let mut cam =
            Camera::look_at(eye, centre, Vec3::Y, yfov).expect("eye differs from centre along z");
        cam.zfar = 4.0 * (dist + half.length()).max(1.0);
        cam
    }
}
