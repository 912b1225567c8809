//! glTF 2.0 loader (`.gltf` with external or embedded buffers, and binary `.glb`).
//!
//! The default scene (else the first; else every root node) is walked from its root nodes;
//! every node's world matrix is the product of its ancestors' local matrices.
//!
//! - **Meshes**: each primitive of mode `TRIANGLES` becomes one [`Mesh`](crate::Mesh) in world
//!   space: positions by the world matrix, normals (if present) by its inverse transpose,
//!   renormalized, winding flipped where the determinant is negative; `TEXCOORD_0` if present;
//!   indices, or `0..n` when absent. Other modes are skipped with a warning. Defective
//!   triangles are removed and counted in [`LoadReport::skipped`](crate::LoadReport).
//!   A mesh used by several nodes is instanced once per node.
//! - **Materials** become [`MaterialModel::MetallicRoughness`](crate::MaterialModel): base
//!   colour factor (RGB), metallic and roughness factors, base-colour texture (sRGB-decoded)
//!   and metallic-roughness texture (linear), both on `TEXCOORD_0`; `doubleSided`;
//!   `KHR_materials_ior` gives `eta` for non-metals (metallic factor 0, `ior` >= 1). A texture
//!   that cannot be read or decoded gives a warning and the factor alone is used; emission and
//!   alpha modes are ignored with a warning, as is a roughness whose square is below
//!   [`ALPHA_MIN`](crate::ALPHA_MIN) (clamped when used). Primitives without a material get
//!   the glTF default material (base colour 1, metallic 1, roughness 1).
//! - **Camera**: the first node (depth-first) with a perspective camera: position = the node's
//!   world translation, view direction = its world -z, up = its world +y, `yfov`, `znear`,
//!   `zfar` (absent: the camera's default far plane).
//! - **Lights** (`KHR_lights_punctual`), **read radiometrically, not photometrically**: a point
//!   or spot light's `intensity` times `color` is its radiant intensity in W/sr per RGB channel
//!   (NOT candela: no 683 lm/W, no 4π), a directional light's is irradiance in W/m² (NOT lux).
//!   Spots point along the node's world -z with the cone angles of the extension (defaults
//!   0 and π/4); directional lights travel along world -z. `range` is ignored (warning).
//!
//! The file is parsed leniently ([`crate::gltf_document`]): parts slc does not use may be
//! anything the specification allows; a required extension slc does not read is an
//! `unsupported: NAME` error. Accessors may be quantized, sparse or without a buffer view
//! (the `gltf_accessor` module). Malformed files (unreadable JSON, missing or short buffers,
//! accessors of the wrong type or outside their buffer) are errors naming the file;
//! unsupported features are warnings.
use crate::camera::Camera;
use crate::error::SceneError;
use crate::file_read::read_capped;
use crate::frame::memory::{available_memory, geometry_bytes};
use crate::gltf_document::{parse, Parsed};
use crate::gltf_material::{default_material, load_materials};
use crate::gltf_mesh::primitive_mesh;
use crate::import_util::add_mesh;
use crate::light::Light;
use crate::scene::Scene;
use glam::{Mat4, Vec3};
use gltf::khr_lights_punctual::Kind;
use std::path::Path;

