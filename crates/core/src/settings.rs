//! Scene settings: a small TOML file that names a scene file and supplies what it lacks (a
//! camera, lights) or changes what it has (materials, e.g. a glossy floor on Sponza).
//! [`load_scene`](crate::load_scene) reads a `.toml` path as settings; the scene is named by
//! the settings file's stem. Ready-made settings are in the repository's `scenes/` folder.
//!
//! A full example (every key; only `scene` is required):
//!
//! ```toml
//! # Relative to this file (an absolute path is used as is): a .gltf, .glb or .obj file.
//! scene = "../../shared/scenes/sponza/sponza.obj"
//! # Optional: what the scene file is and where to get it, said when it is missing.
//! scene_source = "the Dabrovic Sponza atrium (Marko Dabrovic, 2002); see scenes/README.md"
//! # Optional. Default: the [[lights]] below replace the file's lights if any are given,
//! # else the file's lights are kept. false: add them to the file's lights.
//! replace_lights = true
//!
//! [camera]                      # optional: replaces the file's camera
//! position = [-9.5, 1.7, 0.0]
//! target = [10.0, 3.5, 0.0]     # the point looked at (not equal to position)
//! up = [0.0, 1.0, 0.0]          # optional, default +y; not parallel to the view direction
//! yfov_deg = 60.0               # full vertical field of view in degrees, in (0, 180)
//! znear = 0.05                  # optional, default 0.01; 0 < znear < zfar
//! zfar = 100.0                  # optional, default 1000
//!
//! [[lights]]
//! type = "spot"
//! position = [-12.0, 22.0, 0.5]
//! target = [3.0, 0.1, -1.0]     # or direction = [x, y, z]: exactly one of the two
//! intensity = [8000.0, 7600.0, 6800.0]  # W/sr per channel; one number means grey
//! inner_cone_deg = 10.0         # optional, default 0; 0 <= inner <= outer
//! outer_cone_deg = 15.0         # optional, default 45; 0 < outer <= 90
//!
//! [[lights]]
//! type = "point"
//! position = [0.0, 1.9, 0.0]
//! intensity = 5.0               # W/sr per channel
//!
//! [[lights]]
//! type = "directional"
//! direction = [0.3, -1.0, 0.1]  # the direction the light travels in
//! irradiance = 2.0              # W/m^2 per channel on a surface facing the light
//!
//! [[materials]]                 # overrides, applied in order (a later one wins)
//! name = "sp_00_pod"            # exact material name, or a glob: * matches any run of characters
//! kd = 0.8                      # diffuse albedo in [0, 1] (one number or [r, g, b])
//! f0 = 0.04                     # specular reflectance at normal incidence, in [0, 1]
//! alpha = 0.1                   # GGX alpha in (0, 1]; or roughness = 0.316 (alpha = roughness^2)
//! eta = 1.5                     # relative index of refraction in (0, 1e4]: exact dielectric Fresnel
//! double_sided = true
//! anisotropy_strength = 0.8     # KHR_materials_anisotropy strength in [0, 1] (0: isotropic)
//! anisotropy_rotation = 0.5     # its rotation in radians from the tangent (default 0)
//! ```
//!
//! Rules:
//! - Everything is checked before the scene is touched: unknown keys (a misspelt `intensty`),
//!   wrong types, non-finite numbers, angles and ranges outside the limits above, an override
//!   that sets nothing, and an override matching no material of the scene are errors
//!   ([`SceneError::Settings`]) naming the settings file and the problem; a settings file that
//!   cannot be read is [`SceneError::Io`]. Errors of the scene file itself name that file.
//! - Units are those of [`Light`]: radiometric, not photometric (no candela, no lux).
//! - Material overrides: on a material given by kd, F0 and alpha
//!   ([`MaterialModel::Direct`]) they set those values; a diffuse texture keeps multiplying
//!   `kd`. On a glTF metallic-roughness material, `alpha` alone sets its roughness factor to
//!   `sqrt(alpha)`; `kd` or `f0` turn it into kd, F0 and alpha
//!   (`kd = base (1 - metallic)`, `F0 = 0.04 (1 - metallic) + base metallic`,
//!   `alpha = roughness^2`, the base-colour texture then multiplies `kd`) before the override's
//!   values are set; a warning tells when textures no longer apply in full. An `alpha` below
//!   [`ALPHA_MIN`] is clamped up to it with a warning, as the loaders do. An anisotropy
//!   (glTF `KHR_materials_anisotropy`, [`MaterialAnisotropy`]) replaces the material's; meshes
//!   that lack tangents for it get MikkTSpace ones (a warning where they cannot: no texture
//!   coordinates).
//!
//! The same from code, on a built-in scene instead of the named file:
//!
//! ```
//! use slc_core::{builtin, Settings};
//! use std::path::Path;
//!
//! let text = "scene = \"room.obj\"\n[[materials]]\nname = \"wh*\"\nalpha = 0.2\n";
//! let settings = Settings::parse(text, Path::new("scenes/satin.toml"))?;
//! assert_eq!(settings.scene, Path::new("scenes/room.obj"));
//! let mut scene = builtin("default").expect("a built-in scene");
//! settings.apply(&mut scene)?;
//! assert_eq!(scene.name, "satin");
//! assert_eq!(scene.materials[0].brdf_at(None, &[]).alpha, 0.2);
//! # Ok::<(), slc_core::SceneError>(())
//! ```
use crate::camera::Camera;
use crate::error::SceneError;
use crate::file_read::read_capped;
use crate::import_util::small_alpha_warning;
use crate::light::Light;
use crate::load::{extension, load_scene_file};
use crate::material::{metallic_kd_f0, Material, MaterialAnisotropy, MaterialModel, ALPHA_MIN};
use crate::scene::Scene;
use crate::tangents::generate_tangents;
use glam::Vec3;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Validated scene settings: which scene file to load and what to set in it.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// The settings file: errors name it and its stem names the scene.
    pub path: PathBuf,
    /// The scene file, resolved against the settings file's folder.
    pub scene: PathBuf,
    /// What the scene file is and where to get it, for the error when it is missing.
    pub scene_source: Option<String>,
    /// The camera that replaces the scene file's, if given.
    pub camera: Option<Camera>,
    /// Lights in the order of the file.
    pub lights: Vec<Light>,
    /// Whether `lights` replace the scene file's lights (else they are added to them).
    pub replace_lights: bool,
    /// Material overrides in the order of the file.
    pub materials: Vec<MaterialOverride>,
}

