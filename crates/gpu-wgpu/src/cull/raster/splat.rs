//! Splatting \[DS06\], the paper's Table 2 baseline (`--culling splatting`): after the tiled
//! culler's bounds (written as shapes too), partition and tile depth passes
//! ([`TiledCuller::prepare`](crate::cull::list_passes::TileLayout::prepare), which also check
//! the G-buffer), each VPL's bounding mesh (80 triangles around its spheroid or sphere,
//! `cull::raster::mesh`) is drawn into its interleaved subregion's viewport of a deinterleaved atlas,
//! one indirect draw per subregion sized on the GPU (`cull::raster`), back faces only and
//! without depth test: each pixel whose sample's ray meets the mesh evaluates the VPL once,
//! and the blend adds the contributions in f32 (`splat.wesl`). No list exists; a
//! pass puts the atlas back in screen order (`splat_resolve.wesl`).
//!
//! The blend needs `Features::FLOAT32_BLENDABLE` (lavapipe has it): the renderer offers
//! the raster baselines only with it, and [`Splatter::shade`] without it is an error. The sums' order is the rasterizer's, so images
//! equal the list shading's up to f32 rounding. For the metrics, the same draws append each
//! covered pixel's VPL to a per-pixel list in a node buffer (`cull::raster::nodes`).
use crate::cull::frame::{read_status, CullFrame};
use crate::cull::list_passes::PreparedTiles;
use crate::cull::lists::GpuLightLists;
use crate::cull::raster::mesh::BoundMesh;
use crate::cull::raster::nodes::NodeLists;
use crate::cull::raster::records::GpuRasterParams;
use crate::cull::raster::{atlas, bind, render_pipeline, Rasterization, SubregionDraws};
use crate::cull::records::GpuCullStatus;
use crate::cull::room::ListRoom;
use crate::device::buffers::{output, upload};
use crate::device::context::{GpuContext, GpuError};
use crate::vpl::buffers::VPL_BINDINGS;
use slc_core::Interleaving;
use std::mem::offset_of;

/// The bounding meshes' back faces only: each pixel's ray meets a mesh's back face once.
const FRONT_CULLED: Rasterization = Rasterization {
    cull_mode: Some(wgpu::Face::Front),
    ..Rasterization::PLAIN
};

/// The kernel of `splat.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("splat");

/// The kernel of `splat_resolve.wesl`, linked with what it imports (build.rs).
pub(crate) const RESOLVE_SOURCE: &str = kernel!("splat_resolve");

/// The atlas's format: RGB sums in f32.
const ATLAS: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The splatting pipelines.
pub struct Splatter {
    mesh: wgpu::Buffer,
    mesh_vertices: u32,
    draws: SubregionDraws,
    /// `None` on an adapter that cannot blend f32 targets.
    shade: Option<wgpu::RenderPipeline>,
    list: wgpu::RenderPipeline,
    resolve: wgpu::ComputePipeline,
    /// The largest node count seen: the next metrics frame's buffer.
    room: ListRoom,
}

