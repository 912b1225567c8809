//! The sample points of filtered importance sampling (VSGL section 4.2), the same on every
//! backend: a frame's lights and its camera-side VSGLs each warp their own stratified set.
use crate::rng::{stream, uniform};

/// The largest `f64` below 1: a warped coordinate never reaches 1.
pub const ONE_BELOW: f64 = 1.0 - f64::EPSILON / 2.0;

/// Which independent set of sample points of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleSet {
    /// The lights: VSGLs or importance-sampled VPLs.
    Lights = 0,
    /// The camera-side VSGLs that estimate the bidirectional importance (VSGL section 4.3).
    Camera = 1,
}

/// `count` points of the unit square: the 2-D Hammersley set `((k + ½)/N, φ2(k))` shifted
/// modulo 1 by a random offset drawn from `(seed, set)` (Cranley-Patterson rotation). Each point
/// is uniform on the square, so estimates from them are unbiased, and the set is stratified,
/// which the hierarchical warp preserves.
pub fn sample_points(count: u32, seed: u32, set: SampleSet) -> Vec<[f64; 2]> {
    let shift = point_shift(seed, set).map(f64::from);
    let n = f64::from(count.max(1));
    (0..count)
        .map(|k| {
            let radical_inverse = f64::from(k.reverse_bits()) / 4_294_967_296.0;
            [
                fract((f64::from(k) + 0.5) / n + shift[0]),
                fract(radical_inverse + shift[1]),
            ]
        })
        .collect()
}

/// The random offset of [`sample_points`] (the Cranley-Patterson rotation) for `(seed, set)`.
pub fn point_shift(seed: u32, set: SampleSet) -> [f32; 2] {
    [0, 1].map(|c| uniform(seed, set as u32, stream::VSGL_POINTS, c))
}

/// `x − ⌊x⌋`, at most [`ONE_BELOW`].
fn fract(x: f64) -> f64 {
    (x - x.floor()).min(ONE_BELOW)
}