/// New values for the materials whose names match `pattern`; `None` keeps the loaded value.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialOverride {
    /// An exact material name, or a glob where `*` matches any run of characters.
    pub pattern: String,
    pub kd: Option<Vec3>,
    pub f0: Option<Vec3>,
    /// GGX alpha in (0, 1] (a `roughness` in the file is stored squared).
    pub alpha: Option<f32>,
    pub eta: Option<f32>,
    pub double_sided: Option<bool>,
    /// Strength and rotation of an anisotropic lobe (strength 0 makes it isotropic).
    pub anisotropy: Option<MaterialAnisotropy>,
}

/// Loads the scene a settings file names and applies the settings to it.
/// The scene's files ([`crate::LoadReport::files`]) start with the settings file. A scene
/// file that is not there is an error that says what it is and where to get it, where the
/// settings file's `scene_source` tells.
pub fn load_settings(path: &Path) -> Result<Scene, SceneError> {
    let settings = Settings::read(path)?;
    let problem = match std::fs::metadata(&settings.scene) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Some("not found".to_string()),
        Err(e) => Some(format!("cannot be read: {e}")),
        Ok(m) if m.is_dir() => Some("is a folder, not a file".into()),
        Ok(m) if !m.is_file() => Some("is not a regular file (a device, pipe or socket)".into()),
        Ok(_) => None,
    };
    if let Some(problem) = problem {
        let source = settings
            .scene_source
            .as_ref()
            .map_or_else(String::new, |s| format!(": {s}"));
        return Err(SceneError::Settings {
            path: path.to_path_buf(),
            message: format!("scene file {} {problem}{source}", settings.scene.display()),
        });
    }
    let mut scene = load_scene_file(&settings.scene)?;
    settings.apply(&mut scene)?;
    scene.report.files.insert(0, path.to_path_buf());
    Ok(scene)
}

