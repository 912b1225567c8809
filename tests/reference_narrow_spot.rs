//! Agreement with an independent renderer on a spot light of 1° with a hard edge:
//! `scenes/narrow-spot/reference` holds the direct image Mitsuba 3 rendered with 8192 spp
//! from `scenes/narrow-spot/narrow-spot.gltf` (a grey floor seen from above, the lit disk
//! half the image; Mitsuba's `spot` with cutoff angle = beam width is the glTF spot whose inner
//! and outer cone angles are equal). The cone's angle, its edge and the light inside it must
//! agree within noise; the falloff that clamped `cos θi − cos θo` at 1e-3 left 1/3,300 of the
//! light inside this cone. How "within noise" is tested: `mitsuba/mod.rs`.
mod mitsuba;

use mitsuba::{assert_images_agree, render_pair};
use slc_core::frame::Method;
use std::path::Path;

#[test]
fn a_narrow_spots_direct_light_agrees_with_mitsuba() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/narrow-spot");
    // 64 jittered passes: the box pixel filter over the disk's edge, as Mitsuba's.
    let [(a, b), _] = render_pair(
        &dir.join("narrow-spot.gltf"),
        Method::VplReference,
        true,
        64,
        4,
        64,
    );
    assert_images_agree(
        "narrow spot",
        &[("direct", &a, &b)],
        &dir.join("reference"),
        1,
        0.01,
    );
}
