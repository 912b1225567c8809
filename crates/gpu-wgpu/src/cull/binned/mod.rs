//! The `binned` strategy on the GPU (docs/many-vpls.md), the twin of `slc_cull`'s
//! `binned.rs`: scatter instead of gather. Per VPL, its bound (`cull::bounds`: the section-6
//! sphere or the GGX spheroid of eq. 12-15, grown by `BOUND_SLACK`, written in world axes
//! relative to the VPL as well) and the screen rectangle it may cover
//! (`binned_footprint.wesl`, `footprint.rs`'s f32 arithmetic with its conservative rounding);
//! the subregions' VPLs, ascending (`cull::partition`); per 16 x 16 tile of each interleaved
//! subregion image the box of its samples and of its strips of 16 x 2 pixels
//! (`binned_tiles.wesl`); per slice of a subregion's VPLs (`bin_slices`), those VPLs
//! handed to the tiles whose samples their rectangle overlaps and their bound may reach
//! (`binned_bins.wesl`: each tile's bin, its slices' parts in order, ascending); then per
//! tile (`binned_cull.wesl`) the VPLs of its bin, per strip those that reach its samples,
//! and per pixel the test `binned.rs`'s `PixelTest` makes: the sample x not
//! behind the VPL (eq. 4) and inside its bound. So the culling costs the VPLs, the (tile, VPL)
//! pairs they reach and the pixels their rectangles cover, not VPLs x tiles. Every pixel gets
//! its own list (list p for pixel p), ascending in the VPL index like the CPU's: the lists read
//! back equal those of the CPU's `BinnedCuller::per_pixel` (the CPU's default shares large
//! ranges per cell) up to f32 versus f64 decisions at a bound's surface (the f32 test allows
//! its rounding, which for the sharpest lobes, α = 1e-4, widens the spheroid by about 1%:
//! `binned_footprint.wesl`).
//!
//! Binning, counting, the scans (`device::scan`) and writing run in one submission, the bins
//! and the lists each into a buffer of the room earlier frames needed (`cull::room`): bins or
//! lists that outgrew it are culled again with the total their fault record reports, and a
//! total beyond the storage-binding limit is refused ([`GpuError::BufferTooLarge`], naming the
//! tile bins or the light lists).
pub mod records;

