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
//!   with workgroup-shared light lists, offset by [`scan_pass`]; the sphere,
//!   enclosing-sphere and ellipsoid strategies, read back as `slc_core::LightLists` or left
//!   on the GPU for shading;
//! - [`tight_cull_pass`]: the `tight` and `clustered-tight` refinement, per 8 x 8 block,
//!   by the bound of p over the block's receivers (`shaders/box_bound.wgsl`, the f32 twin of
//!   `slc_bounds::BoxBound`; docs/tight-bounds.md);
//! - [`shade_pass`]: stochastic VPL shading from light lists (eq. 2-4 and 6-8 with the K²
//!   weight of section 6; `shaders/brdf.wgsl`, `shaders/vpl_eval.wgsl`, `shaders/shade.wgsl`),
//!   the twin of `slc_cpu_ref::vpl_shading::shade_lists` without visibility, lists uploaded
//!   or straight from a culler;
//! - [`tiled_shade_pass`]: tiled culling and shading in one pass (the paper's Fig. 2): the
//!   hits of each batch of a tile's VPLs in workgroup bit masks, no list stored; the
//!   renderer's path for the tiled strategies;
//! - [`scene_upload`]: the scene (triangles, normals, texture coordinates, materials and
//!   textures) in storage buffers, [`scene_upload::GpuScene`];
//! - [`visibility_pass`]: the nearest triangle per pixel by rasterization (depth test), from
//!   a camera or a light face;
//! - [`gbuffer_pass`]: the rasterized G-buffer (twin of `slc_cpu_ref::gbuffer`), left on the
//!   GPU in the layout culling and shading read, or read back as `slc_core::GBuffer`;
//! - [`rsm_pass`]: reflective shadow maps by rasterization (twin of `slc_cpu_ref::rsm`,
//!   point light = six faces, spot = one, directional = orthographic), whose depth is kept
//!   as a shadow map;
//! - [`vpl_gen_pass`]: VPLs from RSM texels in compute (twin of `slc_cpu_ref::vpls`, same
//!   ids and ξ), compacted by a scan, complete with their bound factor, left on the GPU;
//! - [`direct_pass`]: direct light per G-buffer pixel (twin of `slc_cpu_ref::direct`) with
//!   the RSM depth as shadow maps instead of shadow rays;
//! - [`none_cull_pass`]: no culling (every VPL of the pixel's subregion), the twin of
//!   `slc_cull`'s `none`;
//! - [`clustered_cull_pass`]: clustered culling (32 exponential depth slices per tile,
//!   section 7), the twin of `slc_cull`'s `clustered`, `clustered-sphere` and
//!   `clustered-enclosing-sphere`, with its structs in [`cull_types`];
//! - [`culler`]: every `slc_core::Strategy` ([`culler::GpuCuller`], bound to one strategy as
//!   a `slc_core::Culler`); [`cull_frame`] holds what the culling passes share, [`gpu_lists`]
//!   the lists they leave on the GPU, [`list_room`] the room their buffers get (no count is
//!   read back inside a frame; lists that outgrew it are culled again);
//! - [`denoise_pass`]: the cross bilateral filter guided by depth and normal (section 6),
//!   the twin of `slc_cpu_ref::denoise::cross_bilateral`, on GPU buffers or uploaded images
//!   (struct in [`denoise_types`]);
//! - [`vsgl_build_pass`]: virtual spherical Gaussian lights built from the RSMs where they
//!   lie (Tokuyoshi 2015, sections 4.1-4.3: mipmaps, flux or bidirectional importance,
//!   filtered importance sampling), the twin of `slc_cpu_ref::sampled_lights::sample_vsgls`
//!   (structs in [`vsgl_build_types`]);
//! - [`vsgl_shade_pass`]: shading by those lights (section 3.2, eq. 2-5;
//!   `shaders/sg.wgsl`, `shaders/vsgl_shade.wgsl`), the twin of
//!   `slc_cpu_ref::vsgl::shade_vsgls` (structs in [`vsgl_types`]).
//!
//! [`renderer::GpuRenderer`] composes them into the backend of the renderer API
//! (`slc_core::Renderer`), on a device it opens or one the host owns
//! ([`GpuContext::from_device`]); [`vsgl_readback`] brings RSMs to the CPU (for the CPU's
//! reference passes) and CPU VSGLs to the shading pass.
//!
//! Per-pass GPU times come from timestamp queries where the adapter has them
//! ([`profiler`]: `start_profiling`, `set_stage`, `finish_profiling`).
//!
//! Faults are errors ([`GpuError`]): no adapter (suggests `--backend cpu`), device loss
//! (no hang: bounded waits), buffers beyond the storage-binding limit (refused), dispatches
//! beyond 65535 workgroups per dimension (split into 2-D grids, [`buffers::Grid`]).
pub mod bound_mesh;
pub mod bounds_pass;
pub mod buffers;
pub mod cluster_raster_pass;
pub mod clustered_cull_pass;
pub mod context;
pub mod cull_frame;
pub mod cull_types;
pub mod culler;
pub mod denoise_pass;
pub mod denoise_types;
pub mod direct_pass;
pub mod frame_limits;
pub mod gbuffer_pass;
pub mod gpu_count;
pub mod gpu_lists;
pub mod gpu_types;
pub mod ism_casters;
pub mod ism_pass;
pub mod list_room;
pub mod node_lists;
pub mod none_cull_pass;
pub mod partition_pass;
pub mod profiler;
pub mod raster_draw;
pub mod raster_types;
pub mod renderer;
mod renderer_notes;
pub mod rng_pass;
pub mod rsm_pass;
pub mod scan_pass;
pub mod scene_upload;
pub mod shade_pass;
mod specular_table;
pub mod splat_pass;
pub mod tight_cull_pass;
pub mod tile_depth_pass;
pub mod tiled_cull_pass;
pub mod tiled_shade_pass;
pub mod visibility_pass;
pub mod vpl_gen_pass;
pub mod vsgl_build_pass;
pub mod vsgl_build_types;
pub mod vsgl_readback;
pub mod vsgl_shade_pass;
pub mod vsgl_types;

pub use context::{GpuContext, GpuError};
pub use profiler::GpuProfile;
pub use renderer::{GpuLoadedScene, GpuPrepared, GpuRenderer};
