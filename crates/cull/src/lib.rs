//! # slc-cull
//!
//! CPU light culling for stochastic light culling of virtual point lights (Tokuyoshi and
//! Harada, "Stochastic Light Culling for VPLs on GGX Microsurfaces"; equation and section
//! numbers refer to that paper). Each VPL can only contribute within its random range
//! (eq. 5), which slc-bounds encloses in a sphere (diffuse VPLs, section 6; glossy baselines,
//! section 7) or a GGX spheroid (eq. 12-15). A culler turns a G-buffer, a camera and the VPLs
//! into per-pixel light lists ([`slc_core::LightLists`]) that never leave out a VPL whose
//! probability p(ωo, l) > ξ at the pixel, so shading stays unbiased.
//!
//! Strategies ([`slc_core::Strategy`], [`culler`]):
//! - `none` ([`NoCulling`]): every VPL of the pixel's interleaved subregion (section 6).
//! - `sphere`, `enclosing-sphere`, `ellipsoid` ([`BoundedCuller`]): tiled culling with
//!   Modified HalfZ (section 5.1), 16x16 tiles of each subregion image, two depth clusters
//!   per tile; glossy VPLs bounded by the r/α sphere, the sphere around the spheroid, or the
//!   spheroid itself tested in its stretched and rotated space (eq. 16-17, section 5.2).
//! - `clustered`, `clustered-sphere`, `clustered-enclosing-sphere` ([`BoundedCuller`]): the
//!   same tiles cut into 32 exponential depth slices.
//! - `tight`, `clustered-tight` ([`BoundedCuller`]): the `ellipsoid` and `clustered` lists
//!   cut once more per 8×8 block of each tile, keeping a VPL only where a bound of p(ωo, l)
//!   over the box of the block's receivers ([`slc_bounds::BoxBound`]: D, Fresnel, G1 and the
//!   VPL's tangent plane over the cone of directions to them) may exceed its ξ: far fewer
//!   false positives than the paper's bounds, still none missed (`docs/tight-bounds.md`).
//! - `splatting`, `clustered-raster` ([`GpuOnly`]): the GPU's rasterization baselines; the
//!   CPU culler refuses them with an error.
//! - `binned` ([`BinnedCuller`]): each VPL's bound mapped once to the rectangle of pixels it
//!   may cover and tested at each pixel of it (a list per pixel), or, for rectangles larger
//!   than a tile, at each 4×4 cell of it (a list per cell, shared by its pixels): a cost
//!   that follows the pixels the bounds cover, not VPLs × tiles (docs/many-vpls.md).
//!
//! The crate needs no scene loader, BVH or GPU: it builds on `slc-core` without its
//! `loaders` feature, so an engine can embed it with its own G-buffer and VPLs
//! (`examples/embed.rs`).
//!
//! [`metrics`] measures light lists against the brute-force truth (true and false positives,
//! misses, lights per pixel, false discovery rate). Everything runs in parallel with rayon
//! and in f64 where geometry is compared, with the small documented slack of
//! `vpl_bounds::BOUND_SLACK` and `frusta::FRUSTUM_SLACK`, so float rounding never culls a
//! contributing VPL.
//!
//! ```
//! use glam::Vec3;
//! use slc_bounds::{Brdf, Fresnel};
//! use slc_core::{Camera, CullInput, Culler, GBuffer, GSample, Interleaving, Strategy, Vpl, VplLobe};
//!
//! // A camera 4 units above a floor (y = 0) looking straight down; a 32x32 G-buffer of the
//! // floor from each pixel's centre ray.
//! let camera = Camera::look_at(Vec3::new(0.0, 4.0, 0.0), Vec3::ZERO, Vec3::Z, 1.0).unwrap();
//! let brdf = Brdf { kd: Vec3::splat(0.5), fresnel: Fresnel::Schlick(Vec3::splat(0.04)), alpha: 0.3, anisotropy: None };
//! let (w, h) = (32, 32);
//! let samples = (0..w * h)
//!     .map(|p| {
//!         let dir = camera.ray_direction(p % w, p / w, 0.5, 0.5, w, h);
//!         let position = camera.position + dir * (camera.position.y / -dir.y);
//!         let depth = camera.view_depth(position);
//!         Some(GSample { position, normal: Vec3::Y, geometric_normal: Vec3::Y, omega_o: -dir, depth, brdf })
//!     })
//!     .collect();
//! let gbuffer = GBuffer { width: w, height: h, samples };
//!
//! // A diffuse VPL half a unit above the floor's centre, facing down, and one above the
//! // camera facing up.
//! let lamp = Vpl {
//!     position: Vec3::new(0.0, 0.5, 0.0), normal: Vec3::NEG_Y, geometric_normal: Vec3::NEG_Y,
//!     omega_i: Vec3::NEG_Y, flux: Vec3::ONE, brdf, lobe: VplLobe::Diffuse, id: 0, xi: 0.5,
//! };
//! let above = Vpl {
//!     position: Vec3::new(0.0, 10.0, 0.0), normal: Vec3::Y, geometric_normal: Vec3::Y,
//!     omega_i: Vec3::Y, id: 2, ..lamp
//! };
//! let vpls = [lamp, above];
//! let input = CullInput {
//!     gbuffer: &gbuffer, camera: &camera, vpls: &vpls, delta: 1e-3,
//!     interleaving: Interleaving { k: 1, seed: 0 },
//! };
//! let lists = slc_cull::culler(Strategy::Ellipsoid).cull(&input)?;
//! let centre = (h / 2 * w + w / 2) as usize;
//! assert_eq!(*lists.for_pixel(centre), [0]);
//! assert!(lists.indices.iter().all(|&i| i == 0), "the VPL above the camera is culled");
//!
//! let m = slc_cull::metrics::measure(&input, &lists)?;
//! assert_eq!(m.missed_pairs, 0);
//! assert!(m.true_positive_pairs > 0);
//! # Ok::<(), slc_core::CullError>(())
//! ```
mod acceptance;
mod binned;
mod bound_lanes;
mod cells;
mod depth;
mod footprint;
mod frusta;
pub mod ggx_lanes;
mod lists;
pub mod metrics;
mod pair_lists;
mod par;
mod partition;
mod pixel_rows;
mod positions;
pub mod prefetch;
pub mod reach;
pub mod reach_chunks;
pub mod receiver_chunks;
mod rectangles;
mod refine;
mod rounding;
mod scatter;
mod scatter_lanes;
pub mod strategies;
#[cfg(test)]
mod test_rng;
mod tiled;
pub mod tiles;
pub mod view;
mod vpl_bounds;
mod vpl_lanes;

pub use frusta::FRUSTUM_SLACK;
pub use reach::{ListedReach, VplReach};
pub use reach_chunks::ReachChunks;
pub use receiver_chunks::ReceiverChunks;
pub use strategies::binned::BinnedCuller;
pub use strategies::bounded::BoundedCuller;
pub use strategies::gpu_only::GpuOnly;
pub use strategies::none::NoCulling;
pub use tiled::BoundedMemory;
pub use view::CullView;
pub use vpl_bounds::{GlossyBound, BOUND_SLACK};

use slc_core::{CpuCuller, Layout, Strategy};

/// The CPU culler of `strategy` ([`GpuOnly`], which culls nothing and says so, for the GPU's
/// raster baselines).
pub fn culler(strategy: Strategy) -> Box<dyn CpuCuller> {
    if let Some(c) = BoundedCuller::new(strategy) {
        return Box::new(c);
    }
    match strategy.parts().0 {
        Layout::Unculled => Box::new(NoCulling),
        Layout::Binned => Box::new(BinnedCuller::default()),
        _ => Box::new(GpuOnly(strategy)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_strategy_gives_a_culler_of_that_strategy() {
        for s in Strategy::every() {
            assert_eq!(culler(s).strategy(), s);
        }
    }
}
