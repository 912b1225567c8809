//! No culling on the GPU (`shaders/none_cull.wgsl`), the twin of `slc_cull`'s `none`
//! strategy (`NoCulling`): every pixel with a G-buffer sample gets every VPL of its
//! interleaved subregion (paper section 6), in ascending order; the brute-force baseline.
//!
//! Each VPL becomes a bound that reaches everything, tagged with its subregion, and
//! `partition_pass` groups them by subregion (a stable counting sort): the partition's K²
//! segments are the lists, one per subregion, and each pixel points to its subregion's.
//! VPLs from the CPU are validated as for every GPU pass (`FrameVpls::records`, as the
//! shading pass would), where the CPU's unculled strategy does not look at them.
use crate::buffers::{output, upload, Grid};
use crate::context::{GpuContext, GpuError};
use crate::cull_frame::{check_input, CullFrame, CullSizes};
use crate::cull_types::GpuNoneParams;
use crate::gpu_lists::GpuLightLists;
use crate::gpu_lists::{no_lists, read_lists};
use crate::gpu_types::{GpuBound, GpuCullStatus};
use crate::partition_pass::PartitionPass;
use crate::scan_pass::ScanPass;
use slc_core::{CullInput, LightLists};

/// `shaders/rng.wgsl` (the subregions) and `shaders/bound.wgsl` followed by the kernel.
pub(crate) const SOURCE: &str = concat!(
    include_str!("../shaders/rng.wgsl"),
    include_str!("../shaders/bound.wgsl"),
    include_str!("../shaders/gvpl.wgsl"),
    include_str!("../shaders/none_cull.wgsl")
);
const WORKGROUP: u32 = 64;

/// The no-culling pipelines.
pub struct NoneCuller {
    partition: PartitionPass,
    scan: ScanPass,
    pipeline: wgpu::ComputePipeline,
}

impl NoneCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("no-culling pipelines", || {
            Ok(Self {
                partition: PartitionPass::new(ctx),
                scan: ScanPass::new(ctx),
                pipeline: ctx.compute_pipeline("no culling", SOURCE),
            })
        })
    }

    /// The lists of `slc_cull`'s `none` for `input`, read back. Errors on invalid input (as
    /// the CPU culler: G-buffer size, K), on buffers beyond the device's limits and on
    /// device faults.
    pub fn cull(&self, ctx: &GpuContext, input: &CullInput) -> Result<LightLists, GpuError> {
        read_lists(ctx, &self.cull_on_gpu(ctx, input)?)
    }

    /// [`Self::cull_frame`] of `input` with its G-buffer uploaded.
    pub fn cull_on_gpu(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
    ) -> Result<GpuLightLists, GpuError> {
        self.cull_frame(ctx, &CullFrame::upload(ctx, input)?)
    }

    /// Culls `frame` without a readback: K² lists (one per subregion, empty ones included)
    /// left on the GPU for the shading pass.
    pub fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
    ) -> Result<GpuLightLists, GpuError> {
        let CullSizes {
            pixels,
            k,
            vpl_count,
        } = check_input(frame)?;
        if pixels == 0 {
            return no_lists(ctx);
        }
        let params = GpuNoneParams {
            vpl_count,
            pixel_count: pixels,
            width: frame.width,
            k,
            seed: frame.interleaving.seed,
            pad: [0; 3],
        };
        let vpls = frame.vpls.records(ctx, frame.delta)?;
        let count = frame.vpls.count();
        let bounds = output::<GpuBound>(ctx, "unculled bounds", vpl_count as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        // The partition's scan records its total here; nothing can overflow.
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let grid = Grid::for_items(ctx, u64::from(vpl_count.max(pixels)), WORKGROUP)?;
        let partition = ctx.submit("no culling", |encoder| {
            let params = count.uniform(
                ctx,
                encoder,
                "no-culling params",
                &params,
                std::mem::offset_of!(GpuNoneParams, vpl_count),
            );
            ctx.encode_dispatch(
                encoder,
                "no culling",
                &self.pipeline,
                &[&params, &vpls, &frame.positions, &bounds, &pixel_list],
                grid,
            );
            self.partition
                .encode(ctx, encoder, &self.scan, &bounds, &count, k * k, &status)
        })?;
        Ok(GpuLightLists {
            offsets: partition.sub_offsets,
            indices: partition.order,
            pixel_list,
            list_count: k * k,
            // Every VPL is in exactly one list (GPU VPLs: at most the count's capacity).
            entries: vpl_count,
            pixels,
            writes: Vec::new(),
        })
    }
}
