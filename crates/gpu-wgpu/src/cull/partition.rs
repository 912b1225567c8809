//! The VPLs of each interleaved subregion on the GPU (`partition.wesl`, paper
//! section 6): a stable counting sort of the non-empty bounds by subregion, so each tile
//! reads only its subregion's bounds, in ascending VPL order. Count per subregion and run of
//! VPLs (`chunks`; one workgroup per run reads each bound once), scan (`device::scan`),
//! write.
use crate::cull::records::{GpuPartitionParams, CULL_COUNT, CULL_WRITE};
use crate::device::buffers::{output, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::Count;
use crate::device::scan::ScanPass;

/// The kernel of `partition.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("partition");

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
    /// subregions. Overflowed
    /// bounds are recorded in `status` (`GpuCullStatus::overflow_vpl`); the scan also stores
    /// its total there, which a later scan overwrites.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scan: &ScanPass,
        (bounds, count): (&wgpu::Buffer, &Count),
        subregions: u32,
        status: &wgpu::Buffer,
    ) -> Result<GpuPartition, GpuError> {
        let (chunks, chunk) = chunks(count.capacity(), subregions);
        // Per step of 256 VPLs about 63 iterations (the bitonic sort's and the prefix's
        // loops), and one per 256 subregions.
        ctx.check_loop_budget(
            || format!("partitioning runs of {chunk} VPLs into {subregions} subregions"),
            64 * u64::from(chunk.div_ceil(256)) + u64::from(subregions.div_ceil(256)) + 64,
            "lower K (the subregions) or the VPLs (--rsm)",
        )?;
        let cells = subregions * chunks;
        let grid = Grid::new(
            u64::from(chunks),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let counts = output::<u32>(ctx, "subregion run counts", cells as usize + 1)?;
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
                    chunks,
                    chunk,
                    pad: [0; 3],
                },
                std::mem::offset_of!(GpuPartitionParams, vpl_count),
            );
            ctx.encode_dispatch(
                encoder,
                "partition",
                &self.pipeline,
                &[&params, bounds, &counts, &order, status, &sub_offsets],
                grid,
            );
            if mode == CULL_COUNT {
                scan.encode(ctx, encoder, &counts, cells, status)?;
            }
        }
        Ok(GpuPartition { sub_offsets, order })
    }
}

/// The most (subregion, run) cells the counts may take: 4 MiB of u32.
const MAX_CELLS: u32 = 1 << 20;

/// The runs the partition splits `vpls` VPLs into for `subregions` subregions: (number of
/// runs, VPLs per run, a multiple of 256). One workgroup per run, each reading its run once:
/// runs of about 256 VPLs keep hundreds of workgroups busy (202 for 51,468 VPLs), while the
/// counts, one per subregion and run, stay within [`MAX_CELLS`] (one run for K² of 2^20).
pub(crate) fn chunks(vpls: u32, subregions: u32) -> (u32, u32) {
    const RUN: u32 = 256;
    let most = (MAX_CELLS / subregions.max(1)).max(1);
    let runs = vpls.div_ceil(RUN).clamp(1, most);
    let chunk = vpls.div_ceil(runs).div_ceil(256).max(1) * 256;
    // Rounding the run up to 256 may leave the last runs empty: drop them.
    (vpls.div_ceil(chunk).max(1), chunk)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs cover every VPL in multiples of 256, about 256 each, and the counts never
    /// exceed MAX_CELLS: one run where K² alone reaches it.
    #[test]
    fn runs_cover_the_vpls_within_the_count_budget() {
        for vpls in [
            0,
            1,
            255,
            256,
            1024,
            1025,
            51_468,
            131_072,
            2_000_000,
            u32::MAX / 2,
        ] {
            for subregions in [1, 4, 64, 256, 4096, 1 << 20] {
                let (chunks, chunk) = chunks(vpls, subregions);
                assert!(chunks >= 1 && chunk % 256 == 0, "{vpls} {subregions}");
                assert!(u64::from(chunks) * u64::from(chunk) >= u64::from(vpls));
                assert!(
                    u64::from(chunks) * u64::from(subregions)
                        <= u64::from(MAX_CELLS).max(u64::from(subregions))
                );
                // No run is empty (beyond rounding to 256).
                assert!(u64::from(chunks - 1) * u64::from(chunk) < u64::from(vpls).max(1));
            }
        }
        assert_eq!(chunks(51_468, 64), (202, 256));
        assert_eq!(chunks(51_468, 1 << 20).0, 1);
    }
}
