//! The `--backend gpu` frame: every pass on the GPU (wgpu) — the rasterized G-buffer, the
//! RSMs (also the shadow maps), VPL generation, direct light, culling by any strategy with
//! light lists that stay on the GPU, shading and the cross bilateral filter — as
//! `slc_cpu_ref::render` composes the CPU passes. What comes back to the CPU: the VPLs once
//! per frame (the culler's bounds pass reads them from the CPU), the images, and the
//! G-buffer and lists where the brute-force metrics or `slc compare`'s CPU reference need
//! them. With `--shader vsgl` the RSMs are read back instead of culling: the VSGLs are built
//! and sampled on the CPU (`slc_cpu_ref::vsgl`) and shaded on the GPU
//! (`slc_gpu_wgpu::vsgl_shade_pass`), with `--visibility` weighted by imperfect shadow maps
//! to each VSGL's `μ_v` (`slc_gpu_wgpu::ism_pass`).
//!
//! Pass times (`timings_ms`) are wall clock around each pass, its uploads, readbacks and the
//! wait for completion included, under the CPU's pass names; where the adapter has timestamp
//! queries the GPU's execution time of the same passes is returned beside them
//! (`gpu_timings_ms` in the report).
use crate::gpu_vsgl::{cpu_rsm, vsgl_input};
use crate::report::Device;
use slc_bounds::sg::MeanMap;
use slc_core::rng::{pcg_hash, stream, uniform};
use slc_core::{Camera, CullInput, GBuffer, Image, Interleaving, Scene, Vpl};
use slc_cpu_ref::sampled_lights::{sample_vsgls, Importance, SampledFrame};
use slc_cpu_ref::vsgl::{bidirectional_importance, ImportanceMap, MipRsm};
use slc_cpu_ref::{
    Frame, LightSampling, LobeSelection, Method, Prepared, RenderSettings, Stochastic,
    StochasticFrame, Timings, Tracer,
};
use slc_cull::metrics::measure;
use slc_gpu_wgpu::cull_frame::{read_lists, CullFrame};
use slc_gpu_wgpu::culler::{GpuCuller, Strategy};
use slc_gpu_wgpu::denoise_pass::{BilateralSettings, DenoisePass, Guide};
use slc_gpu_wgpu::direct_pass::DirectPass;
use slc_gpu_wgpu::gbuffer_pass::{GbufferPass, GpuGBuffer};
use slc_gpu_wgpu::ism_pass::{caster_points, GpuCaster, IsmPass, IsmSettings};
use slc_gpu_wgpu::rsm_pass::{GpuRsm, RsmPass};
use slc_gpu_wgpu::scene_upload::GpuScene;
use slc_gpu_wgpu::shade_pass::read_image;
use slc_gpu_wgpu::shade_pass::ShadePass;
use slc_gpu_wgpu::vpl_gen_pass::{VplGenPass, VplLobes};
use slc_gpu_wgpu::vsgl_shade_pass::{GpuVsgls, VsglShadePass};
use slc_gpu_wgpu::{GpuContext, GpuError};
use std::cell::OnceCell;

/// The GPU twin of the CPU culling strategy `culling` (every name of
/// `slc_cull::Strategy::ALL` has one).
pub fn gpu_strategy(culling: &str) -> Result<Strategy, String> {
    Strategy::by_name(culling).ok_or_else(|| {
        format!(
            "unknown culling strategy '{culling}' (choose one of {})",
            slc_cull::Strategy::ALL.join(", ")
        )
    })
}

/// Refuses options the GPU backend does not have: shadow rays between VPLs and pixels.
/// `--visibility` is accepted where the GPU shades VSGLs (`vsgl`): VSGL eq. 3's `V(x_p, μ_v)`
/// from imperfect shadow maps.
pub fn check_visibility(visibility: bool, vsgl: bool) -> Result<(), String> {
    if visibility && !vsgl {
        return Err(
            "--visibility with --backend gpu is only for --shader vsgl (imperfect shadow \
             maps to the VSGLs); shadow rays to VPLs are not on the GPU, render with \
             --backend cpu"
                .into(),
        );
    }
    Ok(())
}

