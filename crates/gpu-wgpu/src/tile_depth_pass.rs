//! Modified HalfZ depth bounds per tile (`shaders/tile_depth.wgsl`, paper section 5.1): from
//! the G-buffer positions, each tile's image-plane rectangle and the depth ranges of its near
//! and far clusters, and each pixel's light list (the list of its cluster).
use crate::buffers::Grid;
use crate::context::GpuContext;

/// `shaders/tiles.wgsl` (tile grid, shared structs) followed by the depth kernel.
pub(crate) const SOURCE: &str = concat!(
    include_str!("../shaders/tiles.wgsl"),
    include_str!("../shaders/tile_depth.wgsl")
);

/// The buffers the depth pass reads and writes (see `shaders/tile_depth.wgsl`).
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
    /// The subregions' VPL ranges (`partition_pass`): each tile's is copied to its frusta.
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
