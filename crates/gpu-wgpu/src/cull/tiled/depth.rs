//! Modified HalfZ depth bounds per tile (`tile_depth.wesl`, paper section 5.1): from
//! the G-buffer positions, each tile's image-plane rectangle and the depth ranges of its near
//! and far clusters, and each pixel's light list (the list of its cluster).
use crate::device::buffers::Grid;
use crate::device::context::GpuContext;

/// The kernel of `tile_depth.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("tile_depth");

/// The buffers the depth pass reads and writes (see `tile_depth.wesl`).
pub struct TileDepthBuffers<'a> {
    /// `GpuCullParams` (uniform).
    pub params: &'a wgpu::Buffer,
    /// World positions per pixel, `[x, y, z, 1]`, or zero where there is no sample.
    pub positions: &'a wgpu::Buffer,
    /// `GpuTileFrusta` per tile (written).
    pub frusta: &'a wgpu::Buffer,
    /// The list of each pixel (written).
    pub pixel_list: &'a wgpu::Buffer,
    /// `GpuCullStatus` (the smallest bad pixel is recorded).
    pub status: &'a wgpu::Buffer,
    /// The subregions' VPL ranges (`cull::partition`): each tile's is copied to its frusta.
    pub sub_offsets: &'a wgpu::Buffer,
}

/// The compiled depth pipeline.
pub struct TileDepthPass {
    pipeline: wgpu::ComputePipeline,
}

impl TileDepthPass {
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            pipeline: ctx.compute_pipeline("tile depth", SOURCE),
        }
    }

    /// Records the pass: one workgroup per tile over the `tiles` grid.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        buffers: &TileDepthBuffers,
        tiles: Grid,
    ) {
        ctx.encode_dispatch(
            encoder,
            "tile depth",
            &self.pipeline,
            &[
                buffers.params,
                buffers.positions,
                buffers.frusta,
                buffers.pixel_list,
                buffers.status,
                buffers.sub_offsets,
            ],
            tiles,
        );
    }
}
