//! What the raster baselines share (`cull::raster::splat`, `cull::raster::clusters`): their render
//! pipelines, bind groups by binding number (a pipeline's derived layout holds only the
//! bindings its entry points use), the indirect draw per interleaved subregion sized on the
//! GPU (`raster_args.wesl`) and the pass that draws every subregion's VPLs into its
//! own viewport of an atlas.
pub mod clusters;
pub mod mesh;
pub mod nodes;
pub mod records;
pub mod splat;

use crate::cull::raster::records::GpuRasterParams;
use crate::device::buffers::Grid;
use crate::device::context::{GpuContext, GpuError};

/// The kernel of `raster_args.wesl`, linked with what it imports (build.rs).
pub(crate) const ARGS_SOURCE: &str = kernel!("raster_args");

/// Largest interleaving factor the raster baselines draw with: one draw per subregion.
pub const MAX_RASTER_K: u32 = 64;

/// How a raster baseline's pipeline rasterizes its triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rasterization {
    /// The vertex entry point.
    pub vertex: &'static str,
    pub cull_mode: Option<wgpu::Face>,
    /// Conservative rasterization in hardware (`Features::CONSERVATIVE_RASTERIZATION`).
    pub conservative: bool,
}

impl Rasterization {
    /// `vs_main`, every fragment whose centre a triangle covers.
    pub const PLAIN: Self = Self {
        vertex: "vs_main",
        cull_mode: None,
        conservative: false,
    };
}

/// A render pipeline of `source` (the vertex entry point of `raster` and `fragment`) drawing
/// triangle lists into one colour target of `format`, without depth.
pub(crate) fn render_pipeline(
    ctx: &GpuContext,
    label: &'static str,
    source: &str,
    fragment: &str,
    target: wgpu::ColorTargetState,
    raster: Rasterization,
) -> wgpu::RenderPipeline {
    let module = ctx
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    ctx.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(raster.vertex),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                front_face: wgpu::FrontFace::Ccw,
                cull_mode: raster.cull_mode,
                conservative: raster.conservative,
                ..Default::default()
            },
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(fragment),
                compilation_options: Default::default(),
                targets: &[Some(target)],
            }),
            multiview_mask: None,
            cache: None,
        })
}

/// A bind group for group 0 of `layout` with each resource at its binding number.
pub(crate) fn bind(
    ctx: &GpuContext,
    label: &'static str,
    layout: &wgpu::BindGroupLayout,
    entries: &[(u32, wgpu::BindingResource)],
) -> wgpu::BindGroup {
    let entries: Vec<_> = entries
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: resource.clone(),
        })
        .collect();
    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A colour target texture of `width` x `height` cells (K viewports across and down); an
/// error beyond the adapter's texture size.
pub(crate) fn atlas(
    ctx: &GpuContext,
    label: &'static str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
) -> Result<wgpu::TextureView, GpuError> {
    let max = ctx.limits.max_texture_dimension_2d;
    if width > max || height > max {
        return Err(GpuError::Input(format!(
            "{label} of {width}x{height} exceeds the adapter's {max} texels"
        )));
    }
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: width.max(1),
            height: height.max(1),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    Ok(texture.create_view(&Default::default()))
}

/// The per-subregion draws of the raster baselines.
pub(crate) struct SubregionDraws {
    args: wgpu::ComputePipeline,
}

impl SubregionDraws {
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            args: ctx.compute_pipeline("raster args", ARGS_SOURCE),
        }
    }

    /// Records the draws of `pipeline` (with `bind` at group 0) for every subregion of
    /// `params` (and the uniform holding them, with the frame's VPL count in it) into
    /// `target`, cleared first: subregion (i, j)'s VPLs
    /// (`order[sub_offsets[s]..sub_offsets[s + 1]]`) as instances of `params.mesh_vertices`
    /// vertices, in the viewport at (i view_w, j view_h) cut to `extent(i, j)` cells. K
    /// beyond [`MAX_RASTER_K`] is an error.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        label: &'static str,
        (params, params_buffer): (&GpuRasterParams, &wgpu::Buffer),
        sub_offsets: &wgpu::Buffer,
        (pipeline, bind): (&wgpu::RenderPipeline, &wgpu::BindGroup),
        target: &wgpu::TextureView,
        extent: impl Fn(u32, u32) -> [u32; 2],
    ) -> Result<(), GpuError> {
        let k = params.k;
        if k > MAX_RASTER_K {
            return Err(GpuError::Input(format!(
                "the raster baselines draw once per subregion: K = {k} exceeds {MAX_RASTER_K}"
            )));
        }
        let subregions = k * k;
        let args = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("raster draw args"),
            size: 16 * u64::from(subregions),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
            mapped_at_creation: false,
        });
        ctx.encode_dispatch(
            encoder,
            "raster args",
            &self.args,
            &[params_buffer, sub_offsets, &args],
            Grid::for_items(ctx, u64::from(subregions), 64)?,
        );
        // Timed while profiling, as the compute passes are: without it a GPU profile of a
        // raster baseline left out its draws.
        let timed = ctx.render_timestamps(label);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: timed
                .as_ref()
                .map(crate::device::profiler::render_pass_writes),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind, &[]);
        let (vw, vh) = (params.view_w, params.view_h);
        for s in 0..subregions {
            let (i, j) = (s % k, s / k);
            let [w, h] = extent(i, j);
            if w == 0 || h == 0 {
                continue;
            }
            let (x, y) = (i * vw, j * vh);
            pass.set_viewport(x as f32, y as f32, vw as f32, vh as f32, 0.0, 1.0);
            pass.set_scissor_rect(x, y, w.min(vw), h.min(vh));
            pass.draw_indirect(&args, 16 * u64::from(s));
        }
        Ok(())
    }
}
