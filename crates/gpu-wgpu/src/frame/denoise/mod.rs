//! The cross bilateral filter on the GPU (`bilateral.wesl`), the twin of
//! `slc_cpu_ref::denoise::cross_bilateral`: the filter that removes the noise of interleaved
//! sampling (paper section 6), a spatial Gaussian weighted by how alike the neighbours'
//! depth and normal are, on demodulated radiance (divided by the reflectance kd + F(1),
//! at least 1e-3, and multiplied back afterwards), applied separably (x then y, 2r + 1 taps
//! each); pixels without a sample keep their value. Same weights, passes, border and sky
//! treatment as the CPU, in f32 as the CPU computes it.
//!
//! [`DenoisePass::filter_on_gpu`] reads an RGB image (3 f32 per pixel, the layout of the
//! shading pass's output) and the G-buffer as [`GpuSample`]s from GPU buffers and leaves the
//! result on the GPU; [`DenoisePass::filter`] uploads an [`Image`] and a [`GBuffer`] and
//! reads the result back. A sample's depth is its linear view depth `(position − eye)·forward`
//! (what `GSample::depth` holds), computed from the camera since `GpuSample` has no depth.
pub mod records;
use crate::device::buffers::{output, read_back, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::frame::denoise::records::{GpuBilateralParams, PASS_HORIZONTAL, PASS_VERTICAL};
use crate::frame::raster::records::{gpu_position, GpuSample};
use glam::Vec3;
use slc_core::frame::BilateralParams;
use slc_core::{Camera, GBuffer, Image};

/// The kernel of `bilateral.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("bilateral");
const WORKGROUP: u32 = 64;

/// Largest kernel radius accepted (the paper uses 8).
pub const MAX_RADIUS: u32 = 256;
/// Largest k of the normal weight max(n·n', 0)^(2^k) accepted (beyond it every weight but a
/// parallel normal's is 0 in f32 anyway).
pub const MAX_NORMAL_SQUARINGS: u32 = 32;

/// The G-buffer that guides the filter, on the GPU.
#[derive(Clone, Copy, Debug)]
pub struct Guide<'a> {
    /// One [`GpuSample`] per pixel, row-major (e.g. the shading pass's input).
    pub samples: &'a wgpu::Buffer,
    /// `[x, y, z, 1]` per pixel, zero without a sample (e.g. `GpuGBuffer::positions`).
    pub positions: &'a wgpu::Buffer,
    pub width: u32,
    pub height: u32,
    /// The camera the G-buffer was seen from (its position and forward axis give depths).
    pub camera: &'a Camera,
}

/// The compiled filter pipeline.
pub struct DenoisePass {
    pipeline: wgpu::ComputePipeline,
}