impl Settings {
    /// Reads and validates a settings file (the scene file is not opened).
    pub fn read(path: &Path) -> Result<Self, SceneError> {
        let bytes = read_capped(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let text = String::from_utf8(bytes).map_err(|_| SceneError::Settings {
            path: path.to_path_buf(),
            message: "not UTF-8 text".into(),
        })?;
        Self::parse(&text, path)
    }

    /// Parses and validates settings text that came from the file `path`.
    pub fn parse(text: &str, path: &Path) -> Result<Self, SceneError> {
        let error = |message: String| SceneError::Settings {
            path: path.to_path_buf(),
            message,
        };
        let raw: RawSettings = toml::from_str(text).map_err(|e| error(e.to_string()))?;
        let scene = path.parent().unwrap_or(Path::new("")).join(&raw.scene);
        if !matches!(extension(&scene).as_deref(), Some("gltf" | "glb" | "obj")) {
            return Err(error(format!(
                "scene '{}' is not a .gltf, .glb or .obj file",
                raw.scene
            )));
        }
        let camera = raw
            .camera
            .map(RawCamera::validate)
            .transpose()
            .map_err(|m| error(format!("[camera]: {m}")))?;
        let lights = numbered(raw.lights, "[[lights]]", RawLight::validate).map_err(error)?;
        let replace_lights = raw.replace_lights.unwrap_or(!lights.is_empty());
        if replace_lights && lights.is_empty() {
            return Err(error(
                "replace_lights = true without [[lights]] would leave the scene without light"
                    .into(),
            ));
        }
        let materials =
            numbered(raw.materials, "[[materials]]", RawMaterial::validate).map_err(error)?;
        Ok(Self {
            path: path.to_path_buf(),
            scene,
            scene_source: raw.scene_source,
            camera,
            lights,
            replace_lights,
            materials,
        })
    }

    /// Applies the settings to a loaded scene: name, camera, lights, then material overrides.
    /// Fails without changing the scene when an override matches none of its materials.
    pub fn apply(&self, scene: &mut Scene) -> Result<(), SceneError> {
        let file = self.scene.display().to_string();
        unmatched(&self.materials, scene, &file).map_err(|(i, message)| SceneError::Settings {
            path: self.path.clone(),
            message: format!("[[materials]] #{}: {message}", i + 1),
        })?;
        scene.name = self.path.file_stem().map_or_else(
            || self.path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        );
        if let Some(camera) = &self.camera {
            scene.camera = Some(camera.clone());
        }
        if self.replace_lights {
            scene.lights.clear();
        }
        scene.lights.extend(self.lights.iter().cloned());
        apply_overrides(&self.materials, scene);
        Ok(())
    }
}

/// The first override that matches no material of `scene` (named `label` in the message):
/// its index and why.
fn unmatched(
    overrides: &[MaterialOverride],
    scene: &Scene,
    label: &str,
) -> Result<(), (usize, String)> {
    match overrides.iter().enumerate().find(|(_, o)| {
        !scene
            .materials
            .iter()
            .any(|m| glob_match(&o.pattern, &m.name))
    }) {
        Some((i, o)) => {
            let names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
            Err((
                i,
                format!(
                    "'{}' matches no material of {label} (its materials: {})",
                    o.pattern,
                    names.join(", ")
                ),
            ))
        }
        None => Ok(()),
    }
}

/// Applies `overrides` in order to the materials they match, adding their warnings to the
/// scene's report.
fn apply_overrides(overrides: &[MaterialOverride], scene: &mut Scene) {
    for o in overrides {
        for m in scene
            .materials
            .iter_mut()
            .filter(|m| glob_match(&o.pattern, &m.name))
        {
            scene.report.warnings.extend(o.apply_to(m));
        }
    }
    for mesh in &mut scene.meshes {
        let anisotropic = scene
            .materials
            .get(mesh.material)
            .is_some_and(|m| m.anisotropy.is_some());
        if anisotropic && mesh.tangents.is_none() {
            if let Err(e) = generate_tangents(mesh) {
                scene.report.warnings.push(format!(
                    "mesh '{}': its anisotropy is not applied ({e})",
                    mesh.name
                ));
            }
        }
    }
}

impl Scene {
    /// Applies material overrides (as a settings file's `[[materials]]` do) to a loaded scene;
    /// fails without changing it when one matches none of its materials.
    pub fn override_materials(&mut self, overrides: &[MaterialOverride]) -> Result<(), String> {
        unmatched(overrides, self, &self.label()).map_err(|(_, message)| message)?;
        apply_overrides(overrides, self);
        Ok(())
    }
}

impl MaterialOverride {
    /// A validated override of the materials `pattern` matches, as a settings file's
    /// `[[materials]]` entry: kd and f0 in [0, 1] per channel, alpha or roughness (not both)
    /// in (0, 1], eta in (0, [`crate::material::MAX_ETA`]], and at least one value set.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        pattern: &str,
        kd: Option<[f32; 3]>,
        f0: Option<[f32; 3]>,
        alpha: Option<f32>,
        roughness: Option<f32>,
        eta: Option<f32>,
        double_sided: Option<bool>,
        (anisotropy_strength, anisotropy_rotation): (Option<f32>, Option<f32>),
    ) -> Result<Self, String> {
        RawMaterial {
            name: pattern.to_string(),
            kd: kd.map(Rgb::Rgb),
            f0: f0.map(Rgb::Rgb),
            alpha,
            roughness,
            eta,
            double_sided,
            anisotropy_strength,
            anisotropy_rotation,
        }
        .validate()
    }

