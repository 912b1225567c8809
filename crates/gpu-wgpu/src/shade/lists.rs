//! Stochastic VPL shading from light lists on the GPU (`brdf.wesl`,
//! `shade.wesl`), the twin of `slc_cpu_ref::vpl_shading::shade_lists` without
//! visibility: each pixel with a G-buffer sample sums, over the VPLs of its list,
//! `f_x(n, ωl, ωo) I(ω) / l² cos θx · K² / p` when `p > ξ` (paper eq. 3 with the interleaved
//! sampling of section 6), with I the VPL's intensity of eq. (4), p = min(I / (δ l²), 1) of
//! eq. (2) on I's largest channel, and the BRDF of eq. (6)-(8) (`slc_bounds::Brdf`).
//!
//! The lists come in the CSR layout of [`LightLists`] (offsets, indices, pixel → list), either
//! uploaded from the CPU ([`ShadePass::shade`], which reads the image back as an [`Image`])
//! or left on the GPU by a culler ([`ShadePass::shade_on_gpu`], e.g. after
//! the tiled culler's [`crate::cull::ListCulling::cull_on_gpu`], whose fixed two lists per tile, empty
//! ones included, are the same layout), for a G-buffer uploaded or rendered on the GPU
//! ([`ShadedGBuffer`]). Buffers beyond the storage-binding limit are refused
//! ([`GpuError::BufferTooLarge`]); more than 65535 workgroups are split into a 2-D grid.
//!
//! f32 throughout, with the CPU's operation order, so results agree to a few ulps (bit for
//! bit on lavapipe); the one place the CPU uses f64 (the half vector of a smooth lobe near
//! grazing opposition) is emulated with compensated f32 arithmetic, see `brdf.wesl`.
use crate::cull::frame::FrameVpls;
use crate::cull::lists::GpuLightLists;
use crate::cull::records::MAX_K;
use crate::device::buffers::{output, read_back, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::frame::raster::gbuffer::GpuGBuffer;
use crate::frame::raster::records::{gpu_position, GpuSample};
use crate::shade::records::GpuShadeParams;
use glam::Vec3;
use slc_core::{CullInput, GBuffer, Image, Interleaving, LightLists};

/// The kernel of `shade.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("shade");
const WORKGROUP: u32 = 64;

/// The G-buffer a shading pass reads: one on the CPU, uploaded as [`GpuSample`]s and
/// positions, or one rendered on the GPU ([`crate::frame::raster::gbuffer::GbufferPass`]),
/// read where it lies.
#[derive(Clone, Copy)]
pub enum ShadedGBuffer<'a> {
    Cpu(&'a GBuffer),
    Gpu(&'a GpuGBuffer),
}

/// What shading needs besides the G-buffer samples.
struct ShadeInput<'a> {
    width: u32,
    height: u32,
    vpls: FrameVpls<'a>,
    delta: f32,
    interleaving: Interleaving,
}

/// The compiled shading pipeline.
pub struct ShadePass {
    pipeline: wgpu::ComputePipeline,
}

impl ShadePass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("shade pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("shade", SOURCE),
            })
        })
    }

    /// Shades `input` (G-buffer, VPLs, δ, K) with `lists` uploaded from the CPU and reads the
    /// image back: the GPU twin of `shade_lists(…, visibility = false, …)`. Errors on invalid
    /// input (δ, ξ or a VPL as the culler validates them, lists that do not fit the input), on
    /// buffers beyond the device's limits and on device faults.
    pub fn shade(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        lists: &LightLists,
    ) -> Result<Image, GpuError> {
        // A pixel's loop runs once per entry of its list (of the union of its two lists,
        // at most the longest own list and the longest shared one together).
        if ctx.loop_budget.is_some() {
            let longest_of = |map: &[u32]| {
                map.iter()
                    .filter_map(|&l| lists.offsets.get(l as usize..l as usize + 2))
                    .map(|w| u64::from(w[1].saturating_sub(w[0])))
                    .max()
                    .unwrap_or(0)
            };
            let longest = longest_of(&lists.pixel_list) + longest_of(&lists.shared_list);
            ctx.check_loop_budget(
                || format!("shading a light list of {longest} VPLs"),
                longest + 64,
                "shorten the lists",
            )?;
        }
        let gpu = GpuLightLists::upload(ctx, lists, input.gbuffer.samples.len(), input.vpls.len())?;
        self.shade_read_back(ctx, input, &gpu)
    }

    /// Shades `input` with `lists` on the GPU (uploaded, or left there by a culler) and reads
    /// the image back.
    pub fn shade_read_back(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        lists: &GpuLightLists,
    ) -> Result<Image, GpuError> {
        let g = input.gbuffer;
        let rgb = self.shade_on_gpu(
            ctx,
            ShadedGBuffer::Cpu(g),
            input.vpls,
            input.delta,
            input.interleaving,
            lists,
        )?;
        read_image(ctx, &rgb, g.width, g.height)
    }

    /// Shades `gbuffer` with `vpls`, δ and K from `lists` on the GPU (uploaded, or left
    /// there by a culler, e.g. the tiled culler's [`crate::cull::ListCulling::cull_on_gpu`], without a
    /// readback), into an image left on the GPU as RGB, 3 f32 per pixel row-major (what
    /// `frame::denoise::DenoisePass::filter_on_gpu` reads; [`read_image`] reads it back).
    pub fn shade_on_gpu<'a>(
        &self,
        ctx: &GpuContext,
        gbuffer: ShadedGBuffer,
        vpls: impl Into<FrameVpls<'a>>,
        delta: f32,
        interleaving: Interleaving,
        lists: &GpuLightLists,
    ) -> Result<wgpu::Buffer, GpuError> {
        let uploaded;
        let (width, height, buffers) = match gbuffer {
            ShadedGBuffer::Gpu(g) => (g.width, g.height, (&g.samples, &g.positions)),
            ShadedGBuffer::Cpu(g) => {
                let pixels = u64::from(g.width) * u64::from(g.height);
                if pixels != g.samples.len() as u64 || u32::try_from(pixels).is_err() {
                    return Err(GpuError::Input(format!(
                        "G-buffer of {}x{} pixels has {} samples",
                        g.width,
                        g.height,
                        g.samples.len()
                    )));
                }
                let samples: Vec<GpuSample> = g
                    .samples
                    .iter()
                    .map(|s| GpuSample::new(s.as_ref()))
                    .collect();
                let positions: Vec<[f32; 4]> =
                    g.samples.iter().map(|s| gpu_position(s.as_ref())).collect();
                uploaded = (
                    upload(ctx, "gbuffer samples", &samples)?,
                    upload(ctx, "gbuffer positions", &positions)?,
                );
                (g.width, g.height, (&uploaded.0, &uploaded.1))
            }
        };
        let input = ShadeInput {
            width,
            height,
            vpls: vpls.into(),
            delta,
            interleaving,
        };
        self.shade_samples(ctx, buffers, &input, lists)
    }

    /// Shades the [`GpuSample`]s and positions in `(samples, positions)` into an RGB buffer
    /// left on the GPU.
    fn shade_samples(
        &self,
        ctx: &GpuContext,
        (samples, positions): (&wgpu::Buffer, &wgpu::Buffer),
        input: &ShadeInput,
        lists: &GpuLightLists,
    ) -> Result<wgpu::Buffer, GpuError> {
        let pixels = u64::from(input.width) * u64::from(input.height);
        if u64::from(lists.pixels) != pixels {
            return Err(GpuError::Input(format!(
                "light lists for {} pixels, G-buffer of {pixels}",
                lists.pixels
            )));
        }
        let k = input.interleaving.k;
        if !(1..=MAX_K).contains(&k) {
            return Err(GpuError::Input(format!(
                "interleaving factor K = {k} must lie in 1..={MAX_K}"
            )));
        }
        let capacity = input.vpls.capacity();
        let vpl_count = u32::try_from(capacity)
            .map_err(|_| GpuError::Input(format!("{capacity} VPLs exceed u32")))?;
        if pixels == 0 {
            return output::<f32>(ctx, "indirect image", 0);
        }
        // The same validation as the culler's (δ and ξ of eq. 2-3, the lobes).
        let vpls = input.vpls.records(ctx, input.delta)?;
        let params = GpuShadeParams {
            width: input.width,
            height: input.height,
            pixel_count: pixels as u32,
            vpl_count,
            list_count: lists.list_count,
            delta: input.delta,
            scale: input.interleaving.scale(),
            pad: 0,
        };
        let out = output::<f32>(ctx, "indirect image", 3 * pixels as usize)?;
        let grid = Grid::for_items(ctx, pixels, WORKGROUP)?;
        let count = input.vpls.count();
        ctx.submit("shade", |encoder| {
            let at = std::mem::offset_of!(GpuShadeParams, vpl_count);
            let params = count.uniform(ctx, encoder, "shade params", &params, at);
            ctx.encode_dispatch_at(
                encoder,
                "shade",
                &self.pipeline,
                &vpls.with(&[
                    &params,
                    samples,
                    &lists.offsets,
                    &lists.indices,
                    &lists.pixel_list,
                    &out,
                    positions,
                ]),
                grid,
            );
            Ok(())
        })?;
        Ok(out)
    }
}

/// A `width` x `height` image from an RGB buffer on the GPU (3 f32 per pixel, row-major):
/// the indirect light every shading pass leaves there (read back as `indirect image`).
pub fn read_image(
    ctx: &GpuContext,
    rgb: &wgpu::Buffer,
    width: u32,
    height: u32,
) -> Result<Image, GpuError> {
    let mut image = Image::new(width, height);
    let pixels = image.pixels.len();
    if pixels == 0 {
        return Ok(image);
    }
    let rgb: Vec<f32> = read_back(ctx, "indirect image", rgb, 3 * pixels)?;
    for (p, c) in image.pixels.iter_mut().zip(rgb.chunks_exact(3)) {
        *p = Vec3::new(c[0], c[1], c[2]);
    }
    Ok(image)
}