use crate::cull::bounds::BoundsPass;
use crate::cull::frame::{
    check_input, cull_params, largest_subregion, tile_grid, CullFrame, CullSizes,
};
use crate::cull::lists::{no_lists, GpuLightLists};
use crate::cull::partition::PartitionPass;
use crate::cull::records::{GpuCullParams, GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::cull::room::ListRoom;
use crate::device::buffers::{output, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::ArgsPass;
use crate::device::scan::ScanPass;
use records::{GpuBinnedParams, GpuBinnedTile, GpuBinnedVpl};
use slc_cull::GlossyBound;
use std::mem::offset_of;
use std::sync::Arc;

/// The kernel of `binned_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("binned_cull");
/// The kernel of `binned_footprint.wesl`.
pub(crate) const FOOTPRINT_SOURCE: &str = kernel!("binned_footprint");
/// The kernel of `binned_tiles.wesl`.
pub(crate) const TILES_SOURCE: &str = kernel!("binned_tiles");
/// The kernel of `binned_bins.wesl`.
pub(crate) const BINS_SOURCE: &str = kernel!("binned_bins");
/// Invocations per workgroup of the per-VPL passes.
const WORKGROUP: u32 = 64;

/// The binned strategy's pipelines and the room its bins and lists needed.
pub struct BinnedCuller {
    bounds: BoundsPass,
    partition: PartitionPass,
    scan: ScanPass,
    args: ArgsPass,
    footprint: wgpu::ComputePipeline,
    tiles: wgpu::ComputePipeline,
    bins: wgpu::ComputePipeline,
    pipeline: wgpu::ComputePipeline,
    /// What the lists of earlier frames needed.
    room: Arc<ListRoom>,
    /// What the bins (tile, VPL) of earlier frames needed.
    bin_room: Arc<ListRoom>,
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
                tiles: ctx.compute_pipeline("binned tiles", TILES_SOURCE),
                bins: ctx.compute_pipeline("binned bins", BINS_SOURCE),
                pipeline: ctx.compute_pipeline("binned cull", SOURCE),
                room: Arc::new(ListRoom::new()),
                bin_room: Arc::new(ListRoom::new()),
            })
        })
    }

    /// Sets the room of the next frames' lists (`cull::room`), and of their bins.
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
        self.bin_room.set(entries);
    }

    /// The lists of `frame` left on the GPU: one per pixel (list p of pixel p, [`slc_core::NO_LIST`]
    /// without a sample), possibly empty, in the CSR layout the shading pass reads. Errors on
    /// invalid input and on buffers beyond the device's limits; faults on the GPU (a sample
    /// behind the camera, a bound beyond f32) and the totals of the bins and the lists are
    /// read after their use ([`GpuLightLists::outgrown`]).
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
        let tiles_per_subregion = u64::from(tiles.0) * u64::from(tiles.1);
        let slices_of = |most| bin_slices(most, tiles, k * k, ctx.loop_budget);
        let most = largest_subregion(ctx, frame, |most| {
            ctx.loop_budget
                .is_none_or(|budget| bin_iterations(slices_of(most).rounds, tiles) <= budget)
        })?;
        let slices = slices_of(most);
        if ctx.loop_budget.is_some() {
            ctx.check_loop_budget(
                || {
                    format!(
                        "binning up to {most} VPLs of a subregion into its \
                         {tiles_per_subregion} tiles in {} slices",
                        slices.slices
                    )
                },
                bin_iterations(slices.rounds, tiles),
                "raise --interleave K (fewer VPLs and tiles per subregion), lower --rsm or \
                 the image size, or shade one of the --lobes",
            )?;
        }
        // Per tile, one part of its bin per slice.
        let bin_parts = tiles.2 * slices.slices;
        let capacity = frame.vpls.capacity();
        let records = output::<GpuBinnedVpl>(ctx, "binned vpls", capacity)?;
        let tile_records = output::<GpuBinnedTile>(ctx, "binned tiles", tiles.2 as usize)?;
        let stray = output::<u32>(ctx, "binned stray", 4)?;
        let bin_offsets = output::<u32>(ctx, "bin offsets", bin_parts as usize + 1)?;
        let offsets = output::<u32>(ctx, "list offsets", pixels as usize + 1)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let scratch = output::<u32>(
            ctx,
            "binned scratch",
            scratch_entries(ctx.storage_limit(), pixels),
        )?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let bin_status = upload(ctx, "bin status", &[GpuCullStatus::CLEAR])?;
        let binned = uniform(ctx, "binned params", &binned_params(frame, slices));
        // The lists of a subregion are its pixels (subregion 0's are the most).
        let per_subregion = u64::from(width.div_ceil(k)) * u64::from(height.div_ceil(k));
        let (entries, write) =
            self.room
                .buffer(ctx, frame, "light lists", per_subregion, &status)?;
        let (bins, bin_write) =
            self.bin_room
                .buffer(ctx, frame, "tile bins", tiles_per_subregion, &bin_status)?;
        let bin_groups = Grid::new(
            u64::from(k * k) * u64::from(slices.slices),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
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
            ctx.encode_dispatch_at(
                encoder,
                "binned footprint",
                &self.footprint,
                &bounds
                    .vpls
                    .with(&[&footprint_params, &binned, &bounds.locals, &records]),
                workgroups,
            );
            ctx.encode_dispatch(
                encoder,
                "binned tiles",
                &self.tiles,
                &[
                    &footprint_params,
                    &binned,
                    &frame.positions,
                    &tile_records,
                    &stray,
                    &status,
                ],
                grid,
            );
            for mode in [CULL_COUNT, CULL_WRITE] {
                let params = uniform(ctx, "binned bins", &cull_params(frame, &view, tiles, mode));
                ctx.encode_dispatch(
                    encoder,
                    "binned bins",
                    &self.bins,
                    &[
                        &params,
                        &binned,
                        &records,
                        &tile_records,
                        &stray,
                        &partition.order,
                        &partition.sub_offsets,
                        &bin_offsets,
                        &bins,
                    ],
                    bin_groups,
                );
                if mode == CULL_COUNT {
                    self.scan
                        .encode(ctx, encoder, &bin_offsets, bin_parts, &bin_status)?;
                }
            }
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
                        &bins,
                        &bin_offsets,
                        &offsets,
                        &entries,
                        &pixel_list,
                        &tile_records,
                        &scratch,
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
            // The bins first: lists made from bins that outgrew theirs are incomplete too.
            writes: vec![bin_write, write],
        })
    }
}

