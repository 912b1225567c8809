//! Visibility by rasterization (`visibility.wesl`): the scene's triangles drawn from a
//! camera or a light face with a 32-bit float depth test, each pixel keeping its nearest
//! triangle's index + 1 (0: nothing) in an `R32Uint` target. The G-buffer and RSM resolves
//! (`frame::raster::gbuffer`, `frame::light::rsm`) then intersect each pixel's or texel's own ray with that
//! triangle, so positions, normals and BRDFs follow the CPU's ray convention exactly and
//! only the choice of triangle is the rasterizer's (it differs from the ray tracer's only
//! where a pixel centre lies within rounding of a triangle edge).
//!
//! Both faces of every triangle are drawn: a one-sided surface seen from behind is black but
//! still hides what lies beyond it, as on the CPU. Where an alpha mask cuts a surface away
//! (at the rasterizer's interpolated texture coordinate) the fragment is discarded. Pinhole views use reversed depth with an
//! infinite far plane; the near plane is `NEAR_RELATIVE` times the scene's extent (nearer
//! surfaces are clipped, the CPU's rays have no near plane).
use crate::device::context::{GpuContext, GpuError};
use crate::frame::raster::records::GpuRasterView;
use crate::frame::raster::scene::GpuScene;
use glam::Vec3;

/// The kernel of `visibility.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("visibility");

/// Near plane of pinhole views relative to the scene extent (`GpuScene::extent`).
pub const NEAR_RELATIVE: f32 = 1e-5;

const IDS: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A pinhole or orthographic view to rasterize (see [`GpuRasterView`]).
#[derive(Clone, Copy, Debug)]
pub struct RasterView {
    pub origin: Vec3,
    pub right: Vec3,
    pub up: Vec3,
    pub forward: Vec3,
    /// Half extents of the image plane at unit depth (pinhole) or in world units
    /// (orthographic).
    pub extent: (f32, f32),
    /// `Some(range)`: orthographic over depths [0, range]; `None`: pinhole.
    pub orthographic: Option<f32>,
    /// Sub-pixel offset (s, t) of the rays in [0, 1)² ((0.5, 0.5): pixel centres).
    pub offset: (f32, f32),
}

impl RasterView {
    fn gpu(&self, scene: &GpuScene, width: u32, height: u32) -> GpuRasterView {
        let shift_x = 2.0 * (0.5 - self.offset.0) / width as f32;
        let shift_y = 2.0 * (self.offset.1 - 0.5) / height as f32;
        let (depth, ortho) = match self.orthographic {
            Some(range) => (1.0 / range, 1.0),
            None => (NEAR_RELATIVE * scene.extent, 0.0),
        };
        GpuRasterView {
            origin: self.origin.extend(0.0).to_array(),
            right: self.right.extend(1.0 / self.extent.0).to_array(),
            up: self.up.extend(1.0 / self.extent.1).to_array(),
            forward: self.forward.extend(depth).to_array(),
            shift: [shift_x, shift_y, ortho, 0.0],
        }
    }
}

/// The triangle-id and depth targets of one view.
pub struct VisibilityTarget {
    pub width: u32,
    pub height: u32,
    ids: wgpu::TextureView,
    depth: wgpu::TextureView,
}

impl VisibilityTarget {
    /// Targets of `width` x `height` pixels; an error beyond the adapter's 2-D texture size.
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Result<Self, GpuError> {
        let max = ctx.limits.max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(GpuError::Input(format!(
                "a {width}x{height} raster target is outside 1..={max} per side on this adapter"
            )));
        }
        let texture = |label, format, usage| {
            ctx.device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width,
                        height,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        Ok(Self {
            width,
            height,
            ids: texture(
                "triangle ids",
                IDS,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            ),
            depth: texture(
                "visibility depth",
                DEPTH,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            ),
        })
    }
}

/// The compiled visibility pipeline.
pub struct VisibilityPass {
    pipeline: wgpu::RenderPipeline,
}

impl VisibilityPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("visibility pipeline", || {
            let module = ctx
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("visibility"),
                    source: wgpu::ShaderSource::Wgsl(SOURCE.into()),
                });
            let pipeline = ctx
                .device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("visibility"),
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("vs_main"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: wgpu::PrimitiveState {
                        cull_mode: None,
                        ..Default::default()
                    },
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format: DEPTH,
                        depth_write_enabled: Some(true),
                        depth_compare: Some(wgpu::CompareFunction::Greater),
                        stencil: Default::default(),
                        bias: Default::default(),
                    }),
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("fs_main"),
                        compilation_options: Default::default(),
                        targets: &[Some(IDS.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                });
            Ok(Self { pipeline })
        })
    }

    /// Records the rasterization of `scene` from `view` into `target` (cleared first).
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        view: &RasterView,
        target: &VisibilityTarget,
    ) {
        let uniform = crate::device::buffers::uniform(
            ctx,
            "raster view",
            &view.gpu(scene, target.width, target.height),
        );
        let mut entries = scene_entries(scene);
        entries.push(entry(5, uniform.as_entire_binding()));
        let bind = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("visibility"),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let timed = ctx.render_timestamps("visibility");
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("visibility"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.ids,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timed
                .as_ref()
                .map(crate::device::profiler::render_pass_writes),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.draw(0..3 * scene.triangle_count, 0..1);
    }
}

fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

/// The scene's buffers at bindings 0-4 (`scene.wesl`).
fn scene_entries(scene: &GpuScene) -> Vec<wgpu::BindGroupEntry<'_>> {
    scene
        .bindings()
        .iter()
        .enumerate()
        .map(|(i, b)| entry(i as u32, b.as_entire_binding()))
        .collect()
}

/// A resolve dispatch (`frame::raster::gbuffer`, `frame::light::rsm`): `pipeline` over `groups` (x, y)
/// workgroups with the scene at bindings 0-4 (`scene.wesl`), the uniform `params`
/// at 5, the target's triangle ids at 6 and `outputs` from 7 on.
pub(crate) struct Resolve<'a> {
    pub label: &'static str,
    pub pipeline: &'a wgpu::ComputePipeline,
    pub params: &'a wgpu::Buffer,
    pub outputs: &'a [&'a wgpu::Buffer],
    pub groups: (u32, u32),
}

impl Resolve<'_> {
    /// Records the dispatch reading `target`'s triangle ids.
    pub(crate) fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        target: &VisibilityTarget,
    ) {
        let mut entries = scene_entries(scene);
        entries.push(entry(5, self.params.as_entire_binding()));
        entries.push(entry(6, wgpu::BindingResource::TextureView(&target.ids)));
        entries.extend(
            self.outputs
                .iter()
                .enumerate()
                .map(|(i, b)| entry(7 + i as u32, b.as_entire_binding())),
        );
        let bind = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.label),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let timed = ctx.compute_timestamps(self.label);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes: timed
                .as_ref()
                .map(crate::device::profiler::compute_pass_writes),
        });
        pass.set_pipeline(self.pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
    }
}
