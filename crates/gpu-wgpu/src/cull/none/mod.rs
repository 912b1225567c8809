//! No culling on the GPU (`none_cull.wesl`), the twin of `slc_cull`'s `none`
//! strategy (`NoCulling`): every pixel with a G-buffer sample gets every VPL of its
//! interleaved subregion (paper section 6), in ascending order; the brute-force baseline.
//!
//! Each VPL becomes a bound that reaches everything, tagged with its subregion, and
//! `cull::partition` groups them by subregion (a stable counting sort): the partition's K²
//! segments are the lists, one per subregion, and each pixel points to its subregion's.
//! VPLs from the CPU are validated as for every GPU pass (`FrameVpls::records`, as the
//! shading pass would), where the CPU's unculled strategy does not look at them.
use crate::cull::frame::{check_input, CullFrame, CullSizes};
use crate::cull::lists::GpuLightLists;
use crate::cull::lists::{no_lists, read_lists};
use crate::cull::partition::PartitionPass;
use crate::cull::records::{GpuBound, GpuCullStatus};
use crate::device::buffers::{output, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::scan::ScanPass;
use bytemuck::{Pod, Zeroable};
use slc_core::{CullInput, LightLists};

/// Parameters of the no-culling pass. Keep in sync with `NoneParams` in
/// `none_cull.wesl`.
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

/// The kernel of `none_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("none_cull");
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
        } = check_input(ctx, frame)?;
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
            ctx.encode_dispatch_at(
                encoder,
                "no culling",
                &self.pipeline,
                &vpls.with(&[&params, &frame.positions, &bounds, &pixel_list]),
                grid,
            );
            self.partition
                .encode(ctx, encoder, &self.scan, (&bounds, &count), k * k, &status)
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