    /// Sets the override's values in `m` (see the module documentation for glTF materials);
    /// returns warnings for the user.
    pub fn apply_to(&self, m: &mut Material) -> Vec<String> {
        let mut warnings = Vec::new();
        if let Some(eta) = self.eta {
            m.eta = Some(eta);
        }
        if let Some(double_sided) = self.double_sided {
            m.double_sided = double_sided;
        }
        if let Some(a) = self.anisotropy {
            m.anisotropy = (a.strength > 0.0).then_some(a);
        }
        if let Some(alpha) = self.alpha {
            warnings.extend(small_alpha_warning(&m.name, alpha));
        }
        let changes_model = self.kd.is_some() || self.f0.is_some();
        match &mut m.model {
            MaterialModel::MetallicRoughness { roughness, .. } if !changes_model => {
                if let Some(alpha) = self.alpha {
                    *roughness = alpha.sqrt();
                }
                return warnings;
            }
            MaterialModel::MetallicRoughness {
                base_color,
                base_color_texture: texture,
                metallic,
                roughness,
                metallic_roughness_texture: mr_map,
            } => {
                let (metal, r) = (metallic.clamp(0.0, 1.0), roughness.clamp(0.0, 1.0));
                if mr_map.is_some() || (texture.is_some() && metal > 0.0 && self.f0.is_none()) {
                    warnings.push(format!(
                        "material '{}': the kd/f0 override turns its metallic-roughness parameters into kd, F0 and alpha; its textures now only tint kd",
                        m.name
                    ));
                }
                let (kd, f0) = metallic_kd_f0(*base_color, metal);
                m.model = MaterialModel::Direct {
                    kd,
                    kd_texture: *texture,
                    f0,
                    alpha: (r * r).max(ALPHA_MIN),
                };
            }
            MaterialModel::Direct { .. } => {}
        }
        if let MaterialModel::Direct { kd, f0, alpha, .. } = &mut m.model {
            *kd = self.kd.unwrap_or(*kd);
            *f0 = self.f0.unwrap_or(*f0);
            *alpha = self.alpha.map_or(*alpha, |a| a.max(ALPHA_MIN));
        }
        warnings
    }
}

/// Whether `name` matches `pattern`: `*` matches any run of characters (none included), every
/// other character matches itself; a pattern without `*` is an exact name.
pub fn glob_match(pattern: &str, name: &str) -> bool {
    let mut parts = pattern.split('*');
    let Some(mut rest) = name.strip_prefix(parts.next().unwrap_or("")) else {
        return false;
    };
    let parts: Vec<&str> = parts.collect();
    let Some((last, middle)) = parts.split_last() else {
        return rest.is_empty();
    };
    for part in middle {
        match rest.find(part) {
            Some(i) => rest = &rest[i + part.len()..],
            None => return false,
        }
    }
    rest.ends_with(last)
}

/// Validates each table of an array of tables; errors say which one (counted from 1).
fn numbered<R, T>(
    raw: Vec<R>,
    what: &str,
    validate: impl Fn(R) -> Result<T, String>,
) -> Result<Vec<T>, String> {
    raw.into_iter()
        .enumerate()
        .map(|(i, r)| validate(r).map_err(|m| format!("{what} #{}: {m}", i + 1)))
        .collect()
}