/// Loads a `.gltf` or `.glb` file. The scene is named by the file's stem.
pub fn load_gltf(path: &Path) -> Result<Scene, SceneError> {
    let bytes = read_capped(path).map_err(|source| SceneError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let error = |message: String| SceneError::Gltf {
        path: path.to_path_buf(),
        message,
    };
    let mut warnings = Vec::new();
    let Parsed {
        document,
        blob,
        ignored_extensions,
    } = parse(bytes, &mut warnings).map_err(error)?;
    check_placed_size(&document).map_err(error)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = load_buffers(&document, base, blob).map_err(error)?;

    let mut scene = Scene {
        name: path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        ),
        ..Scene::default()
    };
    scene.report.warnings = warnings;
    load_materials(&document, &buffers, base, &mut scene);
    for e in ignored_extensions {
        if !scene.report.ignored.contains_key(&e) {
            scene.report.ignore(&e, "the file");
        }
    }
    let mut default_material_index = None;
    let mut visited = vec![false; document.nodes().len()];
    let mut stack: Vec<(gltf::Node, Mat4)> = root_nodes(&document)
        .into_iter()
        .rev()
        .map(|n| (n, Mat4::IDENTITY))
        .collect();
    while let Some((node, parent)) = stack.pop() {
        let name = node
            .name()
            .map_or_else(|| format!("node {}", node.index()), str::to_string);
        if std::mem::replace(&mut visited[node.index()], true) {
            scene.report.warnings.push(format!(
                "{name} is reached twice in the node hierarchy; its second use is skipped"
            ));
            continue;
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            let default = &mut default_material_index;
            read_mesh(&mesh, world, &buffers, default, &mut scene).map_err(error)?;
        }
        if let Some(camera) = node.camera() {
            read_camera(&document, camera.index(), world, &name, &mut scene);
        }
        if let Some(light) = node.light() {
            read_light(&light, world, &name, &mut scene);
        }
        stack.extend(
            node.children()
                .map(|c| (c, world))
                .collect::<Vec<_>>()
                .into_iter()
                .rev(),
        );
    }
    Ok(scene)
}

/// Adds the triangle primitives of `mesh` placed by `world`; primitives without a material
/// get the glTF default material, added once (its index kept in `default_index`).
fn read_mesh(
    mesh: &gltf::Mesh,
    world: Mat4,
    buffers: &[Vec<u8>],
    default_index: &mut Option<usize>,
    scene: &mut Scene,
) -> Result<(), String> {
    let mesh_name = mesh
        .name()
        .map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
    let single = mesh.primitives().len() == 1;
    for primitive in mesh.primitives() {
        let name = match single {
            true => mesh_name.clone(),
            false => format!("{mesh_name}#{}", primitive.index()),
        };
        if primitive.mode() != gltf::mesh::Mode::Triangles {
            scene.report.warnings.push(format!(
                "{name}: primitive mode {:?} is not supported (only triangles); skipped",
                primitive.mode()
            ));
            continue;
        }
        let material = match primitive.material().index() {
            Some(i) => i,
            None => *default_index.get_or_insert_with(|| {
                scene.materials.push(default_material());
                scene.materials.len() - 1
            }),
        };
        if primitive.get(&gltf::Semantic::Positions).is_none() {
            // The specification: such a primitive is not rendered.
            scene.report.warnings.push(format!(
                "{name}: a primitive with no POSITION attribute is skipped (nothing to render)"
            ));
            continue;
        }
        let warnings = &mut scene.report.warnings;
        let m = primitive_mesh(&primitive, buffers, world, name, material, warnings)?;
        add_mesh(scene, m);
    }
    Ok(())
}

/// Refuses, before any buffer is read, a file whose node hierarchy places more geometry than
/// this machine's memory holds: every placement of a mesh is a copy of its vertices and
/// triangles, and the BVH is built over all of them ([`geometry_bytes`]), so a small file
/// that instances a large mesh many times can ask for tens of GB.
fn check_placed_size(document: &gltf::Document) -> Result<(), String> {
    let (mut vertices, mut triangles, mut placements) = (0u64, 0u64, 0u64);
    let mut visited = vec![false; document.nodes().len()];
    let mut stack = root_nodes(document);
    while let Some(node) = stack.pop() {
        if std::mem::replace(&mut visited[node.index()], true) {
            continue;
        }
        if let Some(mesh) = node.mesh() {
            placements += 1;
            for p in mesh.primitives() {
                let count = |a: Option<gltf::Accessor>| a.map_or(0, |a| a.count() as u64);
                let v = count(p.get(&gltf::Semantic::Positions));
                vertices += v;
                triangles += p.indices().map_or(v, |i| i.count() as u64) / 3;
            }
        }
        stack.extend(node.children());
    }
    let need = geometry_bytes(vertices, triangles);
    match available_memory() {
        Some(available) if need > available => {
            let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
            Err(format!(
                "its {placements} mesh placement(s) make {triangles} triangles of {vertices} vertices, which need about {:.1} GiB (meshes and BVH), more than the {:.1} GiB of memory available",
                gib(need),
                gib(available)
            ))
        }
        _ => Ok(()),
    }
}

