//! The passes every list culler of a tile grid runs besides its own kernels (the tiled and
//! the clustered layout): per-VPL bounds, the subregions' VPLs, the scan of list offsets, the
//! tight refinement, and the room the lists of earlier frames needed. A layout brings its
//! depth pass (what decides each pixel's list) and its list kernel; [`TileLayout::prepare`]
//! and [`TileLayout::lists`] run the rest around them.
use crate::cull::bounds::{BoundsPass, GpuBounds};
use crate::cull::frame::{check_input, cull_params, tile_grid, CullFrame, CullSizes};
use crate::cull::lists::{no_lists, GpuLightLists};
use crate::cull::partition::{GpuPartition, PartitionPass};
use crate::cull::records::{GpuCullParams, GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::cull::room::ListRoom;
use crate::cull::tight::{BaseLayout, TightRefiner};
use crate::cull::ListCulling;
use crate::device::buffers::{output, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::scan::ScanPass;
use slc_cull::GlossyBound;
use std::mem::offset_of;
use std::sync::Arc;

/// A layout of lists on the tile grid (Modified HalfZ's two clusters per tile, the clustered
/// strategies' depth slices): its depth pass, which decides each tile's frusta and each
/// pixel's list, and its list kernel; [`ListPasses`] runs the rest around them.
/// [`ListCulling`] comes with it.
pub trait TileLayout {
    /// A frame culled up to its lists.
    type Prepared;
    /// The record per tile the depth pass writes.
    type Frusta: bytemuck::Pod;
    /// The depth pass's label, and the lists per tile.
    const DEPTH: (&'static str, u32);

    /// The passes this layout shares with the others.
    fn passes(&self) -> &ListPasses;

    /// Encodes the depth pass after the shared passes of `tiles`: each tile's frusta and
    /// each pixel's list.
    fn encode_depth(
        &self,
        on: DepthEncoder,
        tiles: PreparedTiles,
    ) -> Result<Self::Prepared, GpuError>;

    /// The list kernel of a prepared frame.
    fn kernel<'a>(&'a self, prepared: &'a Self::Prepared) -> ListKernel<'a>;

    /// The passes before the lists, encoded and submitted: per-VPL bounds (as shapes too
    /// with `shapes`, for the raster baselines' meshes), the subregions' VPLs, then the depth
    /// pass. `None` for a frame without pixels. Errors on invalid input and on buffers beyond
    /// the device's limits; faults on the GPU are read with the lists or the shaded image.
    fn prepare(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
        shapes: bool,
    ) -> Result<Option<Self::Prepared>, GpuError> {
        self.passes().prepare::<Self::Frusta, _>(
            ctx,
            frame,
            (glossy, shapes),
            Self::DEPTH,
            |encoder, tiles| {
                self.encode_depth(
                    DepthEncoder {
                        ctx,
                        frame,
                        encoder,
                    },
                    tiles,
                )
            },
        )
    }

    /// The lists of a prepared frame, counted and written by the layout's kernel; with
    /// [`GlossyBound::Tight`] refined per block, which rewrites the frame's pixel lists in
    /// place (`prepared` is spent then).
    fn lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        prepared: &Self::Prepared,
    ) -> Result<GpuLightLists, GpuError> {
        self.passes().lists(ctx, frame, self.kernel(prepared))
    }

    /// Sets the room of the next frames' lists (`cull::room`), the refinement's too.
    fn set_list_room(&self, entries: u32) {
        self.passes().set_list_room(entries);
    }
}

/// Where a layout's depth pass is encoded: the submission of the shared passes.
pub struct DepthEncoder<'a, 'f> {
    pub ctx: &'a GpuContext,
    pub frame: &'a CullFrame<'f>,
    pub encoder: &'a mut wgpu::CommandEncoder,
}

/// Culls with `glossy` bounds for glossy VPLs (the section-6 sphere for diffuse ones) into
/// the layout's lists, left on the GPU in the CSR layout the shading pass reads, each pixel
/// pointing to its list ([`slc_core::NO_LIST`] without a sample); empty lists are kept.
impl<T: TileLayout> ListCulling for T {
    type Choice = GlossyBound;

    fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        match self.prepare(ctx, frame, glossy, false)? {
            Some(prepared) => self.lists(ctx, frame, &prepared),
            None => no_lists(ctx),
        }
    }
}

/// The passes a list culler shares with the other layouts.
pub struct ListPasses {
    pub bounds: BoundsPass,
    pub partition: PartitionPass,
    pub scan: ScanPass,
    pub tight: TightRefiner,
    /// What the lists of earlier frames needed.
    pub room: Arc<ListRoom>,
}

/// A culling on a tile grid up to its frusta ([`TileLayout::prepare`]): what the list passes
/// ([`TileLayout::lists`]), the one-pass shading (`shade::tiled`) and the raster baselines read.
pub struct PreparedTiles {
    pub bounds: GpuBounds,
    /// The subregions' VPLs in ascending order (`cull::partition`).
    pub partition: GpuPartition,
    /// The layout's frusta record per tile (`GpuTileFrusta` or `GpuClusterFrusta`).
    pub frusta: wgpu::Buffer,
    /// Each pixel's list (a tile's cluster or slice; `NO_LIST` without a sample).
    pub pixel_list: wgpu::Buffer,
    /// The fault record of the passes so far (`GpuCullStatus`).
    pub status: wgpu::Buffer,
    /// The tile grid and culling view.
    pub params: GpuCullParams,
    pub grid: Grid,
    pub pixels: u32,
    pub glossy: GlossyBound,
}

/// A layout's list kernel: counts, then writes each list of a tile grid, reading
/// `params, frusta, bounds, offsets, entries` and then `own`, the layout's own buffers.
pub struct ListKernel<'a> {
    pub label: &'static str,
    pub pipeline: &'a wgpu::ComputePipeline,
    pub layout: BaseLayout,
    pub tiles: &'a PreparedTiles,
    pub own: Vec<&'a wgpu::Buffer>,
}