/// The report note of a GPU VSGL frame without visibility: what ran where.
pub const VSGL_GPU_NOTE: &str =
    "--shader vsgl: the RSMs were read back, the VSGLs built and sampled on the CPU (vsgl_mip, \
     importance_map, light_sampling) and shaded on the GPU (light_shading) instead of culling \
     and VPL shading; without --visibility GPU VSGL shading has no visibility term";

/// The report note of a GPU VSGL frame: [`VSGL_GPU_NOTE`], and with `visibility` what the
/// GPU used for it.
pub fn vsgl_gpu_note(visibility: bool) -> String {
    if !visibility {
        return VSGL_GPU_NOTE.into();
    }
    let s = IsmSettings::paper(0.0);
    format!(
        "--shader vsgl: the RSMs were read back, the VSGLs built and sampled on the CPU \
         (vsgl_mip, importance_map, light_sampling) and shaded on the GPU (light_shading) \
         instead of culling and VPL shading; --visibility on the GPU: V(x_p, mu_v) from \
         imperfect shadow maps (shadow_maps; {} caster points sampled by area, one {}x{} \
         octahedral distance map per VSGL, depth bias {} + {} tan(incidence) texels), not \
         the CPU's shadow rays: light leaks through gaps and small occluders and contact \
         shadows within the bias are lost",
        s.points, s.resolution, s.resolution, s.bias_constant, s.bias_slope
    )
}

fn gpu_err(e: GpuError) -> String {
    e.to_string()
}

/// A frame prepared on the GPU up to its VPLs and direct light: the twin of
/// `slc_cpu_ref::Prepared`, its G-buffer left on the GPU.
pub struct GpuPrepared {
    pub camera: Camera,
    pub gbuffer: GpuGBuffer,
    /// The RSMs, one per light in the scene's order (VSGLs are built from them).
    pub maps: Vec<GpuRsm>,
    pub vpls: Vec<Vpl>,
    pub direct: Image,
    pub timings: Timings,
    /// Timestamp times of the passes, where the adapter has them.
    pub gpu_timings: Option<Timings>,
    /// The G-buffer read back, once something on the CPU needs it.
    cpu_gbuffer: OnceCell<GBuffer>,
}

impl GpuPrepared {
    fn cpu_gbuffer(&self, ctx: &GpuContext) -> Result<&GBuffer, String> {
        if let Some(g) = self.cpu_gbuffer.get() {
            return Ok(g);
        }
        let g = self.gbuffer.read_back(ctx).map_err(gpu_err)?;
        Ok(self.cpu_gbuffer.get_or_init(|| g))
    }
}

/// The device and the compiled GPU passes, created once per command.
pub struct GpuFrame {
    ctx: GpuContext,
    gbuffer: GbufferPass,
    rsm: RsmPass,
    vpl_gen: VplGenPass,
    direct: DirectPass,
    culler: GpuCuller,
    shader: ShadePass,
    vsgl_shader: VsglShadePass,
    ism: IsmPass,
    denoiser: DenoisePass,
}

impl GpuFrame {
    /// Opens the adapter and compiles the passes; no adapter is an error suggesting
    /// `--backend cpu`.
    pub fn new() -> Result<Self, String> {
        let ctx = GpuContext::new().map_err(gpu_err)?;
        Ok(Self {
            gbuffer: GbufferPass::new(&ctx).map_err(gpu_err)?,
            rsm: RsmPass::new(&ctx).map_err(gpu_err)?,
            vpl_gen: VplGenPass::new(&ctx).map_err(gpu_err)?,
            direct: DirectPass::new(&ctx).map_err(gpu_err)?,
            culler: GpuCuller::new(&ctx).map_err(gpu_err)?,
            shader: ShadePass::new(&ctx).map_err(gpu_err)?,
            vsgl_shader: VsglShadePass::new(&ctx).map_err(gpu_err)?,
            ism: IsmPass::new(&ctx).map_err(gpu_err)?,
            denoiser: DenoisePass::new(&ctx).map_err(gpu_err)?,
            ctx,
        })
    }

