//! The VPLs of each interleaved subregion on the GPU (`shaders/partition.wgsl`, paper
//! section 6): a stable counting sort of the non-empty bounds by subregion, so each tile
//! reads only its subregion's bounds, in ascending VPL order. Count, scan (`scan_pass`),
//! write.
use crate::buffers::{output, Grid};
use crate::context::{GpuContext, GpuError};
use crate::gpu_count::Count;
use crate::gpu_types::{GpuPartitionParams, CULL_COUNT, CULL_WRITE};
use crate::scan_pass::ScanPass;

/// `shaders/bound.wgsl` followed by the partition kernel.
pub(crate) const SOURCE: &str = concat!(
    include_str!("../shaders/bound.wgsl"),
    include_str!("../shaders/partition.wgsl")
);

/// A partition on the GPU: subregion s holds the VPL indices
/// `order[sub_offsets[s]..sub_offsets[s + 1]]`, ascending; empty bounds are left out.
pub struct GpuPartition {
    pub sub_offsets: wgpu::Buffer,
    pub order: wgpu::Buffer,
}

/// The compiled partition pipeline.
pub struct PartitionPass {
    pipeline: wgpu::ComputePipeline,
}

impl PartitionPass {
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            pipeline: ctx.compute_pipeline("partition", SOURCE),
        }
    }

    /// Records count, scan and write for the `count` bounds of `bounds` in `subregions`
    /// subregions.
    /// Overflowed bounds are recorded in `status` (`GpuCullStatus::overflow_vpl`); the scan
    /// also stores its total there, which a later scan overwrites.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scan: &ScanPass,
        bounds: &wgpu::Buffer,
        count: &Count,
        subregions: u32,
        status: &wgpu::Buffer,
    ) -> Result<GpuPartition, GpuError> {
        let grid = Grid::new(
            u64::from(subregions),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let sub_offsets = output::<u32>(ctx, "subregion offsets", subregions as usize + 1)?;
        let order = output::<u32>(ctx, "subregion order", count.capacity() as usize)?;
        for mode in [CULL_COUNT, CULL_WRITE] {
            let params = count.uniform(
                ctx,
                encoder,
                "partition params",
                &GpuPartitionParams {
                    vpl_count: count.capacity(),
                    subregions,
                    mode,
                    pad: 0,
                },
                std::mem::offset_of!(GpuPartitionParams, vpl_count),
            );
            ctx.encode_dispatch(
                encoder,
                "partition",
                &self.pipeline,
                &[&params, bounds, &sub_offsets, &order, status],
                grid,
            );
            if mode == CULL_COUNT {
                scan.encode(ctx, encoder, &sub_offsets, subregions, status);
            }
        }
        Ok(GpuPartition { sub_offsets, order })
    }
}
