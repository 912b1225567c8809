//! The `binned` strategy on the GPU (docs/many-vpls.md), the twin of `slc_cull`'s
//! `binned.rs`: scatter instead of gather. Per VPL, its bound (`cull::bounds`: the section-6
//! sphere or the GGX spheroid of eq. 12-15, grown by `BOUND_SLACK`, written in world axes
//! relative to the VPL as well) and the screen rectangle it may cover
//! (`binned_footprint.wesl`, `footprint.rs`'s f32 arithmetic with its conservative rounding);
//! the subregions' VPLs (`cull::partition`); then per 16 x 16 tile of each interleaved
//! subregion image (`binned_cull.wesl`) the VPLs whose rectangle overlaps the tile's samples,
//! and per pixel the test `binned.rs`'s `PixelTest` makes: the sample x not behind the VPL
//! (eq. 4) and inside its bound. Every pixel gets its own list (list p for pixel p), ascending
//! in the VPL index like the CPU's: the lists read back equal those of the CPU's
//! `BinnedCuller::per_pixel` (the CPU's default shares large ranges per cell) up to f32
//! versus f64 decisions at a bound's surface (the f32 test allows its rounding, which for
//! the sharpest lobes, α = 1e-4, widens the spheroid by about 1%: `binned_footprint.wesl`).
//!
//! Counting, a scan (`device::scan`) and writing run in one submission, into a buffer of the
//! room earlier frames' lists needed (`cull::room`): lists that outgrew it are culled again
//! with the total their fault record reports, and a total beyond the storage-binding limit is
//! refused ([`GpuError::BufferTooLarge`], naming the light lists).
pub mod records;

