//! Shading by virtual spherical Gaussian lights on the GPU (Tokuyoshi 2015, "Virtual Spherical
//! Gaussian Lights for Real-time Glossy Indirect Illumination", section 3.2, eq. 2-5;
//! `sg.wesl`, `vsgl_shade.wesl`), the twin of
//! `slc_cpu_ref::vsgl::shade_vsgls(…, visibility = false, …)`: every pixel with a G-buffer
//! sample sums, over the VSGLs, `vsgl_radiance` — for each lobe `c_v G(ω; ξ_v, λ_v)` of the
//! VSGL's radiant intensity, `c_v` times the closed-form shading (`slc_bounds::SgSurface`:
//! irradiance for the diffuse term, fitted GGX SG inner product for the specular one) of the
//! incoming radiance of eq. (5), `1/(2πσ_v²) G(ω; −ξ_v, λ_v) G(ω; ξ_μ, |μ_v − x_p|²/σ_v²)`,
//! a specular lobe of sharpness 3 or more as the three SGs of GGX's profile
//! (`slc_bounds::sg::ggx_mixture`, `mixture_scale` in `vsgl_light.wesl`). Without visibility (entry point `main`: [`VsglShadePass::shade`],
//! [`VsglShadePass::shade_gpu_gbuffer_on_gpu`] without maps) there is no `V(x_p, μ_v)` of
//! eq. 3. With imperfect shadow maps ([`crate::vsgl::ism`], entry point `main_visible`:
//! [`VsglShadePass::shade_visible`], [`VsglShadePass::shade_gpu_gbuffer_on_gpu`] with maps)
//! each VSGL that contributes is weighted by the map's binary visibility of `μ_v`, where the
//! CPU traces a shadow ray (`shade_vsgls(…, visibility = true, …)`). The VSGLs are uploaded
//! from the CPU ([`GpuVsgls::upload`]) or built on the GPU ([`crate::vsgl::build`]); empty
//! slots of the latter shade nothing.
//!
//! The SG algebra is in f32; `sg.wesl` uses forms free of the cancellations f32 would
//! add (series for expm1, the Langevin function and the away-facing irradiance at small
//! sharpness; `1 − L(λ)` formed directly). The CPU's VSGL shading uses the same forms, written
//! again in Rust (`slc_bounds`' `sg/single.rs`, held to its f64 forms by its own tests), so
//! results agree with the CPU within 1.2e-5 of each pixel on the default scene and 2.8e-5 in
//! the worst extreme tested (`tests/gpu/vsgl.rs`; 5.3e-7 and 3.2e-6 with one SG per lobe).
//!
//! Out-of-domain input is an error, never a NaN: uploaded VSGLs are validated on the CPU
//! ([`GpuVsgl::new`]), built ones by the construction's shader with the same checks, an
//! uploaded G-buffer by `SgSurface::new` itself; samples of a GPU G-buffer outside the SG
//! math's domain and a `λ_σ` or SG product beyond `f32` at some pixel are recorded by the
//! shader in the frame's fault record ([`GpuVsglStatus`]), read back after the dispatch with
//! the construction's faults.
pub mod records;
pub(crate) mod specular_table;

