//! Exclusive prefix sum of u32 counts into offsets (`shaders/scan.wgsl`), in place, with the
//! total appended: the light-list offsets from the per-tile list lengths.
use crate::buffers::{uniform, Grid};
use crate::context::GpuContext;
use crate::gpu_types::GpuScanParams;

pub(crate) const SOURCE: &str = include_str!("../shaders/scan.wgsl");

/// The compiled scan pipeline.
pub struct ScanPass {
    pipeline: wgpu::ComputePipeline,
}

impl ScanPass {
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            pipeline: ctx.compute_pipeline("scan", SOURCE),
        }
    }

    /// Records the scan of `values[0..count]` (the buffer holds `count + 1` u32); the total
    /// goes to `values[count]` and to `GpuCullStatus::total` in `status`.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        values: &wgpu::Buffer,
        count: u32,
        status: &wgpu::Buffer,
    ) {
        let params = uniform(ctx, "scan params", &GpuScanParams { count, pad: [0; 3] });
        ctx.encode_dispatch(
            encoder,
            "scan",
            &self.pipeline,
            &[&params, values, status],
            Grid { x: 1, y: 1 },
        );
    }
}
