//! `#[repr(C)]` twins of the WGSL structs of the clustered culling passes (32 depth slices per tile, section 7). Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars and `[f32; 4]` / `[u32; 4]` are used (WGSL `f32`, `u32`, `vec4<f32>`,
//! `vec4<u32>`), never vec3, so the Rust and WGSL layouts agree without hidden padding.
use bytemuck::{Pod, Zeroable};

/// Depth slices per tile of the clustered strategies (`slc_cull`'s 32 exponential slices).
pub const CLUSTER_SLICES: u32 = 32;
/// `GpuCullParams::mode` of `cluster_depth.wesl`: the G-buffer's depth range, then
/// the slices of each tile.
pub const DEPTH_RANGE: u32 = 0;
pub const DEPTH_SPLIT: u32 = 1;
/// One tile's cluster frusta (exponential depth slices): the tile's rectangle at unit depth,
/// the mask of occupied slices and each slice's depth range, all grown by the frustum slack.
/// Keep in sync with `ClusterFrusta` in `clusters.wesl`.
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

    wgsl_twins! {
        crate::cull::clustered::DEPTH_SOURCE => {
            GpuClusterFrusta as "ClusterFrusta",
        }
        crate::cull::clustered::CULL_SOURCE => {
            GpuClusterFrusta as "ClusterFrusta",
        }
    }
}