/// The nodes to walk: the default scene's, else the first scene's, else every node that is
/// no other node's child.
fn root_nodes(document: &gltf::Document) -> Vec<gltf::Node<'_>> {
    if let Some(s) = document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        return s.nodes().collect();
    }
    let mut is_child = vec![false; document.nodes().len()];
    document
        .nodes()
        .flat_map(|n| n.children())
        .for_each(|c| is_child[c.index()] = true);
    document.nodes().filter(|n| !is_child[n.index()]).collect()
}

/// Reads the buffers something reads ([`used_buffers`]): the GLB binary chunk, embedded
/// `data:` URIs, or files relative to `base`. The others are left empty, unread (a buffer
/// nothing uses cannot fail a file).
fn load_buffers(
    document: &gltf::Document,
    base: &Path,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, String> {
    let used = used_buffers(document);
    document
        .buffers()
        .map(|buffer| {
            if !used[buffer.index()] {
                return Ok(Vec::new());
            }
            let what = format!("buffer {}", buffer.index());
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => blob
                    .take()
                    .ok_or(format!("{what}: the GLB binary chunk is missing"))?,
                gltf::buffer::Source::Uri(uri) => {
                    read_uri(uri, base).map_err(|e| format!("{what}: {e}"))?
                }
            };
            if data.len() < buffer.length() {
                return Err(format!(
                    "{what}: {} bytes, but byteLength is {}",
                    data.len(),
                    buffer.length()
                ));
            }
            Ok(data)
        })
        .collect()
}

/// Which buffers are read: those of the buffer views that accessors of mesh primitives
/// (with their sparse parts and morph targets) and images use.
fn used_buffers(document: &gltf::Document) -> Vec<bool> {
    let accessors = crate::gltf_document::used_accessors(document.as_json());
    let mut views = vec![false; document.views().len()];
    for a in document.accessors().filter(|a| accessors[a.index()]) {
        let sparse = a
            .sparse()
            .into_iter()
            .flat_map(|s| [s.indices().view().index(), s.values().view().index()]);
        for v in a.view().map(|v| v.index()).into_iter().chain(sparse) {
            views[v] = true;
        }
    }
    // From the JSON: `Image::source` panics on a view without a MIME type.
    for view in document
        .as_json()
        .images
        .iter()
        .filter_map(|i| i.buffer_view)
    {
        if let Some(v) = views.get_mut(view.value()) {
            *v = true;
        }
    }
    let mut used = vec![false; document.buffers().len()];
    for v in document.views().filter(|v| views[v.index()]) {
        used[v.buffer().index()] = true;
    }
    used
}

/// The bytes a URI refers to: a relative (percent-encoded) path from `base`, or anything the
/// `gltf` crate resolves itself (`data:` base64, `file:`).
pub(crate) fn read_uri(uri: &str, base: &Path) -> Result<Vec<u8>, String> {
    if uri.contains(':') {
        return gltf::buffer::Data::from_source(gltf::buffer::Source::Uri(uri), Some(base))
            .map(|d| d.0)
            .map_err(|e| format!("cannot read '{}': {e}", short(uri)));
    }
    let relative =
        percent_decode(uri).ok_or_else(|| format!("'{uri}' is not a valid percent-encoded URI"))?;
    let file = base.join(relative);
    read_capped(&file).map_err(|e| format!("cannot read '{}': {e}", file.display()))
}

/// A URI cut to a readable length (embedded data URIs are long).
fn short(uri: &str) -> String {
    match uri.char_indices().nth(60) {
        Some((i, _)) => format!("{}...", &uri[..i]),
        None => uri.to_string(),
    }
}

