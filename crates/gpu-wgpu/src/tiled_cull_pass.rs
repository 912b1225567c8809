//! Tiled light culling on the GPU (paper sections 5-6, supplemental Listing 2): per-VPL
//! bounds (`bounds_pass`), the subregions' VPLs (`partition_pass`), Modified HalfZ tile
//! frusta (`tile_depth_pass`), then
//! `shaders/tiled_cull.wgsl` twice, counting and then writing each tile cluster's list, with
//! the offsets from `scan_pass` in between. Tiles are 16 x 16 pixels of each interleaved
//! subregion image (section 6, Fig. 8) and test only their subregion's VPLs. The result,
//! read back, is a [`LightLists`] in the CPU's convention: empty lists are dropped, every
//! list ascends in the VPL index, and each pixel with a sample points to its cluster's list.
//!
//! One count read back between the two culling dispatches sizes the list buffer exactly; a
//! total beyond the storage-binding limit is refused ([`GpuError::BufferTooLarge`]).
//! [`TiledCuller::cull_on_gpu`] leaves the lists on the GPU for `shade_pass` instead.
use crate::bounds_pass::{BoundsPass, BoundsSettings};
use crate::buffers::{output, uniform, upload, Grid};
use crate::context::{GpuContext, GpuError};
use crate::cull_frame::{check_input, cull_params, read_status, tile_grid, CullFrame, CullSizes};
use crate::gpu_lists::GpuLightLists;
use crate::gpu_lists::{no_lists, read_lists};
use crate::gpu_types::{GpuCullStatus, GpuTileFrusta, CULL_COUNT, CULL_WRITE};
use crate::partition_pass::PartitionPass;
use crate::scan_pass::ScanPass;
use crate::tight_cull_pass::{BaseLayout, TightRefiner};
use crate::tile_depth_pass::{TileDepthBuffers, TileDepthPass};
use slc_core::{CullInput, LightLists};
use slc_cull::{CullView, GlossyBound};

/// `shaders/tiles.wgsl`, `shaders/bound.wgsl` and `shaders/frustum_tests.wgsl` followed by
/// the culling kernel.
pub(crate) const SOURCE: &str = concat!(
    include_str!("../shaders/tiles.wgsl"),
    include_str!("../shaders/bound.wgsl"),
    include_str!("../shaders/frustum_tests.wgsl"),
    include_str!("../shaders/tiled_cull.wgsl")
);

/// The tiled culler's pipelines (sphere, enclosing-sphere and ellipsoid strategies, by the
/// [`GlossyBound`] passed to [`TiledCuller::cull`]).
pub struct TiledCuller {
    bounds: BoundsPass,
    partition: PartitionPass,
    depth: TileDepthPass,
    scan: ScanPass,
    tight: TightRefiner,
    pipeline: wgpu::ComputePipeline,
}

impl TiledCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let bounds = BoundsPass::new(ctx)?;
        ctx.scoped("tiled culling pipelines", || {
            Ok(Self {
                bounds,
                partition: PartitionPass::new(ctx),
                depth: TileDepthPass::new(ctx),
                scan: ScanPass::new(ctx),
                tight: TightRefiner::new(ctx),
                pipeline: ctx.compute_pipeline("tiled cull", SOURCE),
            })
        })
    }

    /// Culls `input` with `glossy` bounds for glossy VPLs (the section-6 sphere for diffuse
    /// ones) and two Modified HalfZ clusters per tile. Errors on invalid input (as the CPU
    /// culler), on buffers beyond the device's limits and on device faults.
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

    /// Culls `frame` without a readback: the lists stay on the GPU in the CSR layout the
    /// shading pass reads ([`GpuLightLists`]), two per tile (near and far cluster, possibly
    /// empty), each pixel pointing to its cluster's list ([`slc_core::NO_LIST`] without a sample).
    pub fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        let CullSizes {
            pixels, vpl_count, ..
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
        let tiles = tile_grid(frame, 2)?;
        let tile_count = tiles.2;
        let lists_count = 2 * tile_count;
        let grid = Grid::new(
            u64::from(tile_count),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let positions = frame.positions.clone();
        let frusta = output::<GpuTileFrusta>(ctx, "tile frusta", tile_count as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let offsets = output::<u32>(ctx, "list offsets", lists_count as usize + 1)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let count_params = uniform(
            ctx,
            "cull params (count)",
            &cull_params(frame, &view, tiles, CULL_COUNT),
        );
        // Counting writes no list entry: a placeholder fills the binding.
        let no_entries = output::<u32>(ctx, "no lists", 1)?;
        let k = frame.interleaving.k;
        let partition = ctx.scoped("tiled cull (count)", || {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("tiled cull (count)"),
                });
            let partition = self.partition.encode(
                ctx,
                &mut encoder,
                &self.scan,
                &bounds.buffer,
                vpl_count,
                k * k,
                &status,
            )?;
            self.depth.encode(
                ctx,
                &mut encoder,
                &TileDepthBuffers {
                    params: &count_params,
                    positions: &positions,
                    frusta: &frusta,
                    pixel_list: &pixel_list,
                    status: &status,
                    sub_offsets: &partition.sub_offsets,
                },
                grid,
            );
            self.encode_cull(
                ctx,
                &mut encoder,
                [
                    &count_params,
                    &frusta,
                    &bounds.buffer,
                    &offsets,
                    &no_entries,
                    &partition.order,
                ],
                grid,
            );
            self.scan
                .encode(ctx, &mut encoder, &offsets, lists_count, &status);
            ctx.queue.submit([encoder.finish()]);
            Ok(partition)
        })?;
        let total = read_status(ctx, &status, width)?;
        let lists = output::<u32>(ctx, "light lists", total as usize)?;
        let write_params = uniform(
            ctx,
            "cull params (write)",
            &cull_params(frame, &view, tiles, CULL_WRITE),
        );
        ctx.scoped("tiled cull (write)", || {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("tiled cull (write)"),
                });
            self.encode_cull(
                ctx,
                &mut encoder,
                [
                    &write_params,
                    &frusta,
                    &bounds.buffer,
                    &offsets,
                    &lists,
                    &partition.order,
                ],
                grid,
            );
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let lists = GpuLightLists {
            offsets,
            indices: lists,
            pixel_list,
            list_count: lists_count,
            entries: total,
            pixels,
        };
        if glossy != GlossyBound::Tight {
            return Ok(lists);
        }
        let layout = BaseLayout {
            clusters: 2,
            split: true,
        };
        self.tight.refine(ctx, frame, lists, &bounds, layout)
    }

    fn encode_cull(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        buffers: [&wgpu::Buffer; 6],
        tiles: Grid,
    ) {
        ctx.encode_dispatch(encoder, "tiled cull", &self.pipeline, &buffers, tiles);
    }
}