/// How `binned_bins.wesl` splits each subregion's VPLs: `slices` workgroups per subregion,
/// each walking `rounds` rounds of 256 VPLs (the last one the rest of its subregion's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct BinSlices {
    slices: u32,
    rounds: u64,
}

/// The slices of subregions of up to `most` VPLs on the grid `tiles` (K² = `subregions`
/// subregions): enough for [`BIN_WORKGROUPS`] workgroups in all (one workgroup per subregion
/// would be 64 at K = 8 and one at K = 1, a few of a GPU's cores), and on an adapter with a
/// loop `budget` enough for each slice's loops to keep within it, but never more than its
/// rounds nor than [`BIN_PARTS`] parts of bins in all (each slice counts its part of every
/// tile's bin; a frame whose slices cannot keep within the budget is refused by the caller).
fn bin_slices(
    most: u64,
    tiles: (u32, u32, u32),
    subregions: u32,
    budget: Option<u64>,
) -> BinSlices {
    let rounds = most.div_ceil(256).max(1);
    let most_slices = (BIN_PARTS / u64::from(tiles.2.max(1))).clamp(1, rounds);
    let wanted = BIN_WORKGROUPS.div_ceil(u64::from(subregions.max(1)));
    let needed = budget.map_or(1, |budget| {
        let fit = budget.saturating_sub(BIN_ROUND_FIXED) / bin_round_iterations(tiles);
        rounds.div_ceil(fit.max(1))
    });
    let per_slice = rounds.div_ceil(wanted.max(needed).clamp(1, most_slices));
    BinSlices {
        // No slice left empty: as few as hold the rounds.
        slices: rounds.div_ceil(per_slice) as u32,
        rounds: per_slice,
    }
}

/// Workgroups [`bin_slices`] aims for: four for each of the 132 cores of an H200, and a few
/// hundred on smaller GPUs. A choice, not measured on a GPU; on lavapipe's two threads the
/// slices cost nothing measurable (Sponza at 480x270, K = 8: docs/many-vpls.md).
const BIN_WORKGROUPS: u64 = 512;

/// The most parts of bins (tiles times slices) [`bin_slices`] makes: 16 MiB of counts.
const BIN_PARTS: u64 = 1 << 22;

/// Loop iterations of a `binned_bins.wesl` invocation outside its rounds.
const BIN_ROUND_FIXED: u64 = 64;

/// The most loop iterations an invocation of `binned_bins.wesl` runs for a slice of `rounds`
/// rounds of 256 VPLs on the grid `tiles`.
fn bin_iterations(rounds: u64, tiles: (u32, u32, u32)) -> u64 {
    rounds * bin_round_iterations(tiles) + BIN_ROUND_FIXED
}

/// The loop iterations of one round of 256 VPLs on the grid `tiles` (per subregion `tiles.0`
/// x `tiles.1`): per batch of 256 tiles, its VPL's tiles within the batch (at most 256, and a
/// row loop's own iterations), the eight words of its tile's marks and their set bits.
fn bin_round_iterations((across, down, _): (u32, u32, u32)) -> u64 {
    let per_subregion = u64::from(across) * u64::from(down);
    let batches = per_subregion.div_ceil(256);
    batches * (per_subregion.min(256) + u64::from(down) + 8 + 256 + 2)
}

/// Entries of the list kernel's scratch for `pixels` pixels: [`SCRATCH_SLOTS`] per pixel, or
/// none where that passes [`SCRATCH_BYTES`] or the storage-binding limit `binding` (then every
/// tile is tested again to write its lists; fewer slots would be slower than none, most tiles
/// outgrowing them).
fn scratch_entries(binding: u64, pixels: u32) -> usize {
    let bytes = binding.min(SCRATCH_BYTES);
    let slots = match bytes / 4 / u64::from(pixels.max(1)) >= SCRATCH_SLOTS {
        true => SCRATCH_SLOTS,
        false => 0,
    };
    (u64::from(pixels) * slots) as usize
}

/// The first entries of each pixel's list the count pass keeps (`binned_cull.wesl`): a tile
/// whose pixels' lists all fit is written by copying them, its tests not run again. On
/// Sponza's glossy VPLs at 480x270 (lavapipe) 48 made the culling 0.76-0.79 of its time at
/// RSM 512 and 0.84-0.90 at RSM 128, where 16 made it slower at RSM 512 (1.13-1.19): most
/// tiles have a pixel of more entries.
const SCRATCH_SLOTS: u64 = 48;

