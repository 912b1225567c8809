//! `#[repr(C)]` twins of the WGSL structs of the no-culling and clustered culling passes,
//! in the convention of [`crate::gpu_types`]: each names the WGSL file whose struct of the
//! same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the shader.
use bytemuck::{Pod, Zeroable};

/// Parameters of the no-culling pass. Keep in sync with `NoneParams` in
/// `shaders/none_cull.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuNoneParams {
    pub vpl_count: u32,
    pub pixel_count: u32,
    pub width: u32,
    /// Interleaving factor K and seed (`slc_core::Interleaving`).
    pub k: u32,
    pub seed: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuNoneParams>() == 32);

/// Depth slices per tile of the clustered strategies (`slc_cull`'s 32 exponential slices).
pub const CLUSTER_SLICES: u32 = 32;

/// `GpuCullParams::mode` of `shaders/cluster_depth.wgsl`: the G-buffer's depth range, then
/// the slices of each tile.
pub const DEPTH_RANGE: u32 = 0;
pub const DEPTH_SPLIT: u32 = 1;

/// One tile's cluster frusta (exponential depth slices): the tile's rectangle at unit depth,
/// the mask of occupied slices and each slice's depth range, all grown by the frustum slack.
/// Keep in sync with `ClusterFrusta` in `shaders/clusters.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuClusterFrusta {
    /// (u0, v0, u1, v1).
    pub rect: [f32; 4],
    /// Mask of occupied slices (x; bit s: slice s), unused.
    pub info: [u32; 4],
    /// [z0, z1] of each slice (zero where unoccupied).
    pub ranges: [[f32; 2]; CLUSTER_SLICES as usize],
}
const _: () = assert!(std::mem::size_of::<GpuClusterFrusta>() == 288);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu_types::wgsl_size;

    /// Every Rust struct has the size of its WGSL twin as the shader compiler lays it out.
    #[test]
    fn sizes_match_the_wgsl_twins() {
        use std::mem::size_of;
        let cases = [
            (
                crate::none_cull_pass::SOURCE,
                "NoneParams",
                size_of::<GpuNoneParams>(),
            ),
            (
                crate::clustered_cull_pass::DEPTH_SOURCE,
                "ClusterFrusta",
                size_of::<GpuClusterFrusta>(),
            ),
            (
                crate::clustered_cull_pass::CULL_SOURCE,
                "ClusterFrusta",
                size_of::<GpuClusterFrusta>(),
            ),
        ];
        for (source, name, size) in cases {
            assert_eq!(wgsl_size(source, name), size, "{name}");
        }
    }
}
