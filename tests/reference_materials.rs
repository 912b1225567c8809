//! Agreement with an independent renderer on what real assets carry: `scenes/materials/
//! reference` holds direct and one-bounce indirect images that Mitsuba 3 rendered with 32768
//! spp from `scenes/materials/materials.gltf` (its README gives every convention): a glossy
//! floor with a tangent-space normal map and no stored tangents (Mitsuba's `normalmap`, with
//! the glTF frame T = dp/du, B = N × T towards the image's up), a double-sided sheet cut out
//! by an alpha mask (`mask` around `twosided`, volpath so that shadow rays pass the holes).
//! A wrong tangent frame (a flipped bitangent changes the floor's normals by up to 0.76), an
//! ignored mask or an ignored `doubleSided` fails these tests. How "within noise" is tested:
//! `mitsuba/mod.rs`.
mod mitsuba;

use mitsuba::{assert_agrees, render_pair};
use slc_core::frame::Method;
use std::path::{Path, PathBuf};

fn scene_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/materials")
}

#[test]
fn path_reference_agrees_with_mitsuba() {
    let dir = scene_dir();
    let pairs = render_pair(&dir.join("materials.gltf"), Method::Path, true, 128, 1, 64);
    assert_agrees("path", pairs, &dir.join("reference"), 1, 0.01);
}

#[test]
fn vpl_reference_with_visibility_agrees_with_mitsuba() {
    let dir = scene_dir();
    let pairs = render_pair(
        &dir.join("materials.gltf"),
        Method::VplReference,
        true,
        128,
        24,
        8,
    );
    assert_agrees("vpl", pairs, &dir.join("reference"), 1, 0.02);
}