    /// What the report of a GPU VSGL frame says: [`Self::device`] and [`vsgl_gpu_note`].
    pub fn vsgl_device(&self, visibility: bool) -> Device {
        let mut device = self.device(false);
        device.notes.push(vsgl_gpu_note(visibility));
        device
    }

    /// The caster points of the imperfect shadow maps of `scene` (`IsmSettings::paper`).
    pub fn ism_casters(scene: &Scene) -> (Vec<GpuCaster>, IsmSettings) {
        let settings = IsmSettings::paper(Tracer::scene_epsilon(scene));
        (caster_points(scene, &settings), settings)
    }

    /// What the report says about this backend: the adapter and where each pass ran.
    pub fn device(&self, metrics: bool) -> Device {
        let mut notes = vec![
            format!(
                "every pass ran on the GPU ({}): G-buffer and RSMs by rasterization (visibility \
                 buffer resolved by the pixel's own ray), VPL generation, direct light with the \
                 RSM depth as shadow maps, culling (light lists kept on the GPU), shading and \
                 the cross bilateral filter",
                self.ctx.adapter_name
            ),
            "the VPLs are read back once per frame for the culler's bounds pass; the images \
             are read back at the end of the frame"
                .to_string(),
            if self.ctx.timestamps_trusted {
                "timings_ms of GPU passes are wall clock around the GPU work (uploads, readbacks \
                 and the wait for completion included); gpu_timings_ms are the GPU's execution \
                 times of the same passes from timestamp queries"
                    .to_string()
            } else if self.ctx.timestamps {
                "this adapter's timestamp queries are not used: on a CPU adapter (lavapipe) they \
                 stop bracketing compute work once a render pass has run; GPU pass times are \
                 wall clock around the GPU work (uploads, readbacks and the wait for completion \
                 included) and gpu_timings_ms is null"
                    .to_string()
            } else {
                "this adapter has no timestamp queries: GPU pass times are wall clock around the \
                 GPU work (uploads, readbacks and the wait for completion included) and \
                 gpu_timings_ms is null"
                    .to_string()
            },
        ];
        if metrics {
            notes.push(
                "metrics were measured by brute force on the CPU against the GPU's light lists \
                 and G-buffer, read back after the timed passes"
                    .to_string(),
            );
        }
        Device {
            backend: "gpu",
            adapter: self.ctx.adapter_name.clone(),
            notes,
        }
    }

    /// Uploads `scene`'s triangles, materials and textures.
    pub fn upload(&self, scene: &Scene) -> Result<GpuScene, String> {
        GpuScene::upload(&self.ctx, scene).map_err(gpu_err)
    }

    /// Times `f` under `name` (wall clock, waiting for the GPU) and attributes its passes to
    /// the stage `name`.
    fn pass<T>(
        &self,
        timings: &mut Timings,
        name: &'static str,
        f: impl FnOnce() -> Result<T, GpuError>,
    ) -> Result<T, String> {
        self.ctx.set_stage(name);
        timings
            .time(name, || {
                let out = f()?;
                self.ctx.wait()?;
                Ok(out)
            })
            .map_err(gpu_err)
    }

