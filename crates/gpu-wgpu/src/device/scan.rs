//! Exclusive prefix sum of u32 counts into offsets (`scan.wesl`), in place, with the
//! total appended: the light-list offsets from the per-tile list lengths.
use crate::device::buffers::{uniform, Grid};
use crate::device::context::{GpuContext, GpuError};
use bytemuck::{Pod, Zeroable};

/// Parameters of the exclusive scan (`scan.wesl`, `ScanParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuScanParams {
    /// Number of values; the scan writes n + 1 offsets (the last is the total).
    pub count: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuScanParams>() == 16);

pub(crate) const SOURCE: &str = kernel!("scan");

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
    /// goes to `values[count]` and to `GpuCullStatus::total` in `status`. Errors where the
    /// adapter ends loops before a run's walk is done ([`GpuContext::check_loop_budget`]).
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        values: &wgpu::Buffer,
        count: u32,
        status: &wgpu::Buffer,
    ) -> Result<(), GpuError> {
        // Each invocation walks its run of ⌈count / 256⌉ values twice, eight per iteration
        // and the last few one by one, and scans the 256 runs' sums in eight steps.
        let run = u64::from(count.div_ceil(256));
        ctx.check_loop_budget(
            || format!("scanning {count} values"),
            2 * (run / 8 + 9) + 64,
            "lower the image size or the light count",
        )?;
        let params = uniform(ctx, "scan params", &GpuScanParams { count, pad: [0; 3] });
        ctx.encode_dispatch(
            encoder,
            "scan",
            &self.pipeline,
            &[&params, values, status],
            Grid { x: 1, y: 1 },
        );
        Ok(())
    }
}
