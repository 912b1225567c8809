//! `#[repr(C)]` twins of the WGSL structs of the no-culling, clustered and tight culling passes,
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

/// One VPL's bound as a shape in the culling view, for the raster baselines' meshes
/// (`shaders/bound_mesh.wgsl`), written by `shaders/bounds.wgsl` beside its `GpuBound` when
/// asked: the spheroid of eq. (12)-(15) (or a sphere: both semi-axes equal) with `center` the
/// view-space centre (xyz) and the semi-axis along `axis` (w), `axis` the unit axis ω_u (xyz)
/// and the other two semi-axes (w), all grown as the bound. w < 0: no shape (an empty or
/// overflowed bound). Keep in sync with `Shape` in `shaders/bound_mesh.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBoundShape {
    pub center: [f32; 4],
    pub axis: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBoundShape>() == 32);

/// Parameters of the raster baselines' passes (`shaders/raster_args.wgsl`, `splat.wgsl`,
/// `splat_resolve.wgsl`, `cluster_shell.wgsl`, `cluster_fill.wgsl`). Keep in sync with
/// `RasterParams` in `shaders/bound_mesh.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuRasterParams {
    /// (aspect tan(yfov/2), tan(yfov/2), W, H), as `GpuCullParams::image`.
    pub image: [f32; 4],
    /// Viewport cell (u, v) of subregion (i, j) spans screen pixels `i + cell (u − shift.x)`
    /// onwards (the same in y).
    pub shift: [f32; 2],
    pub cell: f32,
    /// δ of eq. (2).
    pub delta: f32,
    pub width: u32,
    pub height: u32,
    pub k: u32,
    /// Vertices per mesh draw.
    pub mesh_vertices: u32,
    /// Cells per subregion viewport.
    pub view_w: u32,
    pub view_h: u32,
    /// Nodes the node buffer holds.
    pub capacity: u32,
    /// K² of the interleaved sampling (section 6).
    pub scale: f32,
    pub tiles_x: u32,
    pub tiles_y: u32,
    pub vpl_count: u32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuRasterParams>() == 80);

/// One VPL's bound of p(ωo, l) of eq. (2) over boxes of receivers (`slc_bounds::BoxBound`,
/// docs/tight-bounds.md) in the culling view, written by `shaders/bounds.wgsl` for the tight
/// strategies. Keep in sync with `BoxBound` in `shaders/box_bound.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBoxBound {
    /// q = R (position − eye) (xyz) and the growth of every box tested against this VPL for
    /// the f32 rounding of q, of the receivers' view positions and of the shader's offsets
    /// x − q (w).
    pub q_slack: [f32; 4],
    /// The lobe's normal in view (xyz) and the largest intensity in any direction (w).
    pub normal_peak: [f32; 4],
    /// ωi (xyz) and cos θh_max(ωi) of supplemental eq. (2) (w).
    pub omega_i_cos_h_max: [f32; 4],
    /// The mirror direction ω_u (xyz) and G1(ωi)/(4 ωi·n) (w).
    pub omega_u_g1_i: [f32; 4],
    /// Φ times `GlossyLobe::bound_factor` (xyz) and α (w, the lobe's largest).
    pub flux_alpha: [f32; 4],
    /// Schlick's F0 (xyz) and a dielectric's η (w).
    pub f0_eta: [f32; 4],
    /// [`BOX_EMPTY`], [`BOX_DIFFUSE`] or [`BOX_GLOSSY`]; the Fresnel model; the bits of the
    /// α whose G1 bounds G1(ωo) (0.0: bounded by 1, a tilted normal); the bits of
    /// δ ξ / (1 + `PROBABILITY_SLACK`).
    pub info: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBoxBound>() == 112);

/// `GpuBoxBound::info[0]`: never listed, a diffuse lobe (eq. 4, f = kd/π), a glossy one.
pub const BOX_EMPTY: u32 = 0;
pub const BOX_DIFFUSE: u32 = 1;
pub const BOX_GLOSSY: u32 = 2;

/// The refinement of the tight strategies (`shaders/tight_cull.wgsl`): the base strategy's
/// lists per tile and whether each block's samples of a list are split at their half depth.
/// Keep in sync with `TightParams` in `shaders/tight_cull.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuTightParams {
    /// Lists per tile of the base strategy: 2 (Modified HalfZ) or [`CLUSTER_SLICES`].
    pub clusters: u32,
    /// 2 where each block's samples of a list are split at their half depth, else 1.
    pub halves: u32,
    /// max |coordinate| of the eye: the boxes grow for the rounding of R (x − eye).
    pub eye_extent: f32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuTightParams>() == 16);

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
            (
                crate::bounds_pass::SOURCE,
                "BoxBound",
                size_of::<GpuBoxBound>(),
            ),
            (
                crate::tight_cull_pass::SOURCE,
                "BoxBound",
                size_of::<GpuBoxBound>(),
            ),
            (
                crate::tight_cull_pass::SOURCE,
                "TightParams",
                size_of::<GpuTightParams>(),
            ),
        ];
        for (source, name, size) in cases {
            assert_eq!(wgsl_size(source, name), size, "{name}");
        }
    }
}