    /// Rasterizes the G-buffer and the RSMs, makes the VPLs and the direct light: the GPU twin
    /// of `slc_cpu_ref::prepare`. `pass` = `None` samples pixel and texel centres; `Some(p)`
    /// shifts every pixel's sample by one offset for pass p (a rasterizer has one sub-pixel
    /// offset per frame, where the CPU jitters each pixel) and keeps texel centres, with the
    /// CPU's per-pass VPL seed.
    pub fn prepare(
        &self,
        scene: &Scene,
        gpu_scene: &GpuScene,
        settings: &RenderSettings,
        pass: Option<u32>,
    ) -> Result<GpuPrepared, String> {
        let (w, h) = (settings.width, settings.height);
        let camera = scene.camera_or_default();
        let (offset, seed) = match pass {
            None => ((0.5, 0.5), settings.seed),
            Some(p) => (
                (
                    uniform(settings.seed, u32::MAX, stream::PIXEL, 2 * p),
                    uniform(settings.seed, u32::MAX, stream::PIXEL, 2 * p + 1),
                ),
                settings.seed ^ pcg_hash(p),
            ),
        };
        let lobes = match settings.lobes {
            LobeSelection::Both => VplLobes::Both,
            LobeSelection::Diffuse => VplLobes::Diffuse,
            LobeSelection::Glossy => VplLobes::Glossy,
        };
        let ctx = &self.ctx;
        let profiling = ctx.timestamps_trusted && ctx.start_profiling();
        let mut timings = Timings::default();
        let gbuffer = self.pass(&mut timings, "gbuffer", || {
            self.gbuffer.render(ctx, gpu_scene, &camera, w, h, offset)
        })?;
        let maps = self.pass(&mut timings, "rsm", || {
            scene
                .lights
                .iter()
                .map(|l| self.rsm.render(ctx, gpu_scene, l, settings.rsm_resolution))
                .collect::<Result<Vec<_>, _>>()
        })?;
        let vpls = self.pass(&mut timings, "vpl_generation", || {
            self.vpl_gen
                .generate(ctx, &maps, seed, lobes)?
                .read_back(ctx)
        })?;
        let direct = self.pass(&mut timings, "direct", || {
            self.direct.render(ctx, gpu_scene, &gbuffer, &maps)
        })?;
        let profile = ctx.finish_profiling().map_err(gpu_err)?;
        Ok(GpuPrepared {
            camera,
            gbuffer,
            maps,
            vpls,
            direct,
            timings,
            gpu_timings: profiling.then_some(Timings(profile.stages)),
            cpu_gbuffer: OnceCell::new(),
        })
    }

    /// The prepared frame as the CPU reference's `Prepared` (G-buffer read back), for what
    /// only the CPU computes: the all-VPL reference and the unculled estimate of
    /// `slc compare`.
    pub fn to_cpu(&self, p: &GpuPrepared, tracer: Tracer) -> Result<Prepared, String> {
        Ok(Prepared {
            camera: p.camera.clone(),
            tracer,
            gbuffer: p.cpu_gbuffer(&self.ctx)?.clone(),
            maps: p
                .maps
                .iter()
                .map(|m| cpu_rsm(&self.ctx, m))
                .collect::<Result<_, _>>()
                .map_err(gpu_err)?,
            vpls: p.vpls.clone(),
            direct: p.direct.clone(),
            timings: p.timings.clone(),
        })
    }

    /// Culls, shades and denoises a prepared frame on the GPU: the GPU twin of
    /// `slc_cpu_ref::shade_stochastic` without visibility. Also returns the GPU's timestamp
    /// times of its passes, where the adapter has trustworthy ones.
    pub fn shade(
        &self,
        p: &GpuPrepared,
        s: &Stochastic,
        seed: u32,
    ) -> Result<(StochasticFrame, Option<Timings>), String> {
        let strategy = gpu_strategy(s.culling)?;
        let interleaving = Interleaving {
            k: s.interleave,
            seed,
        };
        let ctx = &self.ctx;
        let g = &p.gbuffer;
        let mut timings = Timings::default();
        let profiling = ctx.timestamps_trusted && ctx.start_profiling();
        let lists = self.pass(&mut timings, "culling", || {
            let frame = CullFrame::on_gpu(g, &p.vpls, s.delta, interleaving);
            self.culler.cull_frame(ctx, &frame, strategy)
        })?;
        let mut rgb = self.pass(&mut timings, "shading", || {
            self.shader
                .shade_gpu_gbuffer_on_gpu(ctx, g, &p.vpls, s.delta, interleaving, &lists)
        })?;
        if s.denoise {
            rgb = self.pass(&mut timings, "denoise", || {
                let guide = Guide {
                    samples: &g.samples,
                    positions: &g.positions,
                    width: g.width,
                    height: g.height,
                    camera: &g.camera,
                };
                self.denoiser
                    .filter_on_gpu(ctx, &rgb, &guide, &BilateralSettings::default())
            })?;
        }
        let profile = ctx.finish_profiling().map_err(gpu_err)?;
        let indirect = read_image(ctx, &rgb, g.width, g.height).map_err(gpu_err)?;
        let metrics = if s.metrics {
            let input = CullInput {
                gbuffer: p.cpu_gbuffer(ctx)?,
                camera: &p.camera,
                vpls: &p.vpls,
                delta: s.delta,
                interleaving,
            };
            let read = read_lists(ctx, &lists).map_err(gpu_err)?;
            Some(measure(&input, &read).map_err(|e| e.to_string())?)
        } else {
            None
        };
        Ok((
            StochasticFrame {
                indirect,
                metrics,
                timings,
            },
            profiling.then_some(Timings(profile.stages)),
        ))
    }

