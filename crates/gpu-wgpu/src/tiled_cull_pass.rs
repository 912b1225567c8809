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
use crate::buffers::{output, read_back, uniform, upload, Grid};
use crate::context::{GpuContext, GpuError};
use crate::gbuffer_pass::GpuGBuffer;
use crate::gpu_types::{
    GpuCullParams, GpuCullStatus, GpuTileFrusta, CULL_COUNT, CULL_WRITE, FRUSTUM_SLACK, MAX_K,
};
use crate::partition_pass::PartitionPass;
use crate::scan_pass::ScanPass;
use crate::shade_pass::GpuLightLists;
use crate::tile_depth_pass::{TileDepthBuffers, TileDepthPass};
use slc_core::{Camera, CullInput, Interleaving, LightLists, Vpl, NO_LIST, TILE_SIZE};
use slc_cull::{CullView, GlossyBound};

/// `shaders/tiles.wgsl` and `shaders/bound.wgsl` followed by the culling kernel.
pub(crate) const SOURCE: &str = concat!(
    include_str!("../shaders/tiles.wgsl"),
    include_str!("../shaders/bound.wgsl"),
    include_str!("../shaders/tiled_cull.wgsl")
);

/// The tiled culler's pipelines (sphere, enclosing-sphere and ellipsoid strategies, by the
/// [`GlossyBound`] passed to [`TiledCuller::cull`]).
pub struct TiledCuller {
    bounds: BoundsPass,
    partition: PartitionPass,
    depth: TileDepthPass,
    scan: ScanPass,
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
        let gpu = self.cull_on_gpu(ctx, input, glossy)?;
        if gpu.pixels == 0 {
            return Ok(LightLists {
                offsets: vec![0],
                ..LightLists::default()
            });
        }
        let offsets: Vec<u32> = read_back(
            ctx,
            "list offsets",
            &gpu.offsets,
            gpu.list_count as usize + 1,
        )?;
        let indices: Vec<u32> = read_back(ctx, "light lists", &gpu.indices, gpu.entries as usize)?;
        let pixel_list: Vec<u32> =
            read_back(ctx, "pixel lists", &gpu.pixel_list, gpu.pixels as usize)?;
        Ok(compact(&offsets, indices, &pixel_list))
    }

    /// [`Self::cull`] without the readback: the lists stay on the GPU in the CSR layout the
    /// shading pass reads ([`GpuLightLists`]), two per tile (near and far cluster, possibly
    /// empty), each pixel pointing to its cluster's list ([`NO_LIST`] without a sample).
    pub fn cull_on_gpu(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        let g = input.gbuffer;
        let pixels = u64::from(g.width) * u64::from(g.height);
        if pixels != g.samples.len() as u64 || u32::try_from(pixels).is_err() {
            return Err(GpuError::Input(format!(
                "G-buffer of {}x{} pixels has {} samples",
                g.width,
                g.height,
                g.samples.len()
            )));
        }
        let positions: Vec<[f32; 4]> = g
            .samples
            .iter()
            .map(|s| {
                s.as_ref()
                    .map_or([0.0; 4], |s| s.position.extend(1.0).to_array())
            })
            .collect();
        let positions = upload(ctx, "gbuffer positions", &positions)?;
        self.cull_positions(
            ctx,
            &positions,
            &Frame {
                width: g.width,
                height: g.height,
                camera: input.camera,
                vpls: input.vpls,
                delta: input.delta,
                interleaving: input.interleaving,
            },
            glossy,
        )
    }

    /// [`Self::cull_on_gpu`] for a G-buffer rendered on the GPU
    /// ([`crate::gbuffer_pass::GbufferPass`]), read where it lies (its camera is the
    /// culling view).
    pub fn cull_gpu_gbuffer(
        &self,
        ctx: &GpuContext,
        gbuffer: &GpuGBuffer,
        vpls: &[Vpl],
        delta: f32,
        interleaving: Interleaving,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        self.cull_positions(
            ctx,
            &gbuffer.positions,
            &Frame {
                width: gbuffer.width,
                height: gbuffer.height,
                camera: &gbuffer.camera,
                vpls,
                delta,
                interleaving,
            },
            glossy,
        )
    }

    /// Culls with the G-buffer positions already on the GPU (`[x, y, z, 1]`, zero where a
    /// pixel has no sample).
    fn cull_positions(
        &self,
        ctx: &GpuContext,
        positions: &wgpu::Buffer,
        input: &Frame,
        glossy: GlossyBound,
    ) -> Result<GpuLightLists, GpuError> {
        let (width, height) = (input.width, input.height);
        let pixels = u64::from(width) * u64::from(height);
        let k = input.interleaving.k;
        if !(1..=MAX_K).contains(&k) {
            return Err(GpuError::Input(format!(
                "interleaving factor K = {k} must lie in 1..={MAX_K}"
            )));
        }
        let vpl_count = u32::try_from(input.vpls.len())
            .map_err(|_| GpuError::Input(format!("{} VPLs exceed u32", input.vpls.len())))?;
        if pixels == 0 {
            return Ok(GpuLightLists {
                offsets: output::<u32>(ctx, "list offsets", 1)?,
                indices: output::<u32>(ctx, "light lists", 0)?,
                pixel_list: output::<u32>(ctx, "pixel lists", 0)?,
                list_count: 0,
                entries: 0,
                pixels: 0,
            });
        }
        let view = CullView::new(input.camera, width, height)
            .map_err(|e| GpuError::Input(e.to_string()))?;
        let bounds = self.bounds.run(
            ctx,
            input.vpls,
            &BoundsSettings {
                camera: input.camera,
                width,
                height,
                delta: input.delta,
                glossy,
                interleaving: input.interleaving,
            },
        )?;
        // The uniform per-subregion tile grid, sized for subregion 0 (the largest).
        let tiles_x = width.div_ceil(k).div_ceil(TILE_SIZE);
        let tiles_y = height.div_ceil(k).div_ceil(TILE_SIZE);
        let tile_count = u64::from(k * k) * u64::from(tiles_x) * u64::from(tiles_y);
        let lists_count = 2 * tile_count;
        let tile_count = u32::try_from(tile_count)
            .ok()
            .filter(|_| u32::try_from(lists_count + 1).is_ok())
            .ok_or_else(|| GpuError::Input(format!("{tile_count} tiles exceed u32 list ids")))?;
        let grid = Grid::new(
            u64::from(tile_count),
            ctx.limits.max_compute_workgroups_per_dimension,
        )?;
        let r = view.rotation();
        let tan_half = (0.5 * f64::from(input.camera.yfov)).tan();
        let aspect = f64::from(width) / f64::from(height);
        let params = |mode| GpuCullParams {
            rotation: [
                r.x_axis.extend(0.0).to_array(),
                r.y_axis.extend(0.0).to_array(),
                r.z_axis.extend(0.0).to_array(),
            ],
            eye: input.camera.position.extend(0.0).to_array(),
            image: [
                (aspect * tan_half) as f32,
                tan_half as f32,
                width as f32,
                height as f32,
            ],
            width,
            height,
            k,
            tiles_x,
            tiles_y,
            tile_count,
            vpl_count,
            frustum_slack: FRUSTUM_SLACK,
            mode,
            pad: [0; 3],
        };
        let frusta = output::<GpuTileFrusta>(ctx, "tile frusta", tile_count as usize)?;
        let pixel_list = output::<u32>(ctx, "pixel lists", pixels as usize)?;
        let offsets = output::<u32>(ctx, "list offsets", lists_count as usize + 1)?;
        let status = upload(ctx, "cull status", &[GpuCullStatus::CLEAR])?;
        let count_params = uniform(ctx, "cull params (count)", &params(CULL_COUNT));
        // Counting writes no list entry: a placeholder fills the binding.
        let no_lists = output::<u32>(ctx, "no lists", 1)?;
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
                    positions,
                    frusta: &frusta,
                    pixel_list: &pixel_list,
                    status: &status,
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
                    &no_lists,
                    &partition.sub_offsets,
                    &partition.order,
                ],
                grid,
            );
            self.scan
                .encode(ctx, &mut encoder, &offsets, lists_count as u32, &status);
            ctx.queue.submit([encoder.finish()]);
            Ok(partition)
        })?;
        let [state] = <[GpuCullStatus; 1]>::try_from(read_back(ctx, "cull status", &status, 1)?)
            .map_err(|_| GpuError::Readback {
                label: "cull status".into(),
                message: "short read".into(),
            })?;
        if state.bad_pixel != u32::MAX {
            return Err(GpuError::Input(format!(
                "G-buffer sample of pixel ({}, {}) is not in front of the camera",
                state.bad_pixel % width,
                state.bad_pixel / width
            )));
        }
        if state.overflow_vpl != u32::MAX {
            return Err(GpuError::Input(format!(
                "the bound of VPL {} does not fit in f32 (extreme flux, delta or xi)",
                state.overflow_vpl
            )));
        }
        if state.total_overflow != 0 {
            return Err(GpuError::Input(
                "light-list entries exceed 32-bit offsets".into(),
            ));
        }
        let total = state.total as usize;
        let lists = output::<u32>(ctx, "light lists", total)?;
        let write_params = uniform(ctx, "cull params (write)", &params(CULL_WRITE));
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
                    &partition.sub_offsets,
                    &partition.order,
                ],
                grid,
            );
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        Ok(GpuLightLists {
            offsets,
            indices: lists,
            pixel_list,
            list_count: lists_count as u32,
            entries: state.total,
            pixels: pixels as u32,
        })
    }

    fn encode_cull(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        buffers: [&wgpu::Buffer; 7],
        tiles: Grid,
    ) {
        ctx.encode_dispatch(encoder, "tiled cull", &self.pipeline, &buffers, tiles);
    }
}

/// What culling needs besides the G-buffer positions.
struct Frame<'a> {
    width: u32,
    height: u32,
    camera: &'a Camera,
    vpls: &'a [Vpl],
    delta: f32,
    interleaving: Interleaving,
}

/// [`LightLists`] from the GPU's fixed two lists per tile: empty lists are dropped (their
/// pixels get `NO_LIST`, as on the CPU) and the rest renumbered in order.
fn compact(offsets: &[u32], indices: Vec<u32>, pixel_list: &[u32]) -> LightLists {
    let mut renumber = vec![NO_LIST; offsets.len().saturating_sub(1)];
    let mut kept = vec![0u32];
    for (l, pair) in offsets.windows(2).enumerate() {
        if pair[1] > pair[0] {
            renumber[l] = (kept.len() - 1) as u32;
            kept.push(pair[1]);
        }
    }
    LightLists {
        offsets: kept,
        indices,
        pixel_list: pixel_list
            .iter()
            .map(|&l| renumber.get(l as usize).copied().unwrap_or(NO_LIST))
            .collect(),
    }
}
