//! The refinement of the `tight` and `clustered-tight` strategies on the GPU
//! (`tight_cull.wesl`, the twin of `slc_cull`'s `refine.rs`; docs/tight-bounds.md):
//! the lists of a tiled culling (two Modified HalfZ clusters per tile) or a clustered one
//! (32 depth slices) with the spheroid, cut per 8 x 8 block of each tile, and in the tiled
//! layout once more at each block's own half depth, keeping a VPL only where its
//! `slc_bounds::BoxBound` (formed in f32 by `bounds.wesl`, `GpuBoxBound`) may exceed
//! ξ in the box of the group's receivers.
//!
//! Counting, a scan and writing in one submission, as the base cullers (`cull::room`: no
//! count read back; the refined lists' total is read with the base lists' after the frame);
//! the base lists' pixel entries are rewritten in place to point to the groups.
use crate::cull::bounds::{GpuBounds, BOX_BOUND_BINDINGS};
use crate::cull::frame::{cull_params, tile_grid, CullFrame};
use crate::cull::lists::GpuLightLists;
use crate::cull::records::{GpuCullParams, GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::cull::room::ListRoom;
use crate::device::buffers::{output, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::scan::ScanPass;
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;

/// The refinement of the tight strategies (`tight_cull.wesl`): the base strategy's
/// lists per tile and whether each block's samples of a list are split at their half depth.
/// Keep in sync with `TightParams` in `tight_cull.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuTightParams {
    /// Lists per tile of the base strategy: 2 (Modified HalfZ) or [`crate::cull::clustered::records::CLUSTER_SLICES`].
    pub clusters: u32,
    /// 2 where each block's samples of a list are split at their half depth, else 1.
    pub halves: u32,
    /// max |coordinate| of the eye: the boxes grow for the rounding of R (x − eye).
    pub eye_extent: f32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuTightParams>() == 16);

/// The kernel of `tight_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("tight_cull");

/// Refinement blocks per tile (2 x 2 blocks of 8 x 8 pixels: `slc_cull`'s `BLOCK`).
const BLOCKS_PER_TILE: u32 = 4;

// A block's groups are bits of one u32 in the kernel (MAX_SLOTS): the clustered layout's
// slices must fit.
const _: () = assert!(crate::cull::clustered::records::CLUSTER_SLICES <= 32);

/// The refinement's pipelines.
pub struct TightRefiner {
    scan: ScanPass,
    pipeline: wgpu::ComputePipeline,
    /// What the refined lists of earlier frames needed.
    room: Arc<ListRoom>,
}

/// How the base strategy grouped each tile's pixels.
#[derive(Clone, Copy, Debug)]
pub struct BaseLayout {
    /// Lists per tile: 2 (Modified HalfZ) or the clustered strategies' 32 slices.
    pub clusters: u32,
    /// Whether each block's samples of a list are split at their half depth.
    pub split: bool,
}

impl TightRefiner {
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            scan: ScanPass::new(ctx),
            pipeline: ctx.compute_pipeline("tight cull", SOURCE),
            room: Arc::new(ListRoom::new()),
        }
    }

    /// Sets the room of the next frames' refined lists (`cull::room`).
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
    }

    /// Refines `base`, the lists of `frame` culled with `bounds` in `layout`, left on the
    /// GPU: one list per group of a block (possibly empty), each pixel pointing to its
    /// group's. Every list is a subset of the pixel's base list, in its order.
    pub(crate) fn refine(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        base: GpuLightLists,
        bounds: &GpuBounds,
        layout: BaseLayout,
    ) -> Result<GpuLightLists, GpuError> {
        if base.pixels == 0 {
            return Ok(base);
        }
        let slots = layout.clusters * if layout.split { 2 } else { 1 };
        let tiles = tile_grid(frame, BLOCKS_PER_TILE * slots)?;
        let list_count = BLOCKS_PER_TILE * slots * tiles.2;
        let view = frame.view()?;
        let grid = Grid::new(
            u64::from(BLOCKS_PER_TILE) * u64::from(tiles.2),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let tight = uniform(
            ctx,
            "tight params",
            &GpuTightParams {
                clusters: layout.clusters,
                halves: if layout.split { 2 } else { 1 },
                eye_extent: frame.camera.position.abs().max_element(),
                pad: 0,
            },
        );
        let offsets = output::<u32>(ctx, "tight list offsets", list_count as usize + 1)?;
        let status = upload(ctx, "tight cull status", &[GpuCullStatus::CLEAR])?;
        let per_subregion =
            u64::from(BLOCKS_PER_TILE * slots) * u64::from(tiles.0) * u64::from(tiles.1);
        let (lists, write) =
            self.room
                .buffer(ctx, frame, "tight light lists", per_subregion, &status)?;
        ctx.submit("tight cull", |encoder| {
            for mode in [CULL_COUNT, CULL_WRITE] {
                let at = std::mem::offset_of!(GpuCullParams, vpl_count);
                let params = cull_params(frame, &view, tiles, mode);
                let params = bounds
                    .count
                    .uniform(ctx, encoder, "tight cull", &params, at);
                let buffers = [
                    &params,
                    &tight,
                    &frame.positions,
                    &base.pixel_list,
                    &base.offsets,
                    &base.indices,
                    &bounds.buffer,
                    &offsets,
                    &lists,
                ];
                let bindings = bounds.box_bounds.after(&buffers, BOX_BOUND_BINDINGS);
                ctx.encode_dispatch_at(encoder, "tight cull", &self.pipeline, &bindings, grid);
                if mode == CULL_COUNT {
                    self.scan
                        .encode(ctx, encoder, &offsets, list_count, &status)?;
                }
            }
            Ok(())
        })?;
        let entries = write.held;
        let mut writes = base.writes;
        writes.push(write);
        Ok(GpuLightLists {
            offsets,
            indices: lists,
            pixel_list: base.pixel_list,
            list_count,
            entries,
            pixels: base.pixels,
            writes,
        })
    }
}
