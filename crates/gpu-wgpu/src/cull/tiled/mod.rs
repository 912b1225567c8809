//! Tiled light culling on the GPU (paper sections 5-6, supplemental Listing 2): per-VPL
//! bounds (`cull::bounds`), the subregions' VPLs (`cull::partition`), Modified HalfZ tile
//! frusta (`cull::tiled::depth`), then
//! `tiled_cull.wesl` twice, counting and then writing each tile cluster's list, with
//! the offsets from `device::scan` in between. Tiles are 16 x 16 pixels of each interleaved
//! subregion image (section 6, Fig. 8) and test only their subregion's VPLs. The result,
//! read back, is a [`slc_core::LightLists`] in the CPU's convention: empty lists are dropped, every
//! list ascends in the VPL index, and each pixel with a sample points to its cluster's list.
//!
//! Counting and writing run in one submission, into a buffer of the room earlier frames'
//! lists needed (`cull::room`): no count is read back inside a frame; lists that outgrew
//! their buffer are culled again with the total their fault record reports. A total beyond
//! the storage-binding limit is refused ([`GpuError::BufferTooLarge`]).
//! [`ListCulling::cull_on_gpu`] leaves the lists on the GPU for `shade::lists` instead;
//! [`TiledCuller::prepare`] stops before the lists, for the one-pass culling and shading of
//! `shade::tiled`, and [`TiledCuller::lists`] builds them from there. With
//! [`GlossyBound::Tight`] the lists are refined per block (`cull::tight`).
pub mod depth;

use crate::cull::bounds::{BoundsSettings, GpuBounds};
use crate::cull::frame::{check_input, cull_params, tile_grid, CullFrame, CullSizes};
use crate::cull::list_passes::ListPasses;
use crate::cull::lists::no_lists;
use crate::cull::lists::GpuLightLists;
use crate::cull::records::{GpuCullParams, GpuCullStatus, GpuTileFrusta, CULL_COUNT, CULL_WRITE};
use crate::cull::tight::BaseLayout;
use crate::cull::tiled::depth::{TileDepthBuffers, TileDepthPass};
use crate::cull::ListCulling;
use crate::device::buffers::{output, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use slc_cull::{CullView, GlossyBound};
use std::mem::offset_of;

/// The kernel of `tiled_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("tiled_cull");

/// The tiled culler's pipelines (sphere, enclosing-sphere, ellipsoid and tight strategies,
/// by the [`GlossyBound`] passed to [`ListCulling::cull`]).
pub struct TiledCuller {
    passes: ListPasses,
    depth: TileDepthPass,
    pipeline: wgpu::ComputePipeline,
}

impl TiledCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let (passes, (depth, pipeline)) = ListPasses::new(ctx, "tiled culling pipelines", || {
            (
                TileDepthPass::new(ctx),
                ctx.compute_pipeline("tiled cull", SOURCE),
            )
        })?;
        Ok(Self {
            passes,
            depth,
            pipeline,
        })
    }

    /// The passes before the lists: per-VPL bounds, the subregions' VPLs and the Modified
    /// HalfZ frusta of every tile (with each pixel's cluster), encoded and submitted; `None`
    /// for a frame without pixels. With `shapes` the bounds are written as shapes too (for
    /// splatting's meshes). Errors on invalid input and on buffers beyond the device's
    /// limits; faults on the GPU are read with the lists or the shaded image.
    pub fn prepare(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
        shapes: bool,
    ) -> Result<Option<TiledFrame>, GpuError> {
        let CullSizes { pixels, .. } = check_input(frame)?;
        if pixels == 0 {
            return Ok(None);
        }
        let (width, height) = (frame.width, frame.height);
        let view = CullView::new(frame.camera, width, height)
            .map_err(|e| GpuError::Input(e.to_string()))?;
        let bounds = self.passes.bounds.run(
            ctx,
            frame.vpls,
            &BoundsSettings {
                camera: frame.camera,
                width,
                height,
                delta: frame.delta,
                glossy,
                interleaving: frame.interleaving,
                shapes,
            },
        )?;
        let tiles = tile_grid(frame, 2)?;
        let grid = Grid::new(
            u64::from(tiles.2),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let frusta = output::<GpuTileFrusta>(ctx, "tile frusta", tiles.2 as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let params = cull_params(frame, &view, tiles, CULL_COUNT);
        let k = frame.interleaving.k;
        let partition = ctx.submit("tile depth", |encoder| {
            let partition = self.passes.partition.encode(
                ctx,
                encoder,
                &self.passes.scan,
                &bounds.buffer,
                &bounds.count,
                k * k,
                &status,
            )?;
            let depth_params = bounds.count.uniform(
                ctx,
                encoder,
                "cull params (depth)",
                &params,
                offset_of!(GpuCullParams, vpl_count),
            );
            self.depth.encode(
                ctx,
                encoder,
                &TileDepthBuffers {
                    params: &depth_params,
                    positions: &frame.positions,
                    frusta: &frusta,
                    pixel_list: &pixel_list,
                    status: &status,
                    sub_offsets: &partition.sub_offsets,
                },
                grid,
            );
            Ok(partition)
        })?;
        Ok(Some(TiledFrame {
            bounds,
            order: partition.order,
            sub_offsets: partition.sub_offsets,
            frusta,
            pixel_list,
            status,
            params,
            grid,
            pixels,
            glossy,
        }))
    }

    /// The lists of a prepared frame, in one submission: counted per cluster, scanned,
    /// written into a buffer of the room earlier frames needed (`cull::room`; the total is
    /// read with the work that uses them, [`GpuLightLists::outgrown`]); refined per block for
    /// [`GlossyBound::Tight`] (which rewrites the frame's pixel lists in place: `tiles` is
    /// spent then).
    pub fn lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        tiles: &TiledFrame,
    ) -> Result<GpuLightLists, GpuError> {
        let lists_count = 2 * tiles.params.tile_count;
        let offsets = output::<u32>(ctx, "list offsets", lists_count as usize + 1)?;
        let p = &tiles.params;
        let per_subregion = 2 * u64::from(p.tiles_x) * u64::from(p.tiles_y);
        let (entries, write) =
            self.passes
                .room
                .buffer(ctx, frame, "light lists", per_subregion, &tiles.status)?;
        ctx.submit("tiled cull", |encoder| {
            for mode in [CULL_COUNT, CULL_WRITE] {
                let params = tiles.bounds.count.uniform(
                    ctx,
                    encoder,
                    "tiled cull",
                    &GpuCullParams {
                        mode,
                        ..tiles.params
                    },
                    offset_of!(GpuCullParams, vpl_count),
                );
                ctx.encode_dispatch(
                    encoder,
                    "tiled cull",
                    &self.pipeline,
                    &[
                        &params,
                        &tiles.frusta,
                        &tiles.bounds.buffer,
                        &offsets,
                        &entries,
                        &tiles.order,
                    ],
                    tiles.grid,
                );
                if mode == CULL_COUNT {
                    self.passes
                        .scan
                        .encode(ctx, encoder, &offsets, lists_count, &tiles.status);
                }
            }
            Ok(())
        })?;
        let lists = GpuLightLists {
            offsets,
            indices: entries,
            pixel_list: tiles.pixel_list.clone(),
            list_count: lists_count,
            entries: write.held,
            pixels: tiles.pixels,
            writes: vec![write],
        };
        if tiles.glossy != GlossyBound::Tight {
            return Ok(lists);
        }
        let layout = BaseLayout {
            clusters: 2,
            split: true,
        };
        self.passes
            .tight
            .refine(ctx, frame, lists, &tiles.bounds, layout)
    }

    /// Sets the room of the next frames' lists (`cull::room`), the refinement's too.
    pub fn set_list_room(&self, entries: u32) {
        self.passes.set_list_room(entries);
    }
}