/// Decodes `%XX` escapes; `None` for a broken escape or a result that is not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let mut bytes = Vec::with_capacity(s.len());
    let mut it = s.bytes();
    while let Some(b) = it.next() {
        if b == b'%' {
            let hex = [it.next()?, it.next()?];
            bytes.push(u8::from_str_radix(std::str::from_utf8(&hex).ok()?, 16).ok()?);
        } else {
            bytes.push(b);
        }
    }
    String::from_utf8(bytes).ok()
}

/// Sets the scene's camera from the first perspective camera; warns about the others.
/// Reads the camera's JSON: the `gltf` crate's `projection()` panics on a camera whose `type`
/// names a projection it does not describe.
fn read_camera(
    document: &gltf::Document,
    index: usize,
    world: Mat4,
    node: &str,
    scene: &mut Scene,
) {
    use gltf::json::{camera::Type, validation::Checked};
    let json = document.as_json().cameras.get(index);
    let perspective = json.and_then(|c| match c.type_ {
        Checked::Valid(Type::Perspective) => c.perspective.as_ref(),
        _ => None,
    });
    let Some(p) = perspective else {
        let warning = format!("{node}: only perspective cameras are supported; ignored");
        scene.report.warnings.push(warning);
        return;
    };
    if scene.camera.is_some() {
        let warning = format!("{node}: only the first camera is used; ignored");
        scene.report.warnings.push(warning);
        return;
    }
    let eye = world.transform_point3(Vec3::ZERO);
    let forward = world.transform_vector3(Vec3::NEG_Z);
    let up = world.transform_vector3(Vec3::Y);
    let zfar = p.zfar.unwrap_or(f32::INFINITY);
    match Camera::from_basis(eye, forward, up, p.yfov) {
        Some(cam) if eye.is_finite() && p.znear > 0.0 && zfar > p.znear => {
            let zfar = if zfar.is_finite() { zfar } else { cam.zfar };
            scene.camera = Some(Camera {
                znear: p.znear,
                zfar,
                ..cam
            });
        }
        _ => scene.report.warnings.push(format!(
            "{node}: degenerate camera (transform, yfov {}, znear {} or zfar {zfar}); ignored",
            p.yfov, p.znear
        )),
    }
}

/// Adds a `KHR_lights_punctual` light placed by the node's world matrix.
fn read_light(
    light: &gltf::khr_lights_punctual::Light,
    world: Mat4,
    node: &str,
    scene: &mut Scene,
) {
    if light.range().is_some() {
        scene
            .report
            .warnings
            .push(format!("{node}: light range is ignored (no cut-off)"));
    }
    let power = Vec3::from(light.color()) * light.intensity();
    let position = world.transform_point3(Vec3::ZERO);
    let direction = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
    let converted = match light.kind() {
        Kind::Point => Light::Point {
            position,
            intensity: power,
        },
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => Light::Spot {
            position,
            direction,
            intensity: power,
            inner_cone_angle,
            outer_cone_angle,
        },
        Kind::Directional => Light::Directional {
            direction,
            irradiance: power,
        },
    };
    match converted.problem() {
        None => scene.lights.push(converted),
        Some(problem) => scene.report.warnings.push(format!(
            "{node}: {} light ignored: {problem}",
            converted.kind()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_decoding() {
        assert_eq!(percent_decode("a%20b.bin").as_deref(), Some("a b.bin"));
        assert_eq!(percent_decode("plain.bin").as_deref(), Some("plain.bin"));
        assert_eq!(percent_decode("bad%2"), None);
        assert_eq!(percent_decode("bad%zz"), None);
        assert_eq!(percent_decode("%FF"), None);
    }

    #[test]
    fn uris() {
        let base = Path::new("/nonexistent");
        assert_eq!(
            read_uri("data:application/octet-stream;base64,AQID", base).unwrap()[..3],
            [1, 2, 3]
        );
        assert!(read_uri("missing.bin", base)
            .unwrap_err()
            .contains("/nonexistent/missing.bin"));
        assert!(read_uri("https://example.com/x.bin", base).is_err());
    }
}
