//! Wavefront OBJ + MTL loader (via `tobj`, faces triangulated as fans, one index per vertex).
//!
//! Geometry: every OBJ object/group becomes one [`Mesh`]; `vn` normals and `vt` texture
//! coordinates are used when every vertex of the mesh has them. OBJ texture coordinates have
//! v pointing up from the image's bottom; they are stored as `(u, 1 - v)` so that, as in glTF,
//! (0, 0) is the image's top-left texel. Points and lines are ignored; defective triangles are
//! removed and counted. OBJ has no lights and no camera: `lights` stays empty, `camera` `None`.
//!
//! MTL mapping to the diffuse + GGX model ([`MaterialModel::Direct`]):
//! - `kd = Kd` (each channel clamped to [0, 1]), times the `map_Kd` texture when present
//!   (sRGB-decoded; path relative to the MTL file; texture options such as `-bm` are skipped).
//!   Without `Kd`: 1 when `map_Kd` is given, else 0.5. An unreadable texture gives a warning
//!   and `Kd` alone is used.
//! - `F0 = Ks` clamped to [0, 1]; no `Ks` or `Ks 0 0 0` makes the material purely diffuse.
//! - `alpha = sqrt(2 / (Ns + 2))`, the usual match of a Phong lobe of exponent `Ns` to a
//!   microfacet lobe (`Ns` below 0 or absent: 0, so alpha = 1), clamped to the range from
//!   [`ALPHA_MIN`] to 1 with a warning when clamped.
//! - Emission (`Ke`): OBJ emitters are not lights in this project (lights come from the scene
//!   settings); it is listed as ignored and the material is its reflectance. So are bump
//!   maps (`map_Bump`, `bump`: height maps, not glTF normal maps) and a plain dissolve
//!   `d` < 1 (transparency; drawn opaque).
//! - `map_d` makes a cut-out: the surface exists where `d` (default 1) times the map's
//!   coverage (its alpha channel, else its grey level) is at least 0.5.
//! - Every OBJ material is `double_sided`: OBJ has no facing convention, so the side a face
//!   is seen from decides.
//! - Meshes without a material (no `usemtl`, an unknown name, or an unreadable MTL file, which
//!   gives a warning) get a grey diffuse default material (kd 0.5).
use crate::error::SceneError;
use crate::file_read::{capped_at_end, open_capped, read_capped};
use crate::import_util::{add_mesh, small_alpha_warning};
use crate::material::{AlphaMask, Material, MaterialModel, ALPHA_MIN};
use crate::mesh::Mesh;
use crate::obj_stream::ObjLines;
use crate::scene::Scene;
use crate::texture::TextureId;
use crate::texture_decode::{read_texture, Encoding};
use glam::{Vec2, Vec3};
use std::cell::RefCell;
use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

/// A material library named by the OBJ file: its folder and how many materials it gave.
struct MtlLib {
    dir: PathBuf,
    count: usize,
}

