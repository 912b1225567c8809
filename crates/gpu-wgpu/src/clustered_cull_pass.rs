//! Clustered light culling on the GPU, the twin of `slc_cull`'s `clustered`,
//! `clustered-sphere` and `clustered-enclosing-sphere` strategies (`ClusteredCuller`; 3D
//! clusters after Olsson et al. 2012, the paper's section-7 comparison): the tiles of
//! `tiled_cull_pass` (16 x 16 pixels of each interleaved subregion image, section 6) cut
//! into 32 exponential slices of the G-buffer's depth range instead of Modified HalfZ's two.
//!
//! Per-VPL bounds (`bounds_pass`) and the subregions' VPLs (`partition_pass`) as in the tiled
//! culler, then `shaders/cluster_depth.wgsl` twice (the G-buffer's depth range, then each
//! tile's slices, their depth ranges and each pixel's slice) and `shaders/clustered_cull.wgsl`
//! twice (count and write each slice's list, with the offsets from `scan_pass` in between).
//! A slice exists where some pixel falls and is tested with the depth range of its own pixels;
//! lists ascend in the VPL index. Read back, the result is a [`LightLists`] in the CPU's
//! convention (empty lists dropped); [`ClusteredCuller::cull_on_gpu`] leaves the lists on the
//! GPU for `shade_pass` instead.
//!
//! The GPU decides in f32 what the CPU decides in f64 (view depths, slice boundaries, box
//! tests): a sample within rounding of a slice boundary may fall in the neighbouring slice.
use crate::bounds_pass::{BoundsPass, BoundsSettings};
use crate::buffers::{output, uniform, upload, Grid};
use crate::context::{GpuContext, GpuError};
use crate::cull_frame::{check_input, cull_params, read_status, tile_grid, CullFrame, CullSizes};
use crate::cull_types::{GpuClusterFrusta, CLUSTER_SLICES, DEPTH_RANGE, DEPTH_SPLIT};
use crate::gpu_lists::GpuLightLists;
use crate::gpu_lists::{no_lists, read_lists};
use crate::gpu_types::{GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::partition_pass::PartitionPass;
use crate::scan_pass::ScanPass;
use crate::tight_cull_pass::{BaseLayout, TightRefiner};
use slc_core::{CullInput, LightLists};
use slc_cull::{CullView, GlossyBound};

/// `shaders/tiles.wgsl` and `shaders/clusters.wgsl` followed by the depth-slice kernel.
pub(crate) const DEPTH_SOURCE: &str = concat!(
    include_str!("../shaders/tiles.wgsl"),
    include_str!("../shaders/clusters.wgsl"),
    include_str!("../shaders/cluster_depth.wgsl")
);

/// The tile grid, the cluster frusta, bounds and their tests followed by the culling kernel.
pub(crate) const CULL_SOURCE: &str = concat!(
    include_str!("../shaders/tiles.wgsl"),
    include_str!("../shaders/clusters.wgsl"),
    include_str!("../shaders/bound.wgsl"),
    include_str!("../shaders/frustum_tests.wgsl"),
    include_str!("../shaders/clustered_cull.wgsl")
);

/// The clustered culler's pipelines (the four clustered strategies, by the [`GlossyBound`]
/// passed to [`ClusteredCuller::cull`]).
pub struct ClusteredCuller {
    bounds: BoundsPass,
    partition: PartitionPass,
    scan: ScanPass,
    tight: TightRefiner,
    depth: wgpu::ComputePipeline,
    cull: wgpu::ComputePipeline,
}

impl ClusteredCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let bounds = BoundsPass::new(ctx)?;
        ctx.scoped("clustered culling pipelines", || {
            Ok(Self {
                bounds,
                partition: PartitionPass::new(ctx),
                scan: ScanPass::new(ctx),
                tight: TightRefiner::new(ctx),
                depth: ctx.compute_pipeline("cluster depth", DEPTH_SOURCE),
                cull: ctx.compute_pipeline("clustered cull", CULL_SOURCE),
            })
        })
    }

    /// Culls `input` with `glossy` bounds for glossy VPLs (the section-6 sphere for diffuse
    /// ones) against up to 32 depth slices per tile: `slc_cull`'s `clustered` (ellipsoid),
    /// `clustered-sphere`, `clustered-enclosing-sphere` or `clustered-tight` (each slice's
    /// list then refined per 8 x 8 block, `tight_cull_pass`). Errors on invalid input (as the
    /// CPU culler), on buffers beyond the device's limits and on device faults.
    pub fn cull(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        glossy: GlossyBound,
    ) -> Result<LightLists, GpuError> {
        read_lists(ctx, &self.cull_on_gpu(ctx, input, glossy)?)
    }

    /// [`Self::cull_frame`] of `input` with its G-buffer uploaded.
    pub fn cull_on_gpu(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        self.cull_frame(ctx, &CullFrame::upload(ctx, input)?, glossy)
    }

    /// Culls `frame` without a readback: 32 lists per tile (one per depth slice, slice s
    /// of tile t is list 32 t + s, possibly empty) left on the GPU in the CSR layout the
    /// shading pass reads, each pixel pointing to its slice's list
    /// ([`slc_core::NO_LIST`] without a sample).
    pub fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        let CullSizes {
            pixels,
            k,
            vpl_count,
        } = check_input(frame)?;
        if pixels == 0 {
            return no_lists(ctx);
        }
        let (width, height) = (frame.width, frame.height);
        let view = CullView::new(frame.camera, width, height)
            .map_err(|e| GpuError::Input(e.to_string()))?;
        let bounds = self.bounds.run(
            ctx,
            frame.vpls,
            &BoundsSettings {
                camera: frame.camera,
                width,
                height,
                delta: frame.delta,
                glossy,
                interleaving: frame.interleaving,
            },
        )?;
        let tiles = tile_grid(frame, CLUSTER_SLICES)?;
        let tile_count = tiles.2;
        let list_count = CLUSTER_SLICES * tile_count;
        let grid = Grid::new(
            u64::from(tile_count),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let params = |label, mode| uniform(ctx, label, &cull_params(frame, &view, tiles, mode));
        let positions = frame.positions.clone();
        let frusta = output::<GpuClusterFrusta>(ctx, "cluster frusta", tile_count as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let offsets = output::<u32>(ctx, "list offsets", list_count as usize + 1)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        // Smallest and largest depth as f32 bits, before any sample is seen.
        let depth_range = upload(ctx, "depth range", &[u32::MAX, 0])?;
        // Counting writes no list entry: a placeholder fills the binding.
        let no_entries = output::<u32>(ctx, "no lists", 1)?;
        let partition = ctx.submit("clustered cull (count)", |encoder| {
            let partition = self.partition.encode(
                ctx,
                encoder,
                &self.scan,
                &bounds.buffer,
                vpl_count,
                k * k,
                &status,
            )?;
            for (label, mode) in [
                ("cluster depth range", DEPTH_RANGE),
                ("cluster depth split", DEPTH_SPLIT),
            ] {
                let params = params(label, mode);
                ctx.encode_dispatch(
                    encoder,
                    label,
                    &self.depth,
                    &[
                        &params,
                        &positions,
                        &frusta,
                        &pixel_list,
                        &status,
                        &depth_range,
                    ],
                    grid,
                );
            }
            let count = params("clustered cull params (count)", CULL_COUNT);
            ctx.encode_dispatch(
                encoder,
                "clustered cull",
                &self.cull,
                &[
                    &count,
                    &frusta,
                    &bounds.buffer,
                    &offsets,
                    &no_entries,
                    &partition.sub_offsets,
                    &partition.order,
                ],
                grid,
            );
            self.scan
                .encode(ctx, encoder, &offsets, list_count, &status);
            Ok(partition)
        })?;
        let total = read_status(ctx, &status, width)?;
        let lists = output::<u32>(ctx, "light lists", total as usize)?;
        ctx.submit("clustered cull (write)", |encoder| {
            let write = params("clustered cull params (write)", CULL_WRITE);
            ctx.encode_dispatch(
                encoder,
                "clustered cull",
                &self.cull,
                &[
                    &write,
                    &frusta,
                    &bounds.buffer,
                    &offsets,
                    &lists,
                    &partition.sub_offsets,
                    &partition.order,
                ],
                grid,
            );
            Ok(())
        })?;
        let lists = GpuLightLists {
            offsets,
            indices: lists,
            pixel_list,
            list_count,
            entries: total,
            pixels,
        };
        if glossy != GlossyBound::Tight {
            return Ok(lists);
        }
        let layout = BaseLayout {
            clusters: CLUSTER_SLICES,
            split: false,
        };
        self.tight.refine(ctx, frame, lists, &bounds, layout)
    }
}