impl DenoisePass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("bilateral pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("bilateral", SOURCE),
            })
        })
    }

    /// Filters `image` (RGB, 3 f32 per pixel, row-major) guided by `guide`; the result is a
    /// new buffer of the same layout. Errors on settings outside their domain (σ not
    /// positive or 1 / (2σ²) beyond f32, radius above [`MAX_RADIUS`], squarings above
    /// [`MAX_NORMAL_SQUARINGS`]), a non-finite camera, buffers smaller than the image, and
    /// device faults.
    pub fn filter_on_gpu(
        &self,
        ctx: &GpuContext,
        image: &wgpu::Buffer,
        guide: &Guide,
        settings: &BilateralParams,
    ) -> Result<wgpu::Buffer, GpuError> {
        let bad = |what: String| Err(GpuError::Input(format!("cross bilateral filter: {what}")));
        let inv_2s = |sigma: f32| 1.0 / (2.0 * sigma * sigma);
        let (inv_2ss, inv_2sd) = (inv_2s(settings.sigma_spatial), inv_2s(settings.sigma_depth));
        if !(settings.sigma_spatial > 0.0
            && settings.sigma_depth > 0.0
            && inv_2ss.is_finite()
            && inv_2sd.is_finite())
        {
            return bad(format!(
                "standard deviations {} (spatial) and {} (depth) must be positive, with \
                 1 / (2 sigma^2) finite in f32",
                settings.sigma_spatial, settings.sigma_depth
            ));
        }
        if settings.radius > MAX_RADIUS || settings.normal_squarings > MAX_NORMAL_SQUARINGS {
            return bad(format!(
                "radius {} (at most {MAX_RADIUS}) or normal squarings {} (at most \
                 {MAX_NORMAL_SQUARINGS}) too large",
                settings.radius, settings.normal_squarings
            ));
        }
        let camera = guide.camera;
        if !(camera.position.is_finite() && camera.forward.is_finite()) {
            return bad("the camera's position or forward axis is not finite".into());
        }
        let pixels = u64::from(guide.width) * u64::from(guide.height);
        let Ok(pixel_count) = u32::try_from(pixels) else {
            return bad(format!("{pixels} pixels exceed u32"));
        };
        let rgb_bytes = 3 * 4 * pixels;
        let sample_bytes = std::mem::size_of::<GpuSample>() as u64 * pixels;
        if image.size() < rgb_bytes
            || guide.samples.size() < sample_bytes
            || guide.positions.size() < 16 * pixels
        {
            return bad(format!(
                "image buffer of {} bytes, G-buffer of {} bytes or positions of {} bytes too \
                 small for {}x{} pixels",
                image.size(),
                guide.samples.size(),
                guide.positions.size(),
                guide.width,
                guide.height
            ));
        }
        let horizontal = output::<f32>(ctx, "bilateral (x)", 3 * pixel_count as usize)?;
        let filtered = output::<f32>(ctx, "bilateral (y)", 3 * pixel_count as usize)?;
        if pixels == 0 {
            return Ok(filtered);
        }
        let grid = Grid::for_items(ctx, pixels, WORKGROUP)?;
        let params = |axis| GpuBilateralParams {
            eye: camera.position.extend(0.0).to_array(),
            forward: camera.forward.extend(0.0).to_array(),
            width: guide.width,
            height: guide.height,
            radius: settings.radius,
            normal_squarings: settings.normal_squarings,
            inv_2ss,
            inv_2sd,
            axis,
            pad: 0,
        };
        ctx.scoped("bilateral", || {
            let x = uniform(ctx, "bilateral params (x)", &params(PASS_HORIZONTAL));
            let y = uniform(ctx, "bilateral params (y)", &params(PASS_VERTICAL));
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("bilateral"),
                });
            for (label, params, from, to) in [
                ("bilateral (x)", &x, image, &horizontal),
                ("bilateral (y)", &y, &horizontal, &filtered),
            ] {
                ctx.encode_dispatch(
                    &mut encoder,
                    label,
                    &self.pipeline,
                    &[params, guide.samples, from, to, guide.positions],
                    grid,
                );
            }
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        Ok(filtered)
    }

    /// [`Self::filter_on_gpu`] for an image and G-buffer on the CPU, read back: the GPU twin
    /// of `cross_bilateral(image, gbuffer, params)`. Also errors on an image whose size is
    /// not the G-buffer's, a non-finite pixel value, and a sample whose `depth` is not its
    /// position's view depth for `camera` (within 1e-4 relative; the GPU computes it so).
    pub fn filter(
        &self,
        ctx: &GpuContext,
        image: &Image,
        gbuffer: &GBuffer,
        camera: &Camera,
        settings: &BilateralParams,
    ) -> Result<Image, GpuError> {
        let bad = |what: String| Err(GpuError::Input(format!("cross bilateral filter: {what}")));
        let pixels = u64::from(gbuffer.width) * u64::from(gbuffer.height);
        if (image.width, image.height) != (gbuffer.width, gbuffer.height)
            || image.pixels.len() as u64 != pixels
            || gbuffer.samples.len() as u64 != pixels
        {
            return bad(format!(
                "image of {}x{} ({} pixels) for a G-buffer of {}x{} ({} samples)",
                image.width,
                image.height,
                image.pixels.len(),
                gbuffer.width,
                gbuffer.height,
                gbuffer.samples.len()
            ));
        }
        let at = |p: usize| {
            (
                p as u64 % u64::from(gbuffer.width.max(1)),
                p as u64 / u64::from(gbuffer.width.max(1)),
            )
        };
        if let Some(p) = image.pixels.iter().position(|v| !v.is_finite()) {
            return bad(format!("pixel {:?} is not finite", at(p)));
        }
        let inconsistent = gbuffer.samples.iter().position(|s| {
            s.as_ref().is_some_and(|g| {
                let z = camera.view_depth(g.position);
                // Written so that a NaN depth is inconsistent too.
                let consistent = (g.depth - z).abs() <= 1e-4 * z.abs().max(g.depth.abs());
                !consistent
            })
        });
        if let Some(p) = inconsistent {
            return bad(format!(
                "the depth of pixel {:?} is not its position's view depth",
                at(p)
            ));
        }
        let rgb: Vec<f32> = image.pixels.iter().flat_map(|v| v.to_array()).collect();
        let samples: Vec<GpuSample> = gbuffer
            .samples
            .iter()
            .map(|s| GpuSample::new(s.as_ref()))
            .collect();
        let rgb = upload(ctx, "image", &rgb)?;
        let samples = upload(ctx, "gbuffer samples", &samples)?;
        let positions: Vec<[f32; 4]> = gbuffer
            .samples
            .iter()
            .map(|s| gpu_position(s.as_ref()))
            .collect();
        let positions = upload(ctx, "gbuffer positions", &positions)?;
        let guide = Guide {
            samples: &samples,
            positions: &positions,
            width: gbuffer.width,
            height: gbuffer.height,
            camera,
        };
        let filtered = self.filter_on_gpu(ctx, &rgb, &guide, settings)?;
        let out: Vec<f32> = read_back(ctx, "denoised image", &filtered, 3 * pixels as usize)?;
        Ok(Image {
            width: image.width,
            height: image.height,
            pixels: out
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2]))
                .collect(),
        })
    }
}
