//! # slc-gpu-wgpu
//!
//! The GPU backend of slc on wgpu/WGSL (Tokuyoshi and Harada, "Stochastic Light Culling for
//! VPLs on GGX Microsurfaces"; equation and section numbers refer to that paper). WGSL lives
//! in `shaders/` (loaded with `include_str!`), one Rust file per pass; GPU structs in
//! [`gpu_types`] mirror their WGSL twins with compile-time size checks.
//!
//! Passes so far:
//! - [`rng_pass`]: the counter-based RNG of `slc_core::rng` in WGSL (`shaders/rng.wgsl`),
//!   bit for bit the same numbers (ξ of eq. 3, interleaved subregions);
//! - [`bounds_pass`]: per-VPL bounds (section 6 sphere, section 7 spheres, the spheroid's
//!   test space of eq. 16-17) in the culling view, as `slc_cull` computes them;
//! - [`partition_pass`]: the VPLs of each interleaved subregion (section 6), a stable
//!   counting sort on the GPU;
//! - [`tile_depth_pass`]: Modified HalfZ tile frusta (section 5.1) from G-buffer positions;
//! - [`tiled_cull_pass`]: tiled culling of interleaved subregions (sections 5-6, Listing 2)
//!   with workgroup-shared light lists, sized by [`scan_pass`]; the sphere,
//!   enclosing-sphere and ellipsoid strategies, read back as `slc_core::LightLists` or left
//!   on the GPU for shading;
//! - [`shade_pass`]: stochastic VPL shading from light lists (eq. 2-4 and 6-8 with the K²
//!   weight of section 6; `shaders/brdf.wgsl`, `shaders/shade.wgsl`), the twin of
//!   `slc_cpu_ref::vpl_shading::shade_lists` without visibility, lists uploaded or straight
//!   from the tiled culler.
//! - [`none_cull_pass`]: no culling (every VPL of the pixel's subregion), the twin of
//!   `slc_cull`'s `none`;
//! - [`clustered_cull_pass`]: clustered culling (32 exponential depth slices per tile,
//!   section 7), the twin of `slc_cull`'s `clustered`, `clustered-sphere` and
//!   `clustered-enclosing-sphere`, with its structs in [`cull_types`];
//! - [`culler`]: every strategy of `slc_cull::CULLER_NAMES` by name ([`culler::GpuCuller`]);
//!   [`cull_frame`] holds what the culling passes share;
//! - [`denoise_pass`]: the cross bilateral filter guided by depth and normal (section 6),
//!   the twin of `slc_cpu_ref::denoise::cross_bilateral`, on GPU buffers or uploaded images
//!   (struct in [`denoise_types`]).
//!
//! Faults are errors ([`GpuError`]): no adapter (suggests `--backend cpu`), device loss
//! (no hang: bounded waits), buffers beyond the storage-binding limit (refused), dispatches
//! beyond 65535 workgroups per dimension (split into 2-D grids, [`buffers::Grid`]).
pub mod bounds_pass;
pub mod buffers;
pub mod clustered_cull_pass;
pub mod context;
pub mod cull_frame;
pub mod cull_types;
pub mod culler;
pub mod denoise_pass;
pub mod denoise_types;
pub mod gpu_types;
pub mod none_cull_pass;
pub mod partition_pass;
pub mod rng_pass;
pub mod scan_pass;
pub mod shade_pass;
pub mod tile_depth_pass;
pub mod tiled_cull_pass;

pub use context::{GpuContext, GpuError};