/// The file as written, before validation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSettings {
    scene: String,
    scene_source: Option<String>,
    replace_lights: Option<bool>,
    camera: Option<RawCamera>,
    #[serde(default)]
    lights: Vec<RawLight>,
    #[serde(default)]
    materials: Vec<RawMaterial>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCamera {
    position: [f32; 3],
    target: [f32; 3],
    up: Option<[f32; 3]>,
    yfov_deg: f32,
    znear: Option<f32>,
    zfar: Option<f32>,
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub(crate) enum RawLight {
    Point {
        position: [f32; 3],
        intensity: Rgb,
    },
    Spot {
        position: [f32; 3],
        direction: Option<[f32; 3]>,
        target: Option<[f32; 3]>,
        intensity: Rgb,
        inner_cone_deg: Option<f32>,
        outer_cone_deg: Option<f32>,
    },
    Directional {
        direction: [f32; 3],
        irradiance: Rgb,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    name: String,
    kd: Option<Rgb>,
    f0: Option<Rgb>,
    alpha: Option<f32>,
    roughness: Option<f32>,
    eta: Option<f32>,
    double_sided: Option<bool>,
    anisotropy_strength: Option<f32>,
    anisotropy_rotation: Option<f32>,
}

/// A colour: one number for grey or `[r, g, b]`.
#[derive(Clone, Copy, Deserialize)]
#[serde(
    untagged,
    expecting = "a number or an array of three numbers [r, g, b]"
)]
pub(crate) enum Rgb {
    Grey(f32),
    Rgb([f32; 3]),
}

impl Rgb {
    fn vec3(self) -> Vec3 {
        match self {
            Rgb::Grey(v) => Vec3::splat(v),
            Rgb::Rgb(v) => Vec3::from(v),
        }
    }

    /// The colour if every channel is finite and at least 0 (at most 1 with `unit`).
    fn checked(self, key: &str, unit: bool) -> Result<Vec3, String> {
        let v = self.vec3();
        let max = if unit { 1.0 } else { f32::MAX };
        if v.is_finite() && v.min_element() >= 0.0 && v.max_element() <= max {
            Ok(v)
        } else if unit {
            Err(format!("{key} {v} is outside [0, 1]"))
        } else {
            Err(format!("{key} {v} must be finite and at least 0"))
        }
    }
}

/// A finite point or vector.
fn finite(key: &str, v: [f32; 3]) -> Result<Vec3, String> {
    let v = Vec3::from(v);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("{key} {v} is not finite"))
    }
}

/// A finite, non-zero vector, normalized.
fn unit(key: &str, v: [f32; 3]) -> Result<Vec3, String> {
    finite(key, v)?
        .try_normalize()
        .ok_or_else(|| format!("{key} is the zero vector"))
}

/// A value in (0, 1].
fn in_unit_interval(key: &str, v: f32) -> Result<f32, String> {
    if v > 0.0 && v <= 1.0 {
        Ok(v)
    } else {
        Err(format!("{key} {v} is outside (0, 1]"))
    }
}

impl RawCamera {
    pub(crate) fn validate(self) -> Result<Camera, String> {
        let position = finite("position", self.position)?;
        let target = finite("target", self.target)?;
        let up = unit("up", self.up.unwrap_or([0.0, 1.0, 0.0]))?;
        if !(self.yfov_deg > 0.0 && self.yfov_deg < 180.0) {
            return Err(format!("yfov_deg {} is outside (0, 180)", self.yfov_deg));
        }
        let mut camera = Camera::look_at(position, target, up, self.yfov_deg.to_radians())
            .ok_or("target equals position, or up is parallel to the view direction")?;
        camera.znear = self.znear.unwrap_or(camera.znear);
        camera.zfar = self.zfar.unwrap_or(camera.zfar);
        if !(camera.znear > 0.0 && camera.znear < camera.zfar && camera.zfar.is_finite()) {
            return Err(format!(
                "znear {} and zfar {} must satisfy 0 < znear < zfar < infinity",
                camera.znear, camera.zfar
            ));
        }
        Ok(camera)
    }
}

impl RawLight {
    /// The light, refused where [`Light::problem`] finds a problem (e.g. an intensity whose
    /// products overflow f32).
    pub(crate) fn validate(self) -> Result<Light, String> {
        let light = self.build()?;
        match light.problem() {
            Some(problem) => Err(problem),
            None => Ok(light),
        }
    }

