//! The part of a G-buffer that culling reads, packed: each pixel's position in 16 bytes
//! instead of its whole sample (with its normals and BRDF). The tile passes read samples with
//! the subregion's stride K, a new cache line (and often a new page) per pixel; reading the
//! G-buffer once in order into this array and the tiles from it costs less than reading the
//! samples themselves in tile order.
use glam::Vec3;
use rayon::prelude::*;
use slc_core::GBuffer;

/// Per pixel of `gbuffer` (row-major): its sample's position, `None` where it has no sample;
/// written into `out`'s memory, its old entries dropped.
pub(crate) fn positions(gbuffer: &GBuffer, out: &mut Vec<Option<Vec3>>) {
    gbuffer
        .samples
        .par_iter()
        .map(|g| g.as_ref().map(|g| g.position))
        .collect_into_vec(out);
}
