//! Clustered light culling on the GPU, the twin of `slc_cull`'s `clustered`,
//! `clustered-sphere` and `clustered-enclosing-sphere` strategies (`ClusteredCuller`; 3D
//! clusters after Olsson et al. 2012, the paper's section-7 comparison): the tiles of
//! `cull::tiled` (16 x 16 pixels of each interleaved subregion image, section 6) cut
//! into 32 exponential slices of the G-buffer's depth range instead of Modified HalfZ's two.
//!
//! Per-VPL bounds (`cull::bounds`) and the subregions' VPLs (`cull::partition`) as in the tiled
//! culler, then `cluster_depth.wesl` twice (the G-buffer's depth range, then each
//! tile's slices, their depth ranges and each pixel's slice) and `clustered_cull.wesl`
//! twice (count and write each slice's list, with the offsets from `device::scan` in between).
//! A slice exists where some pixel falls and is tested with the depth range of its own pixels;
//! lists ascend in the VPL index. Read back, the result is a [`slc_core::LightLists`] in the CPU's
//! convention (empty lists dropped); [`ClusteredCuller::cull_on_gpu`] leaves the lists on the
//! GPU for `shade::lists` instead.
//!
//! The GPU decides in f32 what the CPU decides in f64 (view depths, slice boundaries, box
//! tests): a sample within rounding of a slice boundary may fall in the neighbouring slice.
pub mod records;