    fn build(self) -> Result<Light, String> {
        match self {
            RawLight::Point {
                position,
                intensity,
            } => Ok(Light::Point {
                position: finite("position", position)?,
                intensity: intensity.checked("intensity", false)?,
            }),
            RawLight::Spot {
                position,
                direction,
                target,
                intensity,
                inner_cone_deg,
                outer_cone_deg,
            } => {
                let position = finite("position", position)?;
                let direction = match (direction, target) {
                    (Some(d), None) => unit("direction", d)?,
                    (None, Some(t)) => (finite("target", t)? - position)
                        .try_normalize()
                        .ok_or("target equals position")?,
                    _ => return Err("give exactly one of direction and target".into()),
                };
                let outer = outer_cone_deg.unwrap_or(45.0);
                let inner = inner_cone_deg.unwrap_or(0.0);
                if !(outer > 0.0 && outer <= 90.0) {
                    return Err(format!("outer_cone_deg {outer} is outside (0, 90]"));
                }
                if !(inner >= 0.0 && inner <= outer) {
                    return Err(format!(
                        "inner_cone_deg {inner} is outside [0, outer_cone_deg = {outer}]"
                    ));
                }
                let radians = |deg: f32| deg.to_radians().min(std::f32::consts::FRAC_PI_2);
                Ok(Light::Spot {
                    position,
                    direction,
                    intensity: intensity.checked("intensity", false)?,
                    inner_cone_angle: radians(inner),
                    outer_cone_angle: radians(outer),
                })
            }
            RawLight::Directional {
                direction,
                irradiance,
            } => Ok(Light::Directional {
                direction: unit("direction", direction)?,
                irradiance: irradiance.checked("irradiance", false)?,
            }),
        }
    }
}

impl RawMaterial {
    fn validate(self) -> Result<MaterialOverride, String> {
        if self.name.is_empty() {
            return Err("name is empty".into());
        }
        let with_name = |m: String| format!("'{}': {m}", self.name);
        let alpha = match (self.alpha, self.roughness) {
            (Some(_), Some(_)) => {
                return Err(with_name("give alpha or roughness, not both".into()))
            }
            (Some(a), None) => Some(in_unit_interval("alpha", a).map_err(with_name)?),
            (None, Some(r)) => Some(in_unit_interval("roughness", r).map_err(with_name)?.powi(2)),
            (None, None) => None,
        };
        let kd = self.kd.map(|c| c.checked("kd", true)).transpose();
        let f0 = self.f0.map(|c| c.checked("f0", true)).transpose();
        let eta = self
            .eta
            .map(crate::material::check_eta)
            .transpose()
            .map_err(with_name)?;
        let anisotropy = match (self.anisotropy_strength, self.anisotropy_rotation) {
            (None, None) => None,
            (None, Some(_)) => {
                return Err(with_name(
                    "anisotropy_rotation needs anisotropy_strength".into(),
                ))
            }
            (Some(s), rotation) => {
                let strength = match s {
                    s if (0.0..=1.0).contains(&s) => s,
                    s => {
                        return Err(with_name(format!(
                            "anisotropy_strength {s} must lie in [0, 1]"
                        )))
                    }
                };
                let rotation = rotation.unwrap_or(0.0);
                if !rotation.is_finite() {
                    return Err(with_name(format!(
                        "anisotropy_rotation {rotation} must be finite"
                    )));
                }
                Some(MaterialAnisotropy { strength, rotation })
            }
        };
        let o = MaterialOverride {
            kd: kd.map_err(with_name)?,
            f0: f0.map_err(with_name)?,
            alpha,
            eta,
            double_sided: self.double_sided,
            anisotropy,
            pattern: self.name,
        };
        let sets_nothing = o.kd.is_none()
            && o.f0.is_none()
            && o.alpha.is_none()
            && o.eta.is_none()
            && o.double_sided.is_none()
            && o.anisotropy.is_none();
        if sets_nothing {
            return Err(format!(
                "'{}' sets nothing (give kd, f0, alpha or roughness, eta, double_sided or \
                 anisotropy_strength)",
                o.pattern
            ));
        }
        Ok(o)
    }
}

#[cfg(test)]
#[path = "settings_tests.rs"]
mod tests;