use crate::cull::bounds::BoundsPass;
use crate::cull::frame::{check_input, cull_params, tile_grid, CullFrame, CullSizes};
use crate::cull::lists::{no_lists, GpuLightLists};
use crate::cull::partition::PartitionPass;
use crate::cull::records::{GpuCullParams, GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::cull::room::ListRoom;
use crate::device::buffers::{output, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::ArgsPass;
use crate::device::scan::ScanPass;
use records::{GpuBinnedParams, GpuBinnedVpl};
use slc_cull::GlossyBound;
use std::mem::offset_of;
use std::sync::Arc;

/// The kernel of `binned_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("binned_cull");
/// The kernel of `binned_footprint.wesl`.
pub(crate) const FOOTPRINT_SOURCE: &str = kernel!("binned_footprint");
/// Invocations per workgroup of the per-VPL pass.
const WORKGROUP: u32 = 64;

/// The binned strategy's pipelines and the room its lists needed.
pub struct BinnedCuller {
    bounds: BoundsPass,
    partition: PartitionPass,
    scan: ScanPass,
    args: ArgsPass,
    footprint: wgpu::ComputePipeline,
    pipeline: wgpu::ComputePipeline,
    /// What the lists of earlier frames needed.
    room: Arc<ListRoom>,
}

impl BinnedCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let bounds = BoundsPass::new(ctx)?;
        let args = ArgsPass::new(ctx)?;
        ctx.scoped("binned culling pipelines", || {
            Ok(Self {
                bounds,
                partition: PartitionPass::new(ctx),
                scan: ScanPass::new(ctx),
                args,
                footprint: ctx.compute_pipeline("binned footprint", FOOTPRINT_SOURCE),
                pipeline: ctx.compute_pipeline("binned cull", SOURCE),
                room: Arc::new(ListRoom::new()),
            })
        })
    }

    /// Sets the room of the next frames' lists (`cull::room`).
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
    }

    /// The lists of `frame` left on the GPU: one per pixel (list p of pixel p, [`slc_core::NO_LIST`]
    /// without a sample), possibly empty, in the CSR layout the shading pass reads. Errors on
    /// invalid input and on buffers beyond the device's limits; faults on the GPU (a sample
    /// behind the camera, a bound beyond f32) and the lists' total are read after their use
    /// ([`GpuLightLists::outgrown`]).
    pub fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
    ) -> Result<GpuLightLists, GpuError> {
        let CullSizes { pixels, k, .. } = check_input(ctx, frame)?;
        if pixels == 0 {
            return no_lists(ctx);
        }
        let (width, height) = (frame.width, frame.height);
        let view = frame.view()?;
        let settings = frame.bounds_settings(GlossyBound::Ellipsoid, false);
        let bounds = self.bounds.run_with_locals(ctx, frame.vpls, &settings)?;
        // Every list id is a pixel's, which `check_input` keeps in u32.
        let tiles = tile_grid(frame, 1)?;
        let grid = Grid::new(
            u64::from(tiles.2),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let records = output::<GpuBinnedVpl>(ctx, "binned vpls", frame.vpls.capacity())?;
        let offsets = output::<u32>(ctx, "list offsets", pixels as usize + 1)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let binned = uniform(ctx, "binned params", &screen_map(frame));
        // The lists of a subregion are its pixels (subregion 0's are the most).
        let per_subregion = u64::from(width.div_ceil(k)) * u64::from(height.div_ceil(k));
        let (entries, write) =
            self.room
                .buffer(ctx, frame, "light lists", per_subregion, &status)?;
        let at = offset_of!(GpuCullParams, vpl_count);
        ctx.submit("binned cull", |encoder| {
            let partition = self.partition.encode(
                ctx,
                encoder,
                &self.scan,
                bounds.counted(),
                k * k,
                &status,
            )?;
            let params = cull_params(frame, &view, tiles, CULL_COUNT);
            let footprint_params =
                bounds
                    .count
                    .uniform(ctx, encoder, "binned footprint", &params, at);
            let workgroups = bounds
                .count
                .workgroups(ctx, encoder, &self.args, 1, WORKGROUP)?;
            ctx.encode_dispatch(
                encoder,
                "binned footprint",
                &self.footprint,
                &[
                    &footprint_params,
                    &binned,
                    &bounds.vpls,
                    &bounds.locals,
                    &records,
                ],
                workgroups,
            );
            for mode in [CULL_COUNT, CULL_WRITE] {
                let params = cull_params(frame, &view, tiles, mode);
                let params = bounds
                    .count
                    .uniform(ctx, encoder, "binned cull", &params, at);
                ctx.encode_dispatch(
                    encoder,
                    "binned cull",
                    &self.pipeline,
                    &[
                        &params,
                        &binned,
                        &frame.positions,
                        &records,
                        &partition.order,
                        &partition.sub_offsets,
                        &offsets,
                        &entries,
                        &pixel_list,
                        &status,
                    ],
                    grid,
                );
                if mode == CULL_COUNT {
                    self.scan.encode(ctx, encoder, &offsets, pixels, &status)?;
                }
            }
            Ok(())
        })?;
        Ok(GpuLightLists {
            offsets,
            indices: entries,
            pixel_list,
            list_count: pixels,
            entries: write.held,
            pixels,
            writes: vec![write],
        })
    }
}

/// The map from the image plane at unit depth to `frame`'s screen pixels, in f64 and then
/// rounded, as `slc_cull`'s `CullView::screen_map` and `Screen` form it: X = u scale + offset
/// with scale = (W/2) / (aspect tan(yfov/2)), offset = W/2 (y: H/2 / tan(yfov/2), H/2).
fn screen_map(frame: &CullFrame) -> GpuBinnedParams {
    let (w, h) = (f64::from(frame.width), f64::from(frame.height));
    let tan_half = (0.5 * f64::from(frame.camera.yfov)).tan();
    let half_extent = [w / h * tan_half, tan_half];
    GpuBinnedParams {
        screen: [
            (0.5 * w / half_extent[0]) as f32,
            (0.5 * h / half_extent[1]) as f32,
            (0.5 * w) as f32,
            (0.5 * h) as f32,
        ],
    }
}