/// Culls with `glossy` bounds for glossy VPLs (the section-6 sphere for diffuse ones) and two
/// Modified HalfZ clusters per tile (with [`GlossyBound::Tight`], their groups per 8 x 8
/// block, `cull::tight`).
impl ListCulling for TiledCuller {
    type Choice = GlossyBound;

    /// Culls `frame` without reading the lists back: they stay on the GPU in the CSR layout
    /// the shading pass reads ([`GpuLightLists`]), two per tile (near and far cluster,
    /// possibly empty), each pixel pointing to its cluster's list ([`slc_core::NO_LIST`]
    /// without a sample). With [`GlossyBound::Tight`] each list is then refined per block
    /// (`cull::tight`).
    fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        match self.prepare(ctx, frame, glossy, false)? {
            Some(tiles) => self.lists(ctx, frame, &tiles),
            None => no_lists(ctx),
        }
    }
}

/// A tiled culling up to its frusta ([`TiledCuller::prepare`]): what the list passes
/// ([`TiledCuller::lists`]) and the one-pass shading (`shade::tiled`) read.
pub struct TiledFrame {
    pub bounds: GpuBounds,
    /// The subregions' VPLs in ascending order (`cull::partition`); each tile's range is in
    /// its frusta.
    pub order: wgpu::Buffer,
    /// Subregion s's VPLs are `order[sub_offsets[s]..sub_offsets[s + 1]]`.
    pub sub_offsets: wgpu::Buffer,
    /// `GpuTileFrusta` per tile.
    pub frusta: wgpu::Buffer,
    /// Each pixel's cluster list (2 t + 0 near, 2 t + 1 far; `NO_LIST` without a sample).
    pub pixel_list: wgpu::Buffer,
    /// The fault record of the passes so far (`GpuCullStatus`).
    pub status: wgpu::Buffer,
    /// The tile grid and culling view.
    pub params: GpuCullParams,
    pub grid: Grid,
    pub pixels: u32,
    pub glossy: GlossyBound,
}