use crate::device::buffers::{output, read_back, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::Count;
use crate::frame::raster::gbuffer::GpuGBuffer;
use crate::frame::raster::records::{gpu_position, GpuSample};
use crate::shade::lists::read_image;
use crate::vsgl::ism::ImperfectShadowMaps;
use crate::vsgl::shade::records::{GpuVsgl, GpuVsglParams, GpuVsglStatus, VsglInput};
use slc_bounds::SgSurface;
use slc_core::{GBuffer, Image};

/// Loop iterations a pixel's sum over the VSGLs runs per VSGL at most: the sum's own and
/// those of `vsgl_contribution` (its two lobes, and the three SGs of GGX's mixture with the
/// stretch towards the receiver). Measured on lavapipe, which ends an invocation's loops
/// after 65,535 iterations (`LLVMPIPE_LOOP_ITERATIONS`): 8,192 VSGLs on the built-in scene
/// shaded within the noise of the CPU's image, 9,000 VSGLs 1.7% dark, 16,384 VSGLs 15% dark.
pub(crate) const ITERATIONS_PER_VSGL: u64 = 8;

/// The kernel of `vsgl_shade.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("vsgl_shade");
const WORKGROUP: u32 = 64;

/// VSGLs on the GPU in the [`GpuVsgl`] layout, with their centres (for the imperfect shadow
/// maps), their number (the host's, or left on the GPU by [`crate::vsgl::build`]) and
/// the frame's fault record, which the shading fills in and reads.
pub struct GpuVsgls {
    /// [`GpuVsgl`] per VSGL (the buffer holds the count's capacity).
    pub buffer: wgpu::Buffer,
    /// How many there are.
    pub count: Count,
    /// `[μ_v, 1]` per VSGL.
    pub centres: wgpu::Buffer,
    /// The [`GpuVsglStatus`] of the frame.
    pub status: wgpu::Buffer,
}

impl GpuVsgls {
    /// Validates (as [`GpuVsgl::new`]) and uploads `vsgls`, each a light.
    pub fn upload(ctx: &GpuContext, vsgls: &[VsglInput]) -> Result<Self, GpuError> {
        let count = u32::try_from(vsgls.len())
            .map_err(|_| GpuError::Input(format!("{} VSGLs exceed u32", vsgls.len())))?;
        let packed = vsgls
            .iter()
            .enumerate()
            .map(|(i, v)| GpuVsgl::new(v, i))
            .collect::<Result<Vec<_>, _>>()?;
        let centres: Vec<[f32; 4]> = vsgls.iter().map(|v| v.mu.extend(1.0).to_array()).collect();
        Ok(Self {
            buffer: upload(ctx, "vsgls", &packed)?,
            count: Count::Host(count),
            centres: upload(ctx, "vsgl centres", &centres)?,
            status: upload(ctx, "vsgl status", &[GpuVsglStatus::clear(count)])?,
        })
    }
}

/// The compiled VSGL shading pipeline.
pub struct VsglShadePass {
    pipeline: wgpu::ComputePipeline,
    visible: wgpu::ComputePipeline,
    specular_table: wgpu::Buffer,
}

/// What the visibility entry point binds besides the shading inputs.
type Visibility<'a> = (&'a wgpu::Buffer, &'a ImperfectShadowMaps);

impl VsglShadePass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("vsgl shade pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("vsgl_shade", SOURCE),
                visible: ctx.compute_pipeline_entry("vsgl_shade_visible", SOURCE, "main_visible"),
                specular_table: specular_table::buffer(ctx),
            })
        })
    }

    /// Shades an uploaded CPU G-buffer and reads the image back: the GPU twin of
    /// `shade_vsgls(tracer, gbuffer, vsgls, false, …)`. Every sample is first checked by
    /// `SgSurface::new`, the CPU's own check.
    pub fn shade(
        &self,
        ctx: &GpuContext,
        gbuffer: &GBuffer,
        vsgls: &GpuVsgls,
    ) -> Result<Image, GpuError> {
        self.shade_cpu_gbuffer(ctx, gbuffer, vsgls, None)
    }

    /// [`Self::shade`] with visibility from `maps` (one per VSGL, [`crate::vsgl::ism`]): the
    /// GPU twin of `shade_vsgls(tracer, gbuffer, vsgls, true, …)` with imperfect shadow maps
    /// for its shadow rays.
    pub fn shade_visible(
        &self,
        ctx: &GpuContext,
        gbuffer: &GBuffer,
        vsgls: &GpuVsgls,
        maps: &ImperfectShadowMaps,
    ) -> Result<Image, GpuError> {
        self.shade_cpu_gbuffer(ctx, gbuffer, vsgls, Some(maps))
    }

    fn shade_cpu_gbuffer(
        &self,
        ctx: &GpuContext,
        gbuffer: &GBuffer,
        vsgls: &GpuVsgls,
        maps: Option<&ImperfectShadowMaps>,
    ) -> Result<Image, GpuError> {
        let pixels = u64::from(gbuffer.width) * u64::from(gbuffer.height);
        if pixels != gbuffer.samples.len() as u64 || u32::try_from(pixels).is_err() {
            return Err(GpuError::Input(format!(
                "G-buffer of {}x{} pixels has {} samples",
                gbuffer.width,
                gbuffer.height,
                gbuffer.samples.len()
            )));
        }
        for (p, s) in gbuffer.samples.iter().enumerate() {
            if let Some(s) = s {
                SgSurface::new(s.normal, s.omega_o, &s.brdf)
                    .map_err(|e| GpuError::Input(format!("G-buffer pixel {p}: {e}")))?;
                if !s.position.is_finite() {
                    return Err(GpuError::Input(format!(
                        "G-buffer pixel {p}: position {} is not finite",
                        s.position
                    )));
                }
            }
        }
        let samples: Vec<GpuSample> = gbuffer
            .samples
            .iter()
            .map(|s| GpuSample::new(s.as_ref()))
            .collect();
        let positions: Vec<[f32; 4]> = gbuffer
            .samples
            .iter()
            .map(|s| gpu_position(s.as_ref()))
            .collect();
        let samples = upload(ctx, "gbuffer samples", &samples)?;
        let positions = upload(ctx, "gbuffer positions", &positions)?;
        let normals = match maps {
            Some(maps) => {
                let normals: Vec<[f32; 4]> = gbuffer
                    .samples
                    .iter()
                    .map(|s| {
                        s.as_ref().map_or([0.0; 4], |s| {
                            let n = s.geometric_normal;
                            [n.x, n.y, n.z, 0.0]
                        })
                    })
                    .collect();
                Some((upload(ctx, "gbuffer geometric normals", &normals)?, maps))
            }
            None => None,
        };
        let (rgb, _) = self.shade_buffers(
            ctx,
            (&samples, &positions),
            pixels as u32,
            vsgls,
            normals.as_ref().map(|(n, m)| (n, *m)),
        )?;
        read_image(ctx, &rgb, gbuffer.width, gbuffer.height)
    }

    /// Shades a G-buffer rendered on the GPU ([`crate::frame::raster::gbuffer::GbufferPass`]) where it
    /// lies, with visibility from `maps` (see [`Self::shade_visible`]; read from the
    /// G-buffer's geometric normals) or without; the image stays on the GPU as RGB, 3 f32 per
    /// pixel row-major (what `frame::denoise::DenoisePass::filter_on_gpu` reads; see
    /// [`read_image`]). Waits for the pass to read the frame's fault record, and gives the
    /// number of lights it counts.
    pub fn shade_gpu_gbuffer_on_gpu(
        &self,
        ctx: &GpuContext,
        gbuffer: &GpuGBuffer,
        vsgls: &GpuVsgls,
        maps: Option<&ImperfectShadowMaps>,
    ) -> Result<(wgpu::Buffer, u32), GpuError> {
        let pixels = u64::from(gbuffer.width) * u64::from(gbuffer.height);
        let pixels = u32::try_from(pixels)
            .map_err(|_| GpuError::Input(format!("{pixels} pixels exceed u32")))?;
        self.shade_buffers(
            ctx,
            (&gbuffer.samples, &gbuffer.positions),
            pixels,
            vsgls,
            maps.map(|m| (&gbuffer.geometric_normals, m)),
        )
    }

    /// Shades the [`GpuSample`]s and positions (one per pixel) into an RGB buffer, then reads
    /// the frame's fault record and turns its faults into errors; gives the number of lights.
    fn shade_buffers(
        &self,
        ctx: &GpuContext,
        (samples, positions): (&wgpu::Buffer, &wgpu::Buffer),
        pixels: u32,
        vsgls: &GpuVsgls,
        visibility: Option<Visibility>,
    ) -> Result<(wgpu::Buffer, u32), GpuError> {
        let capacity = vsgls.count.capacity();
        ctx.check_loop_budget(
            || format!("shading {capacity} VSGLs at every pixel"),
            ITERATIONS_PER_VSGL * u64::from(capacity) + 64,
            "lower --vsgls",
        )?;
        if let Some((_, maps)) = visibility {
            if maps.params.map_count != capacity {
                return Err(GpuError::Input(format!(
                    "{} shadow maps for {capacity} VSGLs",
                    maps.params.map_count
                )));
            }
        }
        let out = output::<f32>(ctx, "vsgl indirect image", 3 * pixels as usize)?;
        // The shading's own faults start clear (the construction's stay with the lights).
        ctx.queue.write_buffer(
            &vsgls.status,
            0,
            bytemuck::cast_slice(&[u32::MAX, u32::MAX]),
        );
        if pixels > 0 {
            let params = GpuVsglParams {
                pixel_count: pixels,
                vsgl_count: capacity,
                pad: [0; 2],
            };
            let grid = Grid::for_items(ctx, u64::from(pixels), WORKGROUP)?;
            ctx.submit("vsgl_shade", |encoder| {
                let at = std::mem::offset_of!(GpuVsglParams, vsgl_count);
                let params = vsgls
                    .count
                    .uniform(ctx, encoder, "vsgl params", &params, at);
                let mut buffers = vec![
                    &params,
                    samples,
                    positions,
                    &vsgls.buffer,
                    &out,
                    &vsgls.status,
                ];
                let ism;
                let (label, pipeline) = match visibility {
                    None => ("vsgl_shade", &self.pipeline),
                    Some((normals, maps)) => {
                        ism = maps.params_buffer(ctx);
                        buffers.extend([normals, &ism, &maps.depth]);
                        ("vsgl_shade_visible", &self.visible)
                    }
                };
                let mut bound: Vec<_> = (0u32..).zip(buffers).collect();
                bound.push((specular_table::BINDING, &self.specular_table));
                ctx.encode_dispatch_at(encoder, label, pipeline, &bound, grid);
                Ok(())
            })?;
        }
        let [state] =
            <[GpuVsglStatus; 1]>::try_from(read_back(ctx, "vsgl status", &vsgls.status, 1)?)
                .map_err(|_| GpuError::Readback {
                    label: "vsgl status".into(),
                    message: "short read".into(),
                })?;
        Ok((out, state.lights()?))
    }
}

#[cfg(test)]
mod tests {
    use slc_bounds::sg::{GGX_MIXTURE, MIXTURE_FROM, STRETCH_MIN_COS, STRETCH_SHARPNESS};

    /// The WGSL mixture and stretch constants are the Rust ones.
    #[test]
    fn wgsl_declares_the_rust_mixture() {
        let wgsl = include_str!("vsgl_light.wesl");
        let sgs: Vec<String> = GGX_MIXTURE
            .iter()
            .map(|m| format!("vec2<f32>({:?}, {:?})", m.sharpness_scale, m.weight))
            .collect();
        for line in [
            format!(
                "const GGX_MIXTURE = array<vec2<f32>, {}>({});",
                GGX_MIXTURE.len(),
                sgs.join(", ")
            ),
            format!("const MIXTURE_FROM: f32 = {MIXTURE_FROM:?};"),
            format!("const STRETCH_MIN_COS: f32 = {STRETCH_MIN_COS:?};"),
            format!("const STRETCH_SHARPNESS: f32 = {STRETCH_SHARPNESS:?};"),
        ] {
            assert!(wgsl.lines().any(|l| l == line), "missing: {line}");
        }
    }
}