    /// Indirect light from `s.count` VSGLs on a prepared frame, as
    /// `slc_cpu_ref::sampled_lights::shade_vsgl` computes it without visibility: the RSMs read
    /// back (`rsm_readback`), the Toksvig mipmaps (`vsgl_mip`), the flux or bidirectional
    /// importance (`importance_map`; the latter reads the G-buffer back) and the filtered
    /// importance sampling of clusters (`light_sampling`) on the CPU, then the analytic
    /// shading of eq. (2)-(5) on the GPU (`light_shading`, VSGL upload included). `epsilon` is
    /// the scene's ray offset ([`Tracer::scene_epsilon`]): `σ_v²` is floored at its square,
    /// as the CPU's `sigma2_floor` does. With `ism` (caster points and settings,
    /// [`Self::ism_casters`]) an imperfect shadow map per VSGL is rendered (`shadow_maps`) and
    /// the shading weighted by its visibility, where the CPU's `shade_vsgl` traces shadow rays.
    pub fn shade_vsgl(
        &self,
        p: &GpuPrepared,
        s: &LightSampling,
        seed: u32,
        epsilon: f32,
        ism: Option<&(Vec<GpuCaster>, IsmSettings)>,
    ) -> Result<SampledFrame, String> {
        let ctx = &self.ctx;
        let mut timings = Timings::default();
        let floor = epsilon * epsilon;
        let maps = self.pass(&mut timings, "rsm_readback", || {
            p.maps
                .iter()
                .map(|m| cpu_rsm(ctx, m))
                .collect::<Result<Vec<_>, _>>()
        })?;
        let mips = timings
            .time("vsgl_mip", || {
                maps.iter()
                    .map(|rsm| MipRsm::build(rsm, MeanMap::Toksvig))
                    .collect::<Result<Vec<_>, _>>()
            })
            .map_err(|e| e.to_string())?;
        let importance = match s.importance {
            Importance::Flux => timings.time("importance_map", || {
                mips.iter().map(ImportanceMap::from_mip).collect::<Vec<_>>()
            }),
            Importance::Bidirectional { camera_vsgls } => {
                let gbuffer = p.cpu_gbuffer(ctx)?;
                timings
                    .time("importance_map", || {
                        bidirectional_importance(
                            gbuffer,
                            &p.camera,
                            &maps,
                            camera_vsgls,
                            seed,
                            floor,
                            s.diffuse,
                        )
                    })
                    .map_err(|e| e.to_string())?
            }
        };
        let vsgls = timings
            .time("light_sampling", || {
                sample_vsgls(&mips, &importance, s.count, seed, floor)
            })
            .map_err(|e| e.to_string())?;
        let g = &p.gbuffer;
        let maps = ism
            .map(|(casters, settings)| {
                self.pass(&mut timings, "shadow_maps", || {
                    let centres: Vec<_> = vsgls.iter().map(|v| v.mu).collect();
                    let maps = self.ism.render(ctx, casters, &centres, settings)?;
                    ctx.wait()?;
                    Ok(maps)
                })
            })
            .transpose()?;
        let rgb = self.pass(&mut timings, "light_shading", || {
            let inputs: Vec<_> = vsgls.iter().map(|v| vsgl_input(v, s.diffuse)).collect();
            let uploaded = GpuVsgls::upload(ctx, &inputs)?;
            match &maps {
                Some(maps) => self
                    .vsgl_shader
                    .shade_gpu_gbuffer_visible_on_gpu(ctx, g, &uploaded, maps),
                None => self.vsgl_shader.shade_gpu_gbuffer_on_gpu(ctx, g, &uploaded),
            }
        })?;
        let indirect = read_image(ctx, &rgb, g.width, g.height).map_err(gpu_err)?;
        Ok(SampledFrame {
            indirect,
            lights: vsgls.len(),
            timings,
        })
    }

