//! `#[repr(C)]` twins of the WGSL structs of the raster baselines (splatting \[DS06\], rasterized clusters \[OP16\]). Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars and `[f32; 4]` / `[u32; 4]` are used (WGSL `f32`, `u32`, `vec4<f32>`,
//! `vec4<u32>`), never vec3, so the Rust and WGSL layouts agree without hidden padding.
use bytemuck::{Pod, Zeroable};

/// One VPL's bound as a shape in the culling view, for the raster baselines' meshes
/// (`cull::raster::mesh.wesl`), written by `bounds.wesl` beside its `GpuBound` when
/// asked: the spheroid of eq. (12)-(15) (or a sphere: both semi-axes equal) with `center` the
/// view-space centre (xyz) and the semi-axis along `axis` (w), `axis` the unit axis ω_u (xyz)
/// and the other two semi-axes (w), all grown as the bound. w < 0: no shape (an empty or
/// overflowed bound). Keep in sync with `Shape` in `bound_mesh.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBoundShape {
    pub center: [f32; 4],
    pub axis: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBoundShape>() == 32);
/// Parameters of the raster baselines' passes (`raster_args.wesl`, `splat.wesl`,
/// `splat_resolve.wesl`, `cluster_shell.wesl`, `cluster_fill.wesl`). Keep in sync with
/// `RasterParams` in `bound_mesh.wesl`.
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

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        crate::cull::raster::ARGS_SOURCE => {
            GpuRasterParams as "RasterParams",
        }
    }
}
