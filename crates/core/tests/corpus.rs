//! The loader corpus (`tests/corpus/`, written by `make_corpus.py`): spec-valid edge cases
//! load, damaged files are refused or loaded with what was dropped said, required extensions
//! slc cannot read are named. Each file's expected outcome is in [`CASES`].
use slc_core::{load_scene, Scene};
use std::path::PathBuf;

enum Outcome {
    /// Loads with this many triangles and a warning containing the text (if any).
    Loads(usize, Option<&'static str>),
    /// Refused with an error containing the text.
    Fails(&'static str),
}
use Outcome::*;

const CASES: &[(&str, Outcome)] = &[
    ("valid-accessor-without-buffer-view.gltf", Loads(2, None)),
    ("valid-sparse-positions.gltf", Loads(2, None)),
    ("valid-webp-only-texture.glb", Loads(2, None)),
    (
        "valid-ktx2-only-texture-optional.gltf",
        Loads(2, Some("cannot be used")),
    ),
    (
        "valid-texture-without-image.gltf",
        Loads(2, Some("has no image slc can find")),
    ),
    (
        "valid-animation-channel-without-node.gltf",
        Loads(2, Some("1 animation(s) ignored")),
    ),
    (
        "valid-glb-trailing-bytes.glb",
        Loads(2, Some("trailing GLB byte")),
    ),
    ("valid-mesh-quantization.gltf", Loads(2, None)),
    (
        "valid-optional-unknown-extension.gltf",
        Loads(2, Some("ignored: KHR_materials_clearcoat")),
    ),
    (
        "unsupported-required-KHR_draco_mesh_compression.gltf",
        Fails("unsupported: KHR_draco_mesh_compression"),
    ),
    (
        "unsupported-required-EXT_meshopt_compression.gltf",
        Fails("unsupported: EXT_meshopt_compression"),
    ),
    (
        "unsupported-required-KHR_texture_basisu.gltf",
        Fails("unsupported: KHR_texture_basisu"),
    ),
    (
        "damaged-one-index-past-end.gltf",
        Loads(19, Some("1 with an index past the end")),
    ),
    (
        "damaged-non-finite-positions.gltf",
        Fails("3 of 20 triangles have non-finite vertices"),
    ),
    (
        "damaged-glb-truncated.glb",
        Fails("total length 4096 bytes, but the file has 32"),
    ),
    (
        "damaged-glb-length-below-header.glb",
        Fails("below the header's 12 bytes"),
    ),
    (
        "damaged-obj-non-finite-vertices.obj",
        Fails("2 of 3 triangles have non-finite vertices"),
    ),
    (
        "damaged-obj-normal-index.obj",
        Loads(1, Some("normal past the end")),
    ),
    (
        "damaged-obj-texcoord-index.obj",
        Loads(1, Some("texture coordinate or normal past the end")),
    ),
    (
        "valid-obj-one-zero-area-triangle.obj",
        Loads(2, Some("1 of zero area")),
    ),
    (
        "valid-obj-usemtl-undefined.obj",
        Loads(1, Some("in no material library (light)")),
    ),
    ("valid-unused-buffer-without-uri.gltf", Loads(2, None)),
    ("valid-glb-data-uri-buffer.glb", Loads(2, None)),
    ("valid-integers-written-as-floats.gltf", Loads(2, None)),
    ("valid-scene-without-nodes.gltf", Loads(2, None)),
    (
        "valid-primitive-without-position.gltf",
        Loads(2, Some("no POSITION")),
    ),
    ("valid-unused-accessor-of-unknown-type.gltf", Loads(2, None)),
    (
        "valid-spot-outer-cone-0.gltf",
        Loads(2, Some("a cone of 0 emits nothing")),
    ),
    (
        "unsupported-asset-version-3.0.gltf",
        Fails("asset.version 3.0"),
    ),
    (
        "unsupported-min-version-2.5.gltf",
        Fails("asset.minVersion 2.5"),
    ),
];

fn corpus(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(name)
}

fn load(name: &str) -> Result<Scene, String> {
    load_scene(corpus(name).to_str().unwrap()).map_err(|e| e.to_string())
}

#[test]
fn every_corpus_file_has_its_expected_outcome() {
    let files = std::fs::read_dir(corpus(""))
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|f| !f.ends_with(".py"))
        .count();
    assert_eq!(files, CASES.len(), "every corpus file has a case");
    let mut wrong = Vec::new();
    for (name, expected) in CASES {
        match (load(name), expected) {
            (Ok(s), Loads(n, warning)) => {
                let warned =
                    warning.is_none_or(|w| s.report.warnings.iter().any(|x| x.contains(w)));
                if s.triangle_count() != *n || !warned {
                    wrong.push(format!(
                        "{name}: {} triangles, warnings {:?}",
                        s.triangle_count(),
                        s.report.warnings
                    ));
                }
            }
            (Err(e), Fails(text)) if e.contains(text) && e.contains(name) => {}
            (Ok(s), Fails(_)) => {
                wrong.push(format!("{name}: loaded {} triangles", s.triangle_count()))
            }
            (Err(e), _) => wrong.push(format!("{name}: {e}")),
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

fn positions(s: &Scene) -> Vec<glam::Vec3> {
    s.meshes.iter().flat_map(|m| m.positions.clone()).collect()
}

#[test]
fn quantized_and_sparse_positions_are_decoded() {
    // Normalized i16 (0..32767 -> 0..1) under a node scale of 2.
    let q = load("valid-mesh-quantization.gltf").unwrap();
    let max = positions(&q)
        .into_iter()
        .fold(glam::Vec3::ZERO, glam::Vec3::max);
    assert!(
        (max - glam::Vec3::new(2.0, 0.0, 2.0)).abs().max_element() < 1e-6,
        "{max}"
    );
    let uvs = q.meshes[0].uvs.as_ref().unwrap();
    assert!(uvs.iter().any(|uv| (uv.x - 1.0).abs() < 1e-6));
    // Sparse: zeros with vertices 4..8 replaced by a unit quad.
    let s = load("valid-sparse-positions.gltf").unwrap();
    let p = positions(&s);
    assert_eq!(
        p[4..8],
        [
            glam::Vec3::ZERO,
            glam::Vec3::X,
            glam::Vec3::new(1.0, 0.0, 1.0),
            glam::Vec3::Z
        ]
    );
    // No buffer view: zero texture coordinates.
    let z = load("valid-accessor-without-buffer-view.gltf").unwrap();
    assert!(z.meshes[0]
        .uvs
        .as_ref()
        .unwrap()
        .iter()
        .all(|uv| *uv == glam::Vec2::ZERO));
}

#[test]
fn a_webp_only_texture_is_decoded() {
    let s = load("valid-webp-only-texture.glb").unwrap();
    assert_eq!(s.textures.len(), 1, "{:?}", s.report.warnings);
    assert!(s.report.warnings.is_empty(), "{:?}", s.report.warnings);
}