    /// Renders `scene` with the stochastic estimate of `settings` as `slc_cpu_ref::render`
    /// does (the same passes and seeds for `spp` > 1), every pass but the filter on the GPU;
    /// with the GPU's timestamp times of its passes, summed over the passes, where it has
    /// them.
    pub fn render(
        &self,
        scene: &Scene,
        settings: &RenderSettings,
    ) -> Result<(Frame, Option<Timings>), String> {
        settings.validate().map_err(|e| e.to_string())?;
        scene.validate_for_render().map_err(|e| e.to_string())?;
        check_visibility(
            settings.visibility,
            matches!(settings.method, Method::Vsgl(_)),
        )?;
        if !matches!(settings.method, Method::Stochastic(_) | Method::Vsgl(_)) {
            return Err(
                "references and sampled VPLs are rendered on the CPU only; use --backend cpu"
                    .into(),
            );
        }
        let epsilon = Tracer::scene_epsilon(scene);
        let (w, h) = (settings.width, settings.height);
        let mut timings = Timings::default();
        let gpu_scene = timings.time("upload", || self.upload(scene))?;
        let ism = (settings.visibility && matches!(settings.method, Method::Vsgl(_)))
            .then(|| timings.time("ism_points", || Self::ism_casters(scene)));
        let mut direct = Image::new(w, h);
        let mut indirect = Image::new(w, h);
        let (mut vpl_count, mut metrics, mut sampled_lights) = (0, None, None);
        let mut gpu_timings: Option<Timings> = None;
        let mut add_gpu = |t: Option<Timings>| {
            if let Some(t) = t {
                gpu_timings.get_or_insert_with(Timings::default).merge(&t);
            }
        };
        for pass in 0..settings.spp {
            let jitter = (settings.spp > 1).then_some(pass);
            let p = self.prepare(scene, &gpu_scene, settings, jitter)?;
            timings.merge(&p.timings);
            add_gpu(p.gpu_timings.clone());
            vpl_count = p.vpls.len();
            let seed = jitter.map_or(settings.seed, |j| settings.seed ^ pcg_hash(j));
            let ind = match settings.method {
                Method::Vsgl(l) => {
                    let f = self.shade_vsgl(&p, &l, seed, epsilon, ism.as_ref())?;
                    timings.merge(&f.timings);
                    sampled_lights = Some(f.lights);
                    f.indirect
                }
                Method::Stochastic(s) => {
                    let (f, gpu) = self.shade(&p, &s, seed)?;
                    timings.merge(&f.timings);
                    add_gpu(gpu);
                    metrics = f.metrics;
                    f.indirect
                }
                other => return Err(format!("{other:?} is not rendered on the GPU")),
            };
            direct = direct.add(&p.direct);
            indirect = indirect.add(&ind);
        }
        let inv = 1.0 / settings.spp as f32;
        for px in direct.pixels.iter_mut().chain(indirect.pixels.iter_mut()) {
            *px *= inv;
        }
        Ok((
            Frame {
                direct,
                indirect,
                vpl_count,
                timings,
                metrics,
                sampled_lights,
            },
            gpu_timings,
        ))
    }
}