impl Splatter {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let mesh = BoundMesh::icosphere(1);
        let blendable = ctx
            .device
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE);
        let add = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        ctx.scoped("splat pipelines", || {
            Ok(Self {
                mesh: mesh.upload(ctx)?,
                mesh_vertices: 3 * mesh.triangle_count(),
                draws: SubregionDraws::new(ctx),
                shade: blendable.then(|| {
                    let target = wgpu::ColorTargetState {
                        format: ATLAS,
                        blend: Some(wgpu::BlendState {
                            color: add,
                            alpha: add,
                        }),
                        write_mask: wgpu::ColorWrites::ALL,
                    };
                    render_pipeline(ctx, "splat", SOURCE, "fs_shade", target, FRONT_CULLED)
                }),
                list: render_pipeline(
                    ctx,
                    "splat lists",
                    SOURCE,
                    "fs_list",
                    wgpu::ColorTargetState {
                        format: ATLAS,
                        blend: None,
                        write_mask: wgpu::ColorWrites::empty(),
                    },
                    FRONT_CULLED,
                ),
                resolve: ctx.compute_pipeline("splat resolve", RESOLVE_SOURCE),
                room: ListRoom::new(),
            })
        })
    }

    fn params(&self, frame: &CullFrame, tiles: &PreparedTiles, capacity: u32) -> GpuRasterParams {
        let k = frame.interleaving.k;
        let (ox, oy) = frame.sample_offset;
        GpuRasterParams {
            image: tiles.params.image,
            shift: [0.5 - ox / k as f32, 0.5 - oy / k as f32],
            cell: k as f32,
            delta: frame.delta,
            width: frame.width,
            height: frame.height,
            k,
            mesh_vertices: self.mesh_vertices,
            view_w: frame.width.div_ceil(k),
            view_h: frame.height.div_ceil(k),
            capacity,
            scale: frame.interleaving.scale(),
            tiles_x: tiles.params.tiles_x,
            tiles_y: tiles.params.tiles_y,
            vpl_count: tiles.bounds.count.capacity(),
            pad: 0,
        }
    }

    /// Records the draws of `pipeline` for `tiles` into a fresh atlas, returned.
    fn draw(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        (params, params_buffer): (&GpuRasterParams, &wgpu::Buffer),
        tiles: &PreparedTiles,
        pipeline: &wgpu::RenderPipeline,
        bind: &wgpu::BindGroup,
    ) -> Result<wgpu::TextureView, GpuError> {
        let (k, w, h) = (params.k, params.width, params.height);
        let target = atlas(
            ctx,
            "splat atlas",
            (k * params.view_w, k * params.view_h),
            ATLAS,
        )?;
        let interleaving = Interleaving { k, seed: 0 };
        let extent = |i: u32, j: u32| interleaving.subregion_size(w, h, [i, j]);
        self.draws.encode(
            ctx,
            encoder,
            "splat",
            (params, params_buffer),
            &tiles.partition.sub_offsets,
            (pipeline, bind),
            &target,
            extent,
        )?;
        Ok(target)
    }

    /// The indirect image of `frame` (its `GpuSample`s in `samples`), splatted: RGB, 3 f32
    /// per pixel row-major, left on the GPU. The culling passes' fault record is read
    /// afterwards (16 bytes), as after the one-pass tiled shading.
    pub fn shade(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        samples: &wgpu::Buffer,
        tiles: &PreparedTiles,
    ) -> Result<wgpu::Buffer, GpuError> {
        let pipeline = self.shade.as_ref().ok_or_else(|| {
            GpuError::Input(
                "splatting adds f32 colours by blending, which this adapter cannot \
                 (no FLOAT32_BLENDABLE)"
                    .into(),
            )
        })?;
        let params = self.params(frame, tiles, 0);
        let image = output::<f32>(ctx, "indirect image", 3 * tiles.pixels as usize)?;
        ctx.submit("splat", |encoder| {
            let params_buffer = params_uniform(ctx, encoder, tiles, &params);
            let group = bind(
                ctx,
                "splat",
                &pipeline.get_bind_group_layout(0),
                &[
                    (0, params_buffer.as_entire_binding()),
                    (1, self.mesh.as_entire_binding()),
                    (2, tiles.bounds.shapes.as_entire_binding()),
                    (3, tiles.partition.sub_offsets.as_entire_binding()),
                    (4, tiles.partition.order.as_entire_binding()),
                    (6, samples.as_entire_binding()),
                    (7, frame.positions.as_entire_binding()),
                    (VPL_BINDINGS[0], tiles.bounds.vpls.low.as_entire_binding()),
                    (VPL_BINDINGS[1], tiles.bounds.vpls.high.as_entire_binding()),
                ],
            );
            let drawn = (&params, &params_buffer);
            let target = self.draw(ctx, encoder, drawn, tiles, pipeline, &group)?;
            let resolve = bind(
                ctx,
                "splat resolve",
                &self.resolve.get_bind_group_layout(0),
                &[
                    (0, params_buffer.as_entire_binding()),
                    (1, wgpu::BindingResource::TextureView(&target)),
                    (2, image.as_entire_binding()),
                ],
            );
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("splat resolve"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.resolve);
            pass.set_bind_group(0, &resolve, &[]);
            pass.dispatch_workgroups(frame.width.div_ceil(8), frame.height.div_ceil(8), 1);
            Ok(())
        })?;
        read_status(ctx, &tiles.status, frame.width)?;
        Ok(image)
    }

    /// Sets the room of the next metrics frames' node buffers (`cull::room`).
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
    }

    /// What the splats evaluate, as light lists (for the metrics): pixel p's list holds the
    /// VPLs whose mesh covers it, ascending. The draws append them to a node buffer, read
    /// back (and drawn again into a larger one if it was too small) and uploaded in the CSR
    /// layout.
    pub fn lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        tiles: &PreparedTiles,
    ) -> Result<GpuLightLists, GpuError> {
        // The faults of the culling passes (a sample behind the camera, a bound beyond f32).
        read_status(ctx, &tiles.status, frame.width)?;
        loop {
            // One list per pixel.
            let k = frame.interleaving.k;
            let per_subregion =
                u64::from(frame.width.div_ceil(k)) * u64::from(frame.height.div_ceil(k));
            let capacity = self.room.entries::<[u32; 2]>(ctx, frame, per_subregion);
            let params = self.params(frame, tiles, capacity);
            let nodes = NodeLists::new(ctx, tiles.pixels, capacity)?;
            let status = upload(ctx, "splat list status", &[GpuCullStatus::CLEAR])?;
            ctx.submit("splat lists", |encoder| {
                let params_buffer = params_uniform(ctx, encoder, tiles, &params);
                let group = bind(
                    ctx,
                    "splat lists",
                    &self.list.get_bind_group_layout(0),
                    &[
                        (0, params_buffer.as_entire_binding()),
                        (1, self.mesh.as_entire_binding()),
                        (2, tiles.bounds.shapes.as_entire_binding()),
                        (3, tiles.partition.sub_offsets.as_entire_binding()),
                        (4, tiles.partition.order.as_entire_binding()),
                        (7, frame.positions.as_entire_binding()),
                        (8, nodes.heads.as_entire_binding()),
                        (9, nodes.nodes.as_entire_binding()),
                        (10, status.as_entire_binding()),
                    ],
                );
                let drawn = (&params, &params_buffer);
                self.draw(ctx, encoder, drawn, tiles, &self.list, &group)?;
                Ok(())
            })?;
            let count = read_status(ctx, &status, frame.width)?;
            if count > capacity {
                self.room.learn(count);
                continue;
            }
            let pixel_list: Vec<u32> = (0..tiles.pixels).collect();
            let lists = nodes.read(ctx, count, &pixel_list)?;
            let vpls = tiles.bounds.count.capacity() as usize;
            return GpuLightLists::upload(ctx, &lists, tiles.pixels as usize, vpls);
        }
    }
}

/// `params` in a uniform with the frame's VPL count (copied in on the GPU where it lies there).
fn params_uniform(
    ctx: &GpuContext,
    encoder: &mut wgpu::CommandEncoder,
    tiles: &PreparedTiles,
    params: &GpuRasterParams,
) -> wgpu::Buffer {
    let at = offset_of!(GpuRasterParams, vpl_count);
    tiles
        .bounds
        .count
        .uniform(ctx, encoder, "splat params", params, at)
}