/// The most memory the scratch takes (960x540 fits, 1920x1080 does not).
const SCRATCH_BYTES: u64 = 128 << 20;

/// The map from the image plane at unit depth to `frame`'s screen pixels, in f64 and then
/// rounded, as `slc_cull`'s `CullView::screen_map` and `Screen` form it: X = u scale + offset
/// with scale = (W/2) / (aspect tan(yfov/2)), offset = W/2 (y: H/2 / tan(yfov/2), H/2); and
/// the bins' `slices`.
fn binned_params(frame: &CullFrame, slices: BinSlices) -> GpuBinnedParams {
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
        bins: [
            slices.slices,
            u32::try_from(slices.rounds).unwrap_or(u32::MAX),
            0,
            0,
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every VPL of a subregion of `most` lies in one of the slices' rounds, and there are no
    /// more slices than rounds.
    fn cover(slices: BinSlices, most: u64) {
        let s = u64::from(slices.slices);
        assert!(s * slices.rounds * 256 >= most, "{slices:?} for {most}");
        assert!(s <= most.div_ceil(256).max(1), "{slices:?} for {most}");
        assert!(
            (s - 1) * slices.rounds * 256 < most.max(1),
            "an empty slice: {slices:?}"
        );
    }

    /// Sponza at 480x270 with K = 1 on lavapipe's loop budget: 51,468 VPLs in 510 tiles (two
    /// batches) took 217,820 iterations in one workgroup; split, each slice keeps within the
    /// budget. With K = 8 and no budget, enough slices for [`BIN_WORKGROUPS`] workgroups.
    #[test]
    fn slices_keep_within_the_loop_budget_and_fill_the_gpu() {
        let budget = 65_535;
        let k1 = (30, 17, 510);
        assert!(bin_iterations(51_468u64.div_ceil(256), k1) > budget);
        let split = bin_slices(51_468, k1, 1, Some(budget));
        assert!(bin_iterations(split.rounds, k1) <= budget, "{split:?}");
        cover(split, 51_468);
        assert_eq!(
            split.slices, 202,
            "one slice per round, short of 512 workgroups"
        );
        let k8 = (4, 3, 768);
        for most in [0, 1, 255, 256, 257, 3_300, 13_000, 60_000] {
            let free = bin_slices(most, k8, 64, None);
            cover(free, most);
            // 512 / 64 = 8 slices wanted, fewer where there are fewer rounds or the last
            // would be empty.
            let wanted = most.div_ceil(256).clamp(1, 8);
            assert!(
                free.slices <= 8 && 2 * u64::from(free.slices) > wanted,
                "{free:?}"
            );
            cover(bin_slices(most, k8, 64, Some(budget)), most);
            cover(bin_slices(most, k1, 1, Some(budget)), most);
        }
    }

    /// Where even one round per slice passes the budget, or the slices would pass
    /// [`BIN_PARTS`], the slices are capped (the caller then refuses the frame by its loop
    /// budget), still covering every VPL.
    #[test]
    fn slices_are_capped() {
        // 1920x1080 at K = 1: 8,160 tiles, 32 batches; 3.3M VPLs.
        let grid = (120, 68, 8_160);
        let s = bin_slices(3_300_000, grid, 1, Some(65_535));
        assert!(
            u64::from(s.slices) <= BIN_PARTS / 8_160 && s.slices > 400,
            "{s:?}"
        );
        cover(s, 3_300_000);
        assert!(bin_iterations(s.rounds, grid) > 65_535);
        let huge = (4_096, 4_096, 1 << 24);
        let s = bin_slices(1 << 20, huge, 1, Some(65_535));
        assert_eq!((s.slices, s.rounds), (1, 4_096));
    }

    /// 48 entries per pixel up to 128 MiB (960x540), none beyond it or beyond the binding.
    #[test]
    fn the_scratch_holds_its_slots_or_nothing() {
        let lavapipe = 128 << 20;
        assert_eq!(scratch_entries(lavapipe, 480 * 270), 480 * 270 * 48);
        assert_eq!(scratch_entries(lavapipe, 960 * 540), 960 * 540 * 48);
        assert_eq!(scratch_entries(lavapipe, 1920 * 1080), 0);
        assert_eq!(scratch_entries(u64::MAX, 1920 * 1080), 0);
        assert_eq!(scratch_entries(1 << 20, 480 * 270), 0);
        assert_eq!(scratch_entries(lavapipe, 0), 0);
        assert_eq!(scratch_entries(lavapipe, 1), 48);
    }
}