impl ListPasses {
    /// The pipelines, made within `ctx`'s error scope named `what`, with `own` (the layout's
    /// own pipelines) made in the same scope.
    pub fn new<T>(
        ctx: &GpuContext,
        what: &'static str,
        own: impl FnOnce() -> T,
    ) -> Result<(Self, T), GpuError> {
        let bounds = BoundsPass::new(ctx)?;
        ctx.scoped(what, || {
            Ok((
                Self {
                    bounds,
                    partition: PartitionPass::new(ctx),
                    scan: ScanPass::new(ctx),
                    tight: TightRefiner::new(ctx),
                    room: Arc::new(ListRoom::new()),
                },
                own(),
            ))
        })
    }

    /// The passes before the lists, encoded and submitted as `label`: per-VPL bounds (as
    /// shapes too with `shapes`, for the raster baselines), the subregions' VPLs, then
    /// `depth` (the layout's frusta of `F` per tile and each pixel's list, `lists_per_tile`
    /// of them). `None` for a frame without pixels.
    fn prepare<F: bytemuck::Pod, P>(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        (glossy, shapes): (GlossyBound, bool),
        (label, lists_per_tile): (&'static str, u32),
        depth: impl FnOnce(&mut wgpu::CommandEncoder, PreparedTiles) -> Result<P, GpuError>,
    ) -> Result<Option<P>, GpuError> {
        let CullSizes { pixels, k, .. } = check_input(ctx, frame)?;
        if pixels == 0 {
            return Ok(None);
        }
        let view = frame.view()?;
        let settings = frame.bounds_settings(glossy, shapes);
        let bounds = self.bounds.run(ctx, frame.vpls, &settings)?;
        let tiles = tile_grid(frame, lists_per_tile)?;
        let grid = Grid::new(
            u64::from(tiles.2),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let frusta = output::<F>(ctx, "tile frusta", tiles.2 as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let params = cull_params(frame, &view, tiles, CULL_COUNT);
        ctx.submit(label, |encoder| {
            let partition = self.partition.encode(
                ctx,
                encoder,
                &self.scan,
                bounds.counted(),
                k * k,
                &status,
            )?;
            let prepared = PreparedTiles {
                bounds,
                partition,
                frusta,
                pixel_list,
                status,
                params,
                grid,
                pixels,
                glossy,
            };
            depth(encoder, prepared).map(Some)
        })
    }

    /// The lists of a prepared frame, in one submission: counted per list by `kernel`,
    /// scanned, written into a buffer of the room
    /// earlier frames needed (`cull::room`; the total is read with the work that uses them,
    /// [`GpuLightLists::outgrown`]); refined per block for [`GlossyBound::Tight`]
    /// (`cull::tight`, which rewrites the pixel lists in place).
    fn lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        kernel: ListKernel,
    ) -> Result<GpuLightLists, GpuError> {
        let tiles = kernel.tiles;
        let per_tile = kernel.layout.clusters;
        let list_count = per_tile * tiles.params.tile_count;
        let offsets = output::<u32>(ctx, "list offsets", list_count as usize + 1)?;
        let p = &tiles.params;
        let per_subregion = u64::from(per_tile) * u64::from(p.tiles_x) * u64::from(p.tiles_y);
        let (entries, write) =
            self.room
                .buffer(ctx, frame, "light lists", per_subregion, &tiles.status)?;
        ctx.submit(kernel.label, |encoder| {
            for mode in [CULL_COUNT, CULL_WRITE] {
                let params = tiles.bounds.count.uniform(
                    ctx,
                    encoder,
                    kernel.label,
                    &GpuCullParams {
                        mode,
                        ..tiles.params
                    },
                    offset_of!(GpuCullParams, vpl_count),
                );
                let shared = [
                    &params,
                    &tiles.frusta,
                    &tiles.bounds.buffer,
                    &offsets,
                    &entries,
                ];
                let buffers: Vec<_> = shared
                    .into_iter()
                    .chain(kernel.own.iter().copied())
                    .collect();
                ctx.encode_dispatch(encoder, kernel.label, kernel.pipeline, &buffers, tiles.grid);
                if mode == CULL_COUNT {
                    self.scan
                        .encode(ctx, encoder, &offsets, list_count, &tiles.status)?;
                }
            }
            Ok(())
        })?;
        let lists = GpuLightLists {
            offsets,
            indices: entries,
            pixel_list: tiles.pixel_list.clone(),
            list_count,
            entries: write.held,
            pixels: tiles.pixels,
            writes: vec![write],
        };
        if tiles.glossy != GlossyBound::Tight {
            return Ok(lists);
        }
        self.tight
            .refine(ctx, frame, lists, &tiles.bounds, kernel.layout)
    }

    /// Sets the room of the next frames' lists (`cull::room`), the refinement's too.
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
        self.tight.set_list_room(entries);
    }
}
