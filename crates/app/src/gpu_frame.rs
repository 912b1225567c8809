//! The `--backend gpu` frame of this version, a hybrid: the CPU reference prepares the frame
//! (BVH, G-buffer, RSM, VPLs, direct light), the GPU (wgpu) culls with tiled light lists that
//! stay on the GPU and shades from them, and the CPU's cross bilateral filter denoises.
//!
//! Pass times are wall clock around each GPU call, uploads, readbacks and the wait for
//! completion included (no timestamp queries), under the CPU's pass names.
use crate::report::Device;
use slc_core::rng::pcg_hash;
use slc_core::{CullInput, Image, Interleaving, Scene};
use slc_cpu_ref::denoise::{cross_bilateral, BilateralParams};
use slc_cpu_ref::{
    prepare, Frame, Method, Prepared, RenderSettings, Stochastic, StochasticFrame, Timings, Tracer,
};
use slc_cull::metrics::measure;
use slc_cull::GlossyBound;
use slc_gpu_wgpu::shade_pass::ShadePass;
use slc_gpu_wgpu::tiled_cull_pass::TiledCuller;
use slc_gpu_wgpu::GpuContext;

/// The culling strategies the GPU backend has, with the glossy bound each uses.
const GPU_STRATEGIES: [(&str, GlossyBound); 3] = [
    ("sphere", GlossyBound::Sphere),
    ("enclosing-sphere", GlossyBound::EnclosingSphere),
    ("ellipsoid", GlossyBound::Ellipsoid),
];

/// The glossy bound of `culling` on the GPU, or an error naming the strategies it has.
pub fn gpu_bound(culling: &str) -> Result<GlossyBound, String> {
    GPU_STRATEGIES
        .iter()
        .find(|(n, _)| *n == culling)
        .map(|(_, b)| *b)
        .ok_or_else(|| {
            let names: Vec<&str> = GPU_STRATEGIES.iter().map(|(n, _)| *n).collect();
            format!(
                "culling strategy '{culling}' is not available with --backend gpu (it has {}); \
                 choose one of those or render with --backend cpu",
                names.join(", ")
            )
        })
}

/// Refuses options the GPU backend does not have yet: shadow rays between VPLs and pixels.
pub fn check_visibility(visibility: bool) -> Result<(), String> {
    if visibility {
        return Err("--visibility (shadow rays to VPLs) is not on the GPU yet; \
                    render with --backend cpu"
            .into());
    }
    Ok(())
}

/// The device and the compiled GPU passes, created once per command.
pub struct GpuFrame {
    ctx: GpuContext,
    culler: TiledCuller,
    shader: ShadePass,
}

impl GpuFrame {
    /// Opens the adapter and compiles the passes; no adapter is an error suggesting
    /// `--backend cpu`.
    pub fn new() -> Result<Self, String> {
        let ctx = GpuContext::new().map_err(|e| e.to_string())?;
        let culler = TiledCuller::new(&ctx).map_err(|e| e.to_string())?;
        let shader = ShadePass::new(&ctx).map_err(|e| e.to_string())?;
        Ok(Self {
            ctx,
            culler,
            shader,
        })
    }

    /// What the report says about this backend: the adapter and where each pass ran.
    pub fn device(&self, metrics: bool) -> Device {
        let mut notes = vec![
            format!(
                "culling (tiled, light lists kept on the GPU) and shading ran on the GPU \
                 ({})",
                self.ctx.adapter_name
            ),
            "bvh, gbuffer, rsm, vpl_generation, direct and denoise ran on the CPU".to_string(),
            "GPU pass times are wall clock around the GPU work (uploads, readbacks and the wait \
             for completion included), not timestamp queries"
                .to_string(),
        ];
        if metrics {
            notes.push(
                "metrics were measured on the GPU's light lists, read back from a second, \
                 untimed culling run of the same input"
                    .to_string(),
            );
        }
        Device {
            backend: "gpu",
            adapter: self.ctx.adapter_name.clone(),
            notes,
        }
    }

    /// Culls and shades a prepared frame on the GPU, then denoises on the CPU: the GPU twin
    /// of `slc_cpu_ref::shade_stochastic` without visibility.
    pub fn shade(
        &self,
        p: &Prepared,
        s: &Stochastic,
        seed: u32,
    ) -> Result<StochasticFrame, String> {
        let glossy = gpu_bound(s.culling)?;
        let input = CullInput {
            gbuffer: &p.gbuffer,
            camera: &p.camera,
            vpls: &p.vpls,
            delta: s.delta,
            interleaving: Interleaving {
                k: s.interleave,
                seed,
            },
        };
        let gpu = |e: slc_gpu_wgpu::GpuError| e.to_string();
        let mut timings = Timings::default();
        let lists = timings.time("culling", || {
            let lists = self.culler.cull_on_gpu(&self.ctx, &input, glossy)?;
            self.ctx.wait()?;
            Ok(lists)
        });
        let lists = lists.map_err(gpu)?;
        let indirect = timings.time("shading", || {
            self.shader.shade_gpu_lists(&self.ctx, &input, &lists)
        });
        let mut indirect = indirect.map_err(gpu)?;
        if s.denoise {
            indirect = timings.time("denoise", || {
                cross_bilateral(&indirect, &p.gbuffer, BilateralParams::default())
            });
        }
        let metrics = if s.metrics {
            let read = self.culler.cull(&self.ctx, &input, glossy).map_err(gpu)?;
            Some(measure(&input, &read).map_err(|e| e.to_string())?)
        } else {
            None
        };
        Ok(StochasticFrame {
            indirect,
            metrics,
            timings,
        })
    }

    /// Renders `scene` with the stochastic estimate of `settings` as `slc_cpu_ref::render`
    /// does (the same passes, jitter and seeds for `spp` > 1), culling and shading on the GPU.
    pub fn render(&self, scene: &Scene, settings: &RenderSettings) -> Result<Frame, String> {
        settings.validate().map_err(|e| e.to_string())?;
        scene.validate_for_render().map_err(|e| e.to_string())?;
        check_visibility(settings.visibility)?;
        let Method::Stochastic(s) = settings.method else {
            return Err("references are rendered on the CPU only; use --backend cpu".into());
        };
        let (w, h) = (settings.width, settings.height);
        let mut timings = Timings::default();
        let mut tracer = Some(timings.time("bvh", || Tracer::new(scene)));
        let mut direct = Image::new(w, h);
        let mut indirect = Image::new(w, h);
        let (mut vpl_count, mut metrics) = (0, None);
        for pass in 0..settings.spp {
            let jitter = (settings.spp > 1).then_some(pass);
            let taken = tracer
                .take()
                .expect("the tracer comes back after each pass");
            let p = prepare(scene, settings, taken, jitter);
            timings.merge(&p.timings);
            vpl_count = p.vpls.len();
            let seed = jitter.map_or(settings.seed, |j| settings.seed ^ pcg_hash(j));
            let f = self.shade(&p, &s, seed)?;
            timings.merge(&f.timings);
            metrics = f.metrics;
            direct = direct.add(&p.direct);
            indirect = indirect.add(&f.indirect);
            tracer = Some(p.tracer);
        }
        let inv = 1.0 / settings.spp as f32;
        for px in direct.pixels.iter_mut().chain(indirect.pixels.iter_mut()) {
            *px *= inv;
        }
        Ok(Frame {
            direct,
            indirect,
            vpl_count,
            timings,
            metrics,
            sampled_lights: None,
        })
    }
}