/// Loads an `.obj` file and the `.mtl` files it names. The scene is named by the file's stem.
pub fn load_obj(path: &Path) -> Result<Scene, SceneError> {
    let io = |source| SceneError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::io::BufReader::new(open_capped(path).map_err(io)?);
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let libs = RefCell::new(Vec::<MtlLib>::new());
    let warnings = RefCell::new(Vec::<String>::new());
    let load_mtl = |mtl: &Path| {
        let mtl_path = dir.join(mtl);
        let parsed = read_mtl(&mtl_path).map_err(|e| e.to_string());
        match parsed.and_then(|r| r.map_err(|e| e.to_string())) {
            Ok((materials, names)) => {
                let lib_dir = mtl_path.parent().unwrap_or(Path::new("")).to_path_buf();
                let count = materials.len();
                libs.borrow_mut().push(MtlLib {
                    dir: lib_dir,
                    count,
                });
                Ok((materials, names))
            }
            Err(e) => {
                warnings.borrow_mut().push(format!(
                    "{}: material library unusable ({e}); its materials are replaced by a grey diffuse one",
                    mtl_path.display()
                ));
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    // GPU_LOAD_OPTIONS: triangulate, single index, ignore points and lines.
    let options = &tobj::GPU_LOAD_OPTIONS;
    let mut lines = ObjLines::new(&mut file);
    let (models, materials) =
        tobj::load_obj_buf(&mut lines, options, load_mtl).map_err(|e| SceneError::Obj {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    let (dropped, used_materials) = (lines.dropped, lines.materials);
    capped_at_end(file.get_ref()).map_err(io)?;
    if dropped > 0 {
        warnings.borrow_mut().push(format!(
            "{dropped} face corner(s) name a texture coordinate or normal past the end; those references are dropped"
        ));
    }

    let mut scene = Scene {
        name: path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        ),
        ..Scene::default()
    };
    scene.report.warnings = warnings.into_inner();
    let libs = libs.into_inner();
    let lib_dirs = libs
        .iter()
        .flat_map(|l| std::iter::repeat_n(l.dir.as_path(), l.count));
    let mut textures = HashMap::new();
    for (m, lib_dir) in materials.unwrap_or_default().iter().zip(lib_dirs) {
        let material = convert_material(m, lib_dir, &mut textures, &mut scene);
        scene.materials.push(material);
    }
    let material_count = scene.materials.len();
    if let Some(w) = undefined_materials(&used_materials, &scene.materials) {
        scene.report.warnings.push(w);
    }
    let mut default_material = None;
    for model in models {
        let material = match model.mesh.material_id.filter(|&i| i < material_count) {
            Some(i) => i,
            None => *default_material.get_or_insert_with(|| {
                scene.materials.push(Material {
                    double_sided: true,
                    ..Material::direct("default grey", Vec3::splat(0.5), Vec3::ZERO, 1.0)
                });
                scene.materials.len() - 1
            }),
        };
        let mesh = convert_mesh(model, material);
        add_mesh(&mut scene, mesh);
    }
    Ok(scene)
}

/// The warning for `usemtl` names no material library defined (their faces get the grey
/// default), if any.
fn undefined_materials(used: &BTreeSet<String>, defined: &[Material]) -> Option<String> {
    let missing: Vec<&str> = used
        .iter()
        .map(String::as_str)
        .filter(|name| !defined.iter().any(|m| m.name == *name))
        .collect();
    (!missing.is_empty()).then(|| {
        format!(
            "{} material(s) named by usemtl are in no material library ({}): their faces get the grey diffuse default (kd 0.5), which a settings file can set as [[materials]] name = \"default grey\"",
            missing.len(),
            missing.join(", ")
        )
    })
}

/// Parses an MTL file (read leniently: invalid UTF-8 is replaced) after [`pad_colours`].
fn read_mtl(path: &Path) -> std::io::Result<tobj::MTLLoadResult> {
    let text = pad_colours(&String::from_utf8_lossy(&read_capped(path)?));
    Ok(tobj::load_mtl_buf(&mut text.as_bytes()))
}

/// Completes colour statements (`Ka`, `Kd`, `Ks`, `Ke`) given with fewer than three values:
/// missing channels repeat the last value given, as MTL allows (`Kd 0.5` means
/// `Kd 0.5 0.5 0.5`); empty ones are dropped. `tobj` panics on both.
fn pad_colours(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let code = line.split('#').next().unwrap_or("");
        let mut words = code.split_whitespace();
        match (words.next(), words.collect::<Vec<_>>().as_slice()) {
            (Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")), values) if values.len() < 3 => {
                if let Some(last) = values.last() {
                    let padded: Vec<&str> = values
                        .iter()
                        .chain(std::iter::repeat(last))
                        .take(3)
                        .copied()
                        .collect();
                    out.push_str(&format!("{key} {}", padded.join(" ")));
                }
            }
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// A tobj model as a mesh (positions, optional normals and flipped-v texture coordinates).
fn convert_mesh(model: tobj::Model, material: usize) -> Mesh {
    let m = model.mesh;
    let vec3s = |v: &[f32]| {
        v.chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect::<Vec<_>>()
    };
    Mesh {
        name: model.name,
        positions: vec3s(&m.positions),
        normals: (!m.normals.is_empty()).then(|| vec3s(&m.normals)),
        uvs: (!m.texcoords.is_empty()).then(|| {
            m.texcoords
                .chunks_exact(2)
                .map(|c| Vec2::new(c[0], 1.0 - c[1]))
                .collect()
        }),
        tangents: None,
        triangles: m
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        material,
    }
}

/// An MTL material mapped as the module documentation states.
fn convert_material(
    m: &tobj::Material,
    lib_dir: &Path,
    textures: &mut HashMap<(PathBuf, Encoding), Option<TextureId>>,
    scene: &mut Scene,
) -> Material {
    let kd_texture = m
        .diffuse_texture
        .as_deref()
        .and_then(|t| texture(&m.name, t, Encoding::Srgb, lib_dir, textures, scene));
    let kd_default = if m.diffuse_texture.is_some() {
        1.0
    } else {
        0.5
    };
    let kd = m.diffuse.map_or(Vec3::splat(kd_default), unit_rgb);
    let f0 = m.specular.map_or(Vec3::ZERO, unit_rgb);
    let ns = m.shininess.unwrap_or(0.0).max(0.0);
    let alpha = (2.0 / (ns + 2.0)).sqrt();
    if f0.max_element() > 0.0 {
        scene
            .report
            .warnings
            .extend(small_alpha_warning(&m.name, alpha));
    }
    if m.emissive.is_some_and(|ke| ke.iter().any(|&x| x > 0.0)) {
        scene.report.ignore("emission", &m.name);
    }
    if m.normal_texture.is_some() {
        scene.report.ignore("bump map (map_Bump)", &m.name);
    }
    let dissolve = m
        .dissolve
        .filter(|d| d.is_finite())
        .map(|d| d.clamp(0.0, 1.0));
    let alpha_mask = match &m.dissolve_texture {
        Some(t) => Some(AlphaMask {
            cutoff: 0.5,
            factor: dissolve.unwrap_or(1.0),
            texture: texture(&m.name, t, Encoding::Coverage, lib_dir, textures, scene),
        }),
        None => {
            if dissolve.is_some_and(|d| d < 1.0) {
                scene
                    .report
                    .ignore("transparency d < 1 (drawn opaque)", &m.name);
            }
            None
        }
    };
    Material {
        name: m.name.clone(),
        model: MaterialModel::Direct {
            kd,
            kd_texture,
            f0,
            alpha: alpha.clamp(ALPHA_MIN, 1.0),
        },
        eta: None,
        double_sided: true,
        normal_map: None,
        alpha_mask,
        anisotropy: None,
    }
}

/// An MTL colour with each channel clamped to [0, 1] (non-finite channels: 0).
fn unit_rgb(c: [f32; 3]) -> Vec3 {
    Vec3::from(c.map(|x| {
        if x.is_finite() {
            x.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }))
}

/// The texture of a `map_Kd` or `map_d` statement (decoded once per file and encoding), or
/// `None` with a warning.
fn texture(
    material: &str,
    statement: &str,
    encoding: Encoding,
    lib_dir: &Path,
    textures: &mut HashMap<(PathBuf, Encoding), Option<TextureId>>,
    scene: &mut Scene,
) -> Option<TextureId> {
    // Options come before the file name: keep the last word when the statement has options.
    let file = if statement.starts_with('-') {
        statement.split_whitespace().last().unwrap_or("")
    } else {
        statement
    };
    let path = lib_dir.join(file.replace('\\', "/"));
    if let Some(&id) = textures.get(&(path.clone(), encoding)) {
        return id;
    }
    let id = match read_texture(&path, encoding) {
        Ok(t) => {
            scene.textures.push(t);
            Some(scene.textures.len() - 1)
        }
        Err(e) => {
            scene.report.warnings.push(format!(
                "material '{material}': texture {} cannot be used ({e}); the factor alone is used",
                path.display()
            ));
            None
        }
    };
    textures.insert((path, encoding), id);
    id
}