use crate::cull::bounds::{BoundsSettings, GpuBounds};
use crate::cull::clustered::records::{GpuClusterFrusta, CLUSTER_SLICES, DEPTH_RANGE, DEPTH_SPLIT};
use crate::cull::frame::{check_input, cull_params, tile_grid, CullFrame, CullSizes};
use crate::cull::list_passes::ListPasses;
use crate::cull::lists::no_lists;
use crate::cull::lists::GpuLightLists;
use crate::cull::partition::GpuPartition;
use crate::cull::records::{GpuCullParams, GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::cull::tight::BaseLayout;
use crate::cull::ListCulling;
use crate::device::buffers::{output, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use slc_cull::{CullView, GlossyBound};
use std::mem::offset_of;

/// The kernel of `cluster_depth.wesl`, linked with what it imports (build.rs).
pub(crate) const DEPTH_SOURCE: &str = kernel!("cluster_depth");

/// The kernel of `clustered_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const CULL_SOURCE: &str = kernel!("clustered_cull");

/// The clustered culler's pipelines (the four clustered strategies, by the [`GlossyBound`]
/// passed to [`ListCulling::cull`]).
pub struct ClusteredCuller {
    passes: ListPasses,
    depth: wgpu::ComputePipeline,
    cull: wgpu::ComputePipeline,
}

impl ClusteredCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let (passes, (depth, cull)) = ListPasses::new(ctx, "clustered culling pipelines", || {
            (
                ctx.compute_pipeline("cluster depth", DEPTH_SOURCE),
                ctx.compute_pipeline("clustered cull", CULL_SOURCE),
            )
        })?;
        Ok(Self {
            passes,
            depth,
            cull,
        })
    }

    /// The passes before the lists: per-VPL bounds (as shapes too with `shapes`, for the
    /// rasterized clusters), the subregions' VPLs, the G-buffer's depth range and each
    /// tile's occupied slices with each pixel's slice, encoded and submitted; `None` for a
    /// frame without pixels.
    pub fn prepare(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
        shapes: bool,
    ) -> Result<Option<ClusterFrame>, GpuError> {
        let CullSizes { pixels, k, .. } = check_input(frame)?;
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
        let tiles = tile_grid(frame, CLUSTER_SLICES)?;
        let grid = Grid::new(
            u64::from(tiles.2),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let params = cull_params(frame, &view, tiles, CULL_COUNT);
        let frusta = output::<GpuClusterFrusta>(ctx, "cluster frusta", tiles.2 as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        // Smallest and largest depth as f32 bits, before any sample is seen.
        let depth_range = upload(ctx, "depth range", &[u32::MAX, 0])?;
        let partition = ctx.submit("cluster depth", |encoder| {
            let partition = self.passes.partition.encode(
                ctx,
                encoder,
                &self.passes.scan,
                &bounds.buffer,
                &bounds.count,
                k * k,
                &status,
            )?;
            for (label, mode) in [
                ("cluster depth range", DEPTH_RANGE),
                ("cluster depth split", DEPTH_SPLIT),
            ] {
                let params = bounds.count.uniform(
                    ctx,
                    encoder,
                    label,
                    &GpuCullParams { mode, ..params },
                    offset_of!(GpuCullParams, vpl_count),
                );
                ctx.encode_dispatch(
                    encoder,
                    label,
                    &self.depth,
                    &[
                        &params,
                        &frame.positions,
                        &frusta,
                        &pixel_list,
                        &status,
                        &depth_range,
                    ],
                    grid,
                );
            }
            Ok(partition)
        })?;
        Ok(Some(ClusterFrame {
            bounds,
            partition,
            frusta,
            pixel_list,
            status,
            depth_range,
            params,
            grid,
            pixels,
            glossy,
        }))
    }

    /// The lists of a prepared frame, in one submission: counted per slice, scanned,
    /// written into a buffer of the room earlier frames needed (`cull::room`; the total is
    /// read with the work that uses them, [`GpuLightLists::outgrown`]); refined per block for
    /// [`GlossyBound::Tight`].
    pub fn lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        clusters: ClusterFrame,
    ) -> Result<GpuLightLists, GpuError> {
        let list_count = CLUSTER_SLICES * clusters.params.tile_count;
        let offsets = output::<u32>(ctx, "list offsets", list_count as usize + 1)?;
        let p = &clusters.params;
        let per_subregion = u64::from(CLUSTER_SLICES) * u64::from(p.tiles_x) * u64::from(p.tiles_y);
        let (entries, write) =
            self.passes
                .room
                .buffer(ctx, frame, "light lists", per_subregion, &clusters.status)?;
        ctx.submit("clustered cull", |encoder| {
            for mode in [CULL_COUNT, CULL_WRITE] {
                let params = clusters.bounds.count.uniform(
                    ctx,
                    encoder,
                    "clustered cull",
                    &GpuCullParams {
                        mode,
                        ..clusters.params
                    },
                    offset_of!(GpuCullParams, vpl_count),
                );
                ctx.encode_dispatch(
                    encoder,
                    "clustered cull",
                    &self.cull,
                    &[
                        &params,
                        &clusters.frusta,
                        &clusters.bounds.buffer,
                        &offsets,
                        &entries,
                        &clusters.partition.sub_offsets,
                        &clusters.partition.order,
                    ],
                    clusters.grid,
                );
                if mode == CULL_COUNT {
                    self.passes
                        .scan
                        .encode(ctx, encoder, &offsets, list_count, &clusters.status);
                }
            }
            Ok(())
        })?;
        let lists = GpuLightLists {
            offsets,
            indices: entries,
            pixel_list: clusters.pixel_list,
            list_count,
            entries: write.held,
            pixels: clusters.pixels,
            writes: vec![write],
        };
        if clusters.glossy != GlossyBound::Tight {
            return Ok(lists);
        }
        let layout = BaseLayout {
            clusters: CLUSTER_SLICES,
            split: false,
        };
        self.passes
            .tight
            .refine(ctx, frame, lists, &clusters.bounds, layout)
    }

    /// Sets the room of the next frames' lists (`cull::room`), the refinement's too.
    pub fn set_list_room(&self, entries: u32) {
        self.passes.set_list_room(entries);
    }
}

/// Culls with `glossy` bounds for glossy VPLs (the section-6 sphere for diffuse ones) against
/// up to 32 depth slices per tile: `slc_cull`'s `clustered` (ellipsoid), `clustered-sphere`,
/// `clustered-enclosing-sphere` or `clustered-tight` (each slice's list then refined per
/// 8 x 8 block, `cull::tight`).
impl ListCulling for ClusteredCuller {
    type Choice = GlossyBound;

    /// Culls `frame` without a readback: 32 lists per tile (one per depth slice, slice s
    /// of tile t is list 32 t + s, possibly empty) left on the GPU in the CSR layout the
    /// shading pass reads, each pixel pointing to its slice's list
    /// ([`slc_core::NO_LIST`] without a sample).
    fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        match self.prepare(ctx, frame, glossy, false)? {
            Some(clusters) => self.lists(ctx, frame, clusters),
            None => no_lists(ctx),
        }
    }
}

/// A clustered culling up to its cluster frusta ([`ClusteredCuller::prepare`]): what the
/// list passes and the rasterized clusters (`cull::raster::clusters`) read.
pub struct ClusterFrame {
    pub bounds: GpuBounds,
    pub partition: GpuPartition,
    /// `GpuClusterFrusta` per tile (occupied slices in `info.x`).
    pub frusta: wgpu::Buffer,
    /// Each pixel's cluster (32 t + slice; `NO_LIST` without a sample).
    pub pixel_list: wgpu::Buffer,
    /// The fault record of the passes so far (`GpuCullStatus`).
    pub status: wgpu::Buffer,
    /// The G-buffer's smallest and largest view depth as f32 bits.
    pub depth_range: wgpu::Buffer,
    /// The tile grid and culling view.
    pub params: GpuCullParams,
    pub grid: Grid,
    pub pixels: u32,
    pub glossy: GlossyBound,
}
