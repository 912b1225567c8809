//! The rasterized G-buffer, GPU twin of `slc_cpu_ref::gbuffer::trace_gbuffer`: the
//! visibility pass (`frame::raster::visibility`) picks each pixel's nearest triangle, then
//! `gbuffer.wesl` intersects the pixel's ray (`Camera::ray_direction`, at a
//! frame-wide sub-pixel offset) with that triangle and records position, oriented shading
//! and geometric normals, ωo and the BRDF (`Material::brdf_at`, textures included).
//!
//! The result stays on the GPU ([`GpuGBuffer`]) in the [`GpuSample`] layout the tile depth,
//! tiled culling and shading passes read
//! (`CullFrame::on_gpu` for the cullers, `ShadePass::shade_on_gpu`), and can be read back
//! as a `slc_core::GBuffer` ([`GpuGBuffer::read_back`]).
//!
//! The CPU's `PixelSample::Jittered` draws a different offset per pixel, which a rasterizer
//! cannot; the offset here is one (s, t) for the whole frame ((0.5, 0.5): pixel centres, the
//! CPU's `PixelSample::Centre`).
use crate::device::buffers::{output, read_back, uniform};
use crate::device::context::{GpuContext, GpuError};
use crate::frame::raster::records::GpuGbufferParams;
use crate::frame::raster::records::GpuSample;
use crate::frame::raster::scene::GpuScene;
use crate::frame::raster::visibility::{RasterView, Resolve, VisibilityPass, VisibilityTarget};
use glam::Vec3;
use slc_core::{Camera, GBuffer, GSample};

/// The kernel of `gbuffer.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("gbuffer");

/// A G-buffer on the GPU, `width` x `height` pixels, row-major from the top-left.
pub struct GpuGBuffer {
    pub width: u32,
    pub height: u32,
    /// The camera it was rendered from.
    pub camera: Camera,
    /// [`GpuSample`] per pixel ([`GpuSample::EMPTY`]-like, `info[0]` = 0, where the camera
    /// sees nothing or the back of a one-sided surface).
    pub samples: wgpu::Buffer,
    /// The unit geometric normal per pixel, oriented as `GSample::geometric_normal` (xyz; w 0).
    pub geometric_normals: wgpu::Buffer,
    /// `[x, y, z, 1]` per pixel with a sample, zero otherwise: what the tile depth pass reads.
    pub positions: wgpu::Buffer,
    /// The frame's sub-pixel offset (s, t): each sample lies on the ray through pixel
    /// (x + s, y + t).
    pub offset: (f32, f32),
}

impl GpuGBuffer {
    /// Number of pixels.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// The G-buffer as the CPU's `GBuffer` (depth = `Camera::view_depth` of the position).
    pub fn read_back(&self, ctx: &GpuContext) -> Result<GBuffer, GpuError> {
        let samples: Vec<GpuSample> =
            read_back(ctx, "gbuffer samples", &self.samples, self.pixels())?;
        let normals: Vec<[f32; 4]> = read_back(
            ctx,
            "gbuffer geometric normals",
            &self.geometric_normals,
            self.pixels(),
        )?;
        let positions: Vec<[f32; 4]> =
            read_back(ctx, "gbuffer positions", &self.positions, self.pixels())?;
        let samples = samples
            .iter()
            .zip(normals.iter().zip(&positions))
            .map(|(s, (ng, x))| s.is_present().then(|| self.unpack(s, ng, x)))
            .collect();
        Ok(GBuffer {
            width: self.width,
            height: self.height,
            samples,
        })
    }

    fn unpack(&self, s: &GpuSample, ng: &[f32; 4], x: &[f32; 4]) -> GSample {
        let v = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
        let position = v(*x);
        GSample {
            position,
            normal: v(s.normal_alpha),
            geometric_normal: v(*ng),
            omega_o: v(s.omega_o_phi),
            depth: self.camera.view_depth(position),
            brdf: s.brdf(),
        }
    }
}

