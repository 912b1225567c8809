//! Agreement with an independent renderer: `shared/reference/cornell-a` holds direct and
//! one-bounce indirect images that Mitsuba 3 rendered with 32768 spp from the same glTF scene
//! (box pixel filter, point light in W/sr, one-sided diffuse + GGX surfaces). How "within
//! noise" is tested: `mitsuba/mod.rs`.
mod mitsuba;

use mitsuba::{assert_agrees, render_pair};
use slc_core::frame::Method;
use std::path::{Path, PathBuf};

fn reference_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/reference/cornell-a")
}

#[test]
fn path_reference_agrees_with_mitsuba() {
    let dir = reference_dir();
    let pairs = render_pair(&dir.join("cornell-a.gltf"), Method::Path, true, 256, 1, 16);
    assert_agrees("path", pairs, &dir, 1, 0.01);
}

#[test]
fn vpl_reference_with_visibility_agrees_with_mitsuba() {
    // 128 x 128 against the reference box-filtered 2 x 2: the same pixel filter at half the
    // resolution, so the VPL-to-pixel shadow rays stay affordable.
    let dir = reference_dir();
    let pairs = render_pair(
        &dir.join("cornell-a.gltf"),
        Method::VplReference,
        true,
        128,
        16,
        8,
    );
    assert_agrees("vpl", pairs, &dir, 2, 0.02);
}
