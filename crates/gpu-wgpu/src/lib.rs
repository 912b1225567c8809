//! # slc-gpu-wgpu
//!
//! The GPU backend of slc on wgpu (Tokuyoshi and Harada, "Stochastic Light Culling for VPLs
//! on GGX Microsurfaces"; equation and section numbers refer to that paper), a sibling of the
//! CPU reference renderer: each pass is the twin of a CPU step, checked against it by the
//! conformance tests in `tests/gpu/`.
//!
//! The crate is laid out by feature, in the order of a frame. Each folder holds its passes'
//! Rust, the WESL modules of their shaders beside them and the `#[repr(C)]` records the two
//! share (`records.rs`, each with a test that naga lays the WGSL twin out the same):
//! - [`device`]: the context and its errors, timestamp profiles, buffers and readbacks,
//!   counts kept on the GPU, the prefix sum;
//! - `material/` (WESL only): the BRDF of eq. (6)-(8) and Fresnel, shared by every pass that
//!   shades;
//! - [`frame`]: scene upload, visibility and G-buffer by rasterization, reflective shadow maps,
//!   direct light, the cross bilateral filter;
//! - [`vpl`]: the counter-based RNG and VPL generation;
//! - [`cull`]: per-VPL bounds and the partition by subregion, then one folder per layout
//!   (`tiled` Modified HalfZ tiles, `clustered` depth slices, `tight` per-block refinement,
//!   `none`, and the `raster` baselines of the paper's Table 2), with [`cull::GpuCulling`]
//!   running any `slc_core::Strategy`;
//! - [`shade`]: stochastic shading from light lists, or culled and shaded in one pass;
//! - [`vsgl`]: virtual spherical Gaussian lights built, sampled and shaded on the GPU, with
//!   imperfect shadow maps;
//! - [`renderer`]: [`GpuRenderer`], the backend of the renderer API (`slc_core::Renderer`),
//!   on a device it opens or one the host owns ([`GpuContext::from_device`]; the host asks
//!   for [`GpuContext::required_limits`] at least, a device below them is refused by name),
//!   and the frame sizes it refuses before any work ([`renderer::limits`]).
//!
//! Shaders are WESL modules (`*.wesl` beside their Rust): a kernel imports what it uses
//! (`import package::material::brdf::{brdf_eval};`), `build.rs` links each kernel into one
//! WGSL source with the `wesl` crate and validates it with naga, so a missing import or a
//! clash of names fails the build; `kernel!` includes a linked kernel.
//!
//! Per-pass GPU times come from timestamp queries where the adapter has them
//! ([`device::profiler`]). Faults are errors ([`GpuError`]): no adapter (suggests `--backend
//! cpu`), device loss (no hang: bounded waits), buffers beyond the storage-binding limit
//! (refused), dispatches beyond 65535 workgroups per dimension (split into 2-D grids,
//! [`device::buffers::Grid`]).

/// The WGSL source of the kernel `name` as `build.rs` linked it from the WESL modules.
macro_rules! kernel {
    ($name:literal) => {
        include_str!(concat!(env!("OUT_DIR"), "/kernels/", $name, ".wgsl"))
    };
}

/// The test that each Rust record has the size of its WGSL twin in the kernels that read it,
/// as the shader compiler lays the twin out: `kernel => { RustType as "WgslName", … }`.
#[cfg(test)]
macro_rules! wgsl_twins {
    ($($kernel:expr => { $($ty:ty as $name:literal),+ $(,)? })+) => {
        #[test]
        fn sizes_match_the_wgsl_twins() {
            $($(assert_eq!(
                crate::device::wgsl_size($kernel, $name),
                std::mem::size_of::<$ty>(),
                "{} in {}",
                $name,
                stringify!($kernel)
            );)+)+
        }
    };
}

pub mod cull;
pub mod device;
pub mod frame;
pub mod renderer;
pub mod shade;
pub mod vpl;
pub mod vsgl;

pub use device::profiler::GpuProfile;
pub use device::{GpuContext, GpuError};
pub use renderer::{GpuLoadedScene, GpuPrepared, GpuRenderer};