/// The compiled G-buffer pipelines (visibility and resolve).
pub struct GbufferPass {
    visibility: VisibilityPass,
    resolve: wgpu::ComputePipeline,
}

impl GbufferPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let visibility = VisibilityPass::new(ctx)?;
        ctx.scoped("gbuffer pipeline", || {
            Ok(Self {
                visibility,
                resolve: ctx.compute_pipeline("gbuffer resolve", SOURCE),
            })
        })
    }

    /// Renders `scene` from `camera` into a `width` x `height` G-buffer with every ray at
    /// sub-pixel offset `offset` = (s, t) in [0, 1)² ((0.5, 0.5): pixel centres). Errors on
    /// an invalid camera or offset, a size beyond the adapter's texture or storage limits,
    /// and device faults.
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        camera: &Camera,
        width: u32,
        height: u32,
        offset: (f32, f32),
    ) -> Result<GpuGBuffer, GpuError> {
        validate_camera(camera)?;
        let inside = |x: f32| (0.0..1.0).contains(&x);
        if !(inside(offset.0) && inside(offset.1)) {
            return Err(GpuError::Input(format!(
                "sub-pixel offset {offset:?} is outside [0, 1)²"
            )));
        }
        let target = VisibilityTarget::new(ctx, width, height)?;
        let pixels = width as usize * height as usize;
        let samples = output::<GpuSample>(ctx, "gbuffer samples", pixels)?;
        let geometric_normals = output::<[f32; 4]>(ctx, "gbuffer geometric normals", pixels)?;
        let positions = output::<[f32; 4]>(ctx, "gbuffer positions", pixels)?;
        // Camera::ray_direction's constants, computed as the CPU computes them.
        let tan_half = (0.5 * camera.yfov).tan();
        let aspect = width as f32 / height as f32;
        let params = GpuGbufferParams {
            position: camera.position.extend(0.0).to_array(),
            forward: camera.forward.extend(0.0).to_array(),
            right: camera.right.extend(0.0).to_array(),
            up: camera.up.extend(0.0).to_array(),
            frame: [aspect, tan_half, offset.0, offset.1],
            width,
            height,
            pad: [0; 2],
        };
        let view = RasterView {
            origin: camera.position,
            right: camera.right,
            up: camera.up,
            forward: camera.forward,
            extent: (aspect * tan_half, tan_half),
            orthographic: None,
            offset,
        };
        ctx.scoped("gbuffer", || {
            let params = uniform(ctx, "gbuffer params", &params);
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("gbuffer"),
                });
            self.visibility
                .encode(ctx, &mut encoder, scene, &view, &target);
            Resolve {
                label: "gbuffer resolve",
                pipeline: &self.resolve,
                params: &params,
                outputs: &[&samples, &geometric_normals, &positions],
                groups: (width.div_ceil(8), height.div_ceil(8)),
            }
            .encode(ctx, &mut encoder, scene, &target);
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        Ok(GpuGBuffer {
            width,
            height,
            camera: camera.clone(),
            samples,
            geometric_normals,
            positions,
            offset,
        })
    }
}

/// A camera the rasterizer can use: finite position, an orthonormal basis, yfov in (0, π).
fn validate_camera(camera: &Camera) -> Result<(), GpuError> {
    let unit = |v: Vec3| v.is_finite() && (v.length() - 1.0).abs() < 1e-3;
    let orthogonal = camera.forward.dot(camera.right).abs() < 1e-3
        && camera.forward.dot(camera.up).abs() < 1e-3
        && camera.right.dot(camera.up).abs() < 1e-3;
    if camera.position.is_finite()
        && unit(camera.forward)
        && unit(camera.right)
        && unit(camera.up)
        && orthogonal
        && camera.yfov > 0.0
        && camera.yfov < std::f32::consts::PI
    {
        Ok(())
    } else {
        Err(GpuError::Input(format!(
            "camera {camera:?} needs a finite position, an orthonormal basis and yfov in (0, π)"
        )))
    }
}
