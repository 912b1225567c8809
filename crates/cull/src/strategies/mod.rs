//! The culling strategies: [`none::NoCulling`], and [`bounded::BoundedCuller`] for every
//! strategy that tests bounds (they share `tiled` and differ only in the bound of glossy VPLs
//! and the depth clustering); [`binned::BinnedCuller`] scatters each VPL's bound into the
//! tiles it covers and tests it per pixel; [`gpu_only::GpuOnly`] names the GPU's raster
//! baselines.
pub mod binned;
pub mod bounded;
pub mod gpu_only;
pub mod none;
