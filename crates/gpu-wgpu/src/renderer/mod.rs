//! The GPU backend of the renderer API: [`GpuRenderer`] runs every step of
//! `slc_core::Renderer` on wgpu — the rasterized G-buffer, the RSMs (also the shadow maps),
//! VPL generation, direct light, culling by any strategy (the tiled ones culled and shaded
//! in one pass, [`crate::shade::tiled`]; the others with light lists that stay on the
//! GPU), shading and the cross bilateral filter — on a device it opens
//! ([`GpuRenderer::new`]) or one the host owns ([`GpuRenderer::from_context`] with
//! [`GpuContext::from_device`]). What comes back to the CPU: the images, the fault record of
//! the culling or VSGL passes after the shading, the VPL count when asked (after the frame,
//! for its report; right after VPL generation where the culling's per-VPL buffers sized by
//! the room generation leaves would outgrow a binding, `GpuVpls::fit_capacity`), and the
//! G-buffer, VPLs and lists where the brute-force metrics or a CPU
//! reference need them ([`GpuRenderer::read_frame`]). VSGLs are built from the RSMs where they lie
//! ([`crate::vsgl::build`]) and shaded there ([`crate::vsgl::shade`]), with visibility
//! from imperfect shadow maps to each VSGL's `μ_v` ([`crate::vsgl::ism`]).
//!
//! Pass times are wall clock around each step, its uploads, readbacks and the wait for
//! completion included; where the adapter has trustworthy timestamp queries the GPU's
//! execution times of the same passes come beside them.
pub mod limits;
mod notes;

use crate::cull::bounds::BoundsPass;
use crate::cull::frame::CullFrame;
use crate::cull::lists::read_lists;
use crate::cull::{Culled, GpuCulling, ListCulling};
use crate::device::context::{GpuContext, GpuError};
use crate::frame::denoise::{DenoisePass, Guide};
use crate::frame::light::direct::DirectPass;
use crate::frame::light::rsm::{GpuRsm, RsmLayout, RsmPass};
use crate::frame::raster::gbuffer::{GbufferPass, GpuGBuffer};
use crate::frame::raster::scene::GpuScene;
use crate::renderer::notes::{
    cluster_raster_note, frame_notes, one_pass_note, vsgl_note, METRICS_NOTE, SPLAT_NOTE,
};
use crate::shade::lists::{read_image, ShadePass, ShadedGBuffer};
use crate::shade::tiled::TiledShadePass;
use crate::vpl::generate::{GpuVpls, VplGenPass, VplLobes};
use crate::vsgl::build::{VsglBuildPass, VsglSampling};
use crate::vsgl::ism::{caster_points, GpuCaster, IsmPass, IsmSettings};
use crate::vsgl::readback::cpu_rsm;
use crate::vsgl::shade::VsglShadePass;
use slc_core::frame::{
    BilateralParams, Importance, LightSampling, Method, PassTime, PreparedData, RenderError,
    RenderSettings, Shaded, Timings,
};
use slc_core::render::pass_seed;
use slc_core::rng::{stream, uniform};
use slc_core::shader::SampledLights;
use slc_core::{
    BackendInfo, Camera, Capabilities, CullInput, CullMetrics, GBuffer, Image, Interleaving,
    PreparedFrame, Progress, Renderer, Scene, Strategy, Vpl,
};
use std::cell::{OnceCell, RefCell};
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

fn gpu(e: GpuError) -> RenderError {
    RenderError::backend(e)
}

/// A scene as the GPU keeps it between frames.
pub struct GpuLoadedScene {
    /// Triangles, materials and textures in GPU buffers.
    pub gpu: GpuScene,
    /// The scene's ray offset ([`Scene::ray_epsilon`]).
    pub epsilon: f32,
    /// Caster points of the imperfect shadow maps, made when VSGL visibility first needs them.
    casters: OnceCell<(Vec<GpuCaster>, IsmSettings)>,
}

/// A frame prepared on the GPU up to its VPLs and direct light, its G-buffer and RSMs left
/// on the GPU.
pub struct GpuPrepared {
    pub camera: Camera,
    pub gbuffer: GpuGBuffer,
    /// The RSMs, one per light in the scene's order (VSGLs are built from them).
    pub maps: Vec<GpuRsm>,
    /// The VPLs, generated on the GPU and left there.
    pub vpls: GpuVpls,
    pub direct: Image,
    pub timings: Timings,
    /// Timestamp times of the passes, where the adapter has trustworthy ones.
    pub gpu_timings: Option<Timings>,
    /// The G-buffer read back, once something on the CPU needs it.
    cpu_gbuffer: OnceCell<GBuffer>,
    /// The VPLs read back, once something on the CPU needs them.
    cpu_vpls: OnceCell<Vec<Vpl>>,
    /// Their number read back (after the frame, for its report), once asked for.
    vpl_count: OnceCell<usize>,
    ctx: Arc<GpuContext>,
}

impl PreparedFrame for GpuPrepared {
    fn camera(&self) -> &Camera {
        &self.camera
    }

    fn vpl_count(&self) -> Result<usize, RenderError> {
        if let Some(v) = self.cpu_vpls.get() {
            return Ok(v.len());
        }
        if let Some(&n) = self.vpl_count.get() {
            return Ok(n);
        }
        let n = self.vpls.read_count(&self.ctx).map_err(gpu)? as usize;
        Ok(*self.vpl_count.get_or_init(|| n))
    }

    fn vpls(&self) -> Result<&[Vpl], RenderError> {
        if let Some(v) = self.cpu_vpls.get() {
            return Ok(v);
        }
        let v = self.vpls.read_back(&self.ctx).map_err(gpu)?;
        Ok(self.cpu_vpls.get_or_init(|| v))
    }

    fn direct(&self) -> &Image {
        &self.direct
    }

    fn timings(&self) -> &Timings {
        &self.timings
    }

    fn gpu_timings(&self) -> Option<&Timings> {
        self.gpu_timings.as_ref()
    }
}

/// The device and the compiled GPU passes, created once and used for every frame.
pub struct GpuRenderer {
    ctx: Arc<GpuContext>,
    gbuffer: GbufferPass,
    rsm: RsmPass,
    vpl_gen: VplGenPass,
    direct: DirectPass,
    culler: GpuCulling,
    shader: ShadePass,
    tiled_shader: TiledShadePass,
    vsgl_build: VsglBuildPass,
    vsgl_shader: VsglShadePass,
    ism: IsmPass,
    denoiser: DenoisePass,
    /// Whether the tiled strategies are culled and shaded in one pass
    /// ([`GpuCulling::one_pass`]); else into light lists, shaded by a second pass.
    one_pass: bool,
    /// The passes of the last profiled run ([`Renderer::last_pass_times`]).
    last_passes: Mutex<Option<Vec<PassTime>>>,
}

impl GpuRenderer {
    /// Opens the first adapter wgpu finds and compiles the passes; no adapter is
    /// [`GpuError::NoAdapter`].
    pub fn new() -> Result<Self, GpuError> {
        Self::from_context(GpuContext::new()?)
    }

    /// Compiles the passes on `ctx`, e.g. a host's device ([`GpuContext::from_device`]); a
    /// device whose limits fall below [`GpuContext::required_limits`] is refused first, each
    /// limit named ([`GpuError::Limits`]).
    pub fn from_context(ctx: GpuContext) -> Result<Self, GpuError> {
        ctx.check_limits()?;
        Ok(Self {
            gbuffer: GbufferPass::new(&ctx)?,
            rsm: RsmPass::new(&ctx)?,
            vpl_gen: VplGenPass::new(&ctx)?,
            direct: DirectPass::new(&ctx)?,
            culler: GpuCulling::new(&ctx)?,
            shader: ShadePass::new(&ctx)?,
            tiled_shader: TiledShadePass::new(&ctx),
            vsgl_build: VsglBuildPass::new(&ctx)?,
            vsgl_shader: VsglShadePass::new(&ctx)?,
            ism: IsmPass::new(&ctx)?,
            denoiser: DenoisePass::new(&ctx)?,
            ctx: Arc::new(ctx),
            one_pass: true,
            last_passes: Mutex::new(None),
        })
    }

    /// The same renderer with the tiled strategies culled and shaded in one pass (`true`, the
    /// default: `shade::tiled`, the paper's Fig. 2) or culled into light lists and shaded
    /// by a second pass (`false`: `cull::tiled` and `shade::lists`, to compare the two).
    /// Both shade the same VPLs in the same order: the images are the same.
    pub fn with_one_pass(mut self, one_pass: bool) -> Self {
        self.set_one_pass(one_pass);
        self
    }

    /// [`Self::with_one_pass`] on a renderer kept between frames.
    pub fn set_one_pass(&mut self, one_pass: bool) {
        self.one_pass = one_pass;
    }

    /// The same renderer with clustered-raster's shell pass rasterized conservatively in
    /// hardware (`true`, the default, where the adapter has it) or in software (`false`):
    /// the same lists and image, at another cost
    /// ([`ClusterRasterizer::set_hardware`](crate::cull::raster::clusters::ClusterRasterizer::set_hardware)).
    pub fn with_hardware_conservative(self, hardware: bool) -> Self {
        self.culler.rasterizer().set_hardware(hardware);
        self
    }

    /// Sets the room the list cullers leave for the next frames' lists
    /// ([`GpuCulling::set_list_room`]).
    pub fn set_list_room(&self, entries: u32) {
        self.culler.set_list_room(entries);
    }

    /// The device the passes run on.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// Runs `f` as the pass `stage` (timestamp profiles attribute its work to it) and waits
    /// for the GPU, so wall-clock times around it are the pass's.
    fn step<T>(
        &self,
        stage: &'static str,
        f: impl FnOnce() -> Result<T, GpuError>,
    ) -> Result<T, RenderError> {
        self.ctx.set_stage(stage);
        let out = f().map_err(gpu)?;
        self.ctx.wait().map_err(gpu)?;
        Ok(out)
    }

    fn cpu_gbuffer<'a>(&self, p: &'a GpuPrepared) -> Result<&'a GBuffer, RenderError> {
        if let Some(g) = p.cpu_gbuffer.get() {
            return Ok(g);
        }
        let g = p.gbuffer.read_back(&self.ctx).map_err(gpu)?;
        Ok(p.cpu_gbuffer.get_or_init(|| g))
    }

    fn cull_frame<'a>(p: &'a GpuPrepared, delta: f32, interleaving: Interleaving) -> CullFrame<'a> {
        CullFrame::on_gpu(&p.gbuffer, &p.vpls, delta, interleaving)
    }
}

impl GpuRenderer {
    /// The backend's name in reports and errors ([`Renderer::name`]).
    pub const NAME: &'static str = "gpu";

    /// What the backend has on an adapter with every feature it uses
    /// ([`Renderer::capabilities`] says what it has on its own): no shadow rays between VPLs
    /// and pixels, no references, no sampled VPLs.
    pub const CAPABILITIES: Capabilities = Capabilities {
        vpl_visibility: false,
        vsgl_visibility: true,
        references: false,
        sampled_vpls: false,
        tight_culling: true,
        raster_culling: true,
    };
}

impl Renderer for GpuRenderer {
    type Scene = GpuLoadedScene;
    type Prepared = GpuPrepared;
    type Lists = Culled;
    type Image = wgpu::Buffer;

    fn name(&self) -> &'static str {
        Self::NAME
    }

    fn capabilities(&self) -> Capabilities {
        Capabilities {
            // Splatting sums by blending into f32 targets (`cull::raster::splat`).
            raster_culling: self
                .ctx
                .device
                .features()
                .contains(wgpu::Features::FLOAT32_BLENDABLE),
            ..Self::CAPABILITIES
        }
    }

    fn check(&self, settings: &RenderSettings) -> Result<(), RenderError> {
        self.capabilities().check(self.name(), settings)?;
        limits::check_frame_size(&self.ctx, settings)
    }

    fn info(&self, settings: &RenderSettings) -> BackendInfo {
        let mut notes = frame_notes(&self.ctx);
        if let Method::Stochastic(s) = settings.method {
            if self.one_pass && GpuCulling::one_pass(s.strategy) {
                notes.push(one_pass_note(self.tiled_shader.subgroups()));
            }
            match s.strategy {
                Strategy::Splatting => notes.push(SPLAT_NOTE.into()),
                Strategy::ClusteredRaster => {
                    notes.push(cluster_raster_note(self.culler.rasterizer().hardware()))
                }
                _ => {}
            }
            if s.metrics {
                notes.push(METRICS_NOTE.into());
            }
        }
        if let Method::Vsgl(_) = settings.method {
            notes.push(vsgl_note(settings.visibility));
        }
        BackendInfo {
            backend: Self::NAME,
            adapter: self.ctx.adapter_name.clone(),
            notes,
        }
    }

    fn readback_bytes(&self) -> Option<BTreeMap<String, u64>> {
        Some(self.ctx.readback_bytes())
    }

    fn last_pass_times(&self) -> Option<Vec<PassTime>> {
        self.last_passes.lock().ok().and_then(|p| p.clone())
    }

    fn load(&self, scene: &Scene) -> Result<GpuLoadedScene, RenderError> {
        Ok(GpuLoadedScene {
            gpu: GpuScene::upload(&self.ctx, scene).map_err(gpu)?,
            epsilon: scene.ray_epsilon(),
            casters: OnceCell::new(),
        })
    }

    /// The twin of `slc_cpu_ref::prepare`. `pass` = `Some(p)` shifts every pixel's sample by
    /// one offset for pass p (a rasterizer has one sub-pixel offset per frame, where the CPU
    /// jitters each pixel) and keeps texel centres, with the CPU's per-pass VPL seed.
    /// `progress` is checked between the passes.
    fn prepare(
        &self,
        scene: &Scene,
        loaded: &GpuLoadedScene,
        settings: &RenderSettings,
        pass: Option<u32>,
        progress: Progress,
    ) -> Result<GpuPrepared, RenderError> {
        let (w, h) = (settings.width, settings.height);
        let camera = scene.camera_or_default();
        let offset = match pass {
            None => (0.5, 0.5),
            Some(p) => (
                uniform(settings.seed, u32::MAX, stream::PIXEL, 2 * p),
                uniform(settings.seed, u32::MAX, stream::PIXEL, 2 * p + 1),
            ),
        };
        let seed = pass_seed(settings.seed, pass);
        let lobes = VplLobes::from(settings.lobes);
        let (ctx, scene_gpu) = (&self.ctx, &loaded.gpu);
        let faces: Vec<usize> = (scene.lights.iter())
            .map(|l| RsmLayout::new(l, scene_gpu.bounds).faces.len())
            .collect();
        limits::check_scene_size(ctx, settings, &faces)?;
        let ((gbuffer, maps, vpls, direct, timings), gpu_timings) = self.profiled(|| {
            let mut t = Timings::default();
            let gbuffer = t.time("gbuffer", || {
                self.step("gbuffer", || {
                    self.gbuffer.render(ctx, scene_gpu, &camera, w, h, offset)
                })
            })?;
            progress.check()?;
            let maps = t.time("rsm", || {
                self.step("rsm", || {
                    scene
                        .lights
                        .iter()
                        .map(|l| self.rsm.render(ctx, scene_gpu, l, settings.rsm_resolution))
                        .collect::<Result<Vec<_>, _>>()
                })
            })?;
            progress.check()?;
            let (vpls, counted) = t.time("vpl_generation", || {
                self.step("vpl_generation", || {
                    let mut vpls = self.vpl_gen.generate(ctx, &maps, seed, lobes)?;
                    let counted = vpls.fit_capacity(ctx, BoundsPass::most_vpls(ctx))?;
                    Ok((vpls, counted))
                })
            })?;
            progress.check()?;
            let direct = t.time("direct", || {
                self.step("direct", || {
                    self.direct.render(ctx, scene_gpu, &gbuffer, &maps)
                })
            })?;
            Ok((gbuffer, maps, (vpls, counted), direct, t))
        })?;
        let (vpls, counted) = vpls;
        Ok(GpuPrepared {
            camera,
            gbuffer,
            maps,
            vpls,
            direct,
            timings,
            gpu_timings,
            cpu_gbuffer: OnceCell::new(),
            cpu_vpls: OnceCell::new(),
            // Read already where the VPLs' count sized their buffers: not read again.
            vpl_count: counted.map_or_else(OnceCell::new, |n| OnceCell::from(n as usize)),
            ctx: Arc::clone(&self.ctx),
        })
    }

    fn cull(
        &self,
        p: &GpuPrepared,
        strategy: Strategy,
        delta: f32,
        interleaving: Interleaving,
    ) -> Result<Culled, RenderError> {
        self.step("culling", || {
            let frame = Self::cull_frame(p, delta, interleaving);
            if self.one_pass || strategy.is_raster() {
                self.culler.prepare_frame(&self.ctx, &frame, strategy)
            } else {
                let lists = self.culler.cull_frame(&self.ctx, &frame, strategy)?;
                Ok(Culled::Lists(RefCell::new(lists), strategy))
            }
        })
    }

    fn shade_lists(
        &self,
        _loaded: &GpuLoadedScene,
        p: &GpuPrepared,
        lists: &Culled,
        delta: f32,
        interleaving: Interleaving,
        visibility: bool,
        progress: Progress,
    ) -> Result<wgpu::Buffer, RenderError> {
        if visibility {
            let needs = Capabilities {
                vpl_visibility: true,
                ..Capabilities::NONE
            };
            return Err(self.unsupported("shadow rays between VPLs and pixels (visibility)", needs));
        }
        let frame = Self::cull_frame(p, delta, interleaving);
        let samples = &p.gbuffer.samples;
        let image = self.step("shading", || match lists {
            Culled::Tiles(tiles) => self.tiled_shader.shade(&self.ctx, &frame, samples, tiles),
            Culled::Splats(tiles) => self
                .culler
                .splatter()
                .shade(&self.ctx, &frame, samples, tiles),
            Culled::Nodes(nodes) => self
                .culler
                .rasterizer()
                .shade(&self.ctx, &frame, samples, nodes),
            // The lists' totals are read after the shading; lists that outgrew their buffer
            // are culled again and shaded again (`cull::room`).
            Culled::Lists(lists, strategy) => {
                self.culler
                    .use_lists(&self.ctx, &frame, *strategy, lists, |l| {
                        self.shader.shade_on_gpu(
                            &self.ctx,
                            ShadedGBuffer::Gpu(&p.gbuffer),
                            &p.vpls,
                            delta,
                            interleaving,
                            l,
                        )
                    })
            }
        })?;
        // One dispatch shades every pixel: they are done together.
        progress.advance(u64::from(p.gbuffer.width) * u64::from(p.gbuffer.height));
        progress.check()?;
        Ok(image)
    }

    fn denoise(
        &self,
        p: &GpuPrepared,
        image: wgpu::Buffer,
        progress: Progress,
    ) -> Result<wgpu::Buffer, RenderError> {
        progress.check()?;
        let g = &p.gbuffer;
        self.step("denoise", || {
            let guide = Guide {
                samples: &g.samples,
                positions: &g.positions,
                width: g.width,
                height: g.height,
                camera: &g.camera,
            };
            self.denoiser
                .filter_on_gpu(&self.ctx, &image, &guide, &BilateralParams::default())
        })
    }

    fn read_image(&self, p: &GpuPrepared, image: wgpu::Buffer) -> Result<Image, RenderError> {
        read_image(&self.ctx, &image, p.gbuffer.width, p.gbuffer.height).map_err(gpu)
    }

    fn measure(
        &self,
        p: &GpuPrepared,
        lists: &Culled,
        delta: f32,
        interleaving: Interleaving,
    ) -> Result<CullMetrics, RenderError> {
        let lists = self
            .culler
            .frame_lists(&self.ctx, &Self::cull_frame(p, delta, interleaving), lists)
            .map_err(gpu)?;
        let input = CullInput {
            gbuffer: self.cpu_gbuffer(p)?,
            camera: &p.camera,
            vpls: p.vpls()?,
            delta,
            interleaving,
        };
        let read = read_lists(&self.ctx, &lists).map_err(gpu)?;
        Ok(slc_cull::metrics::measure(&input, &read)?)
    }

    /// VSGLs as `slc_cpu_ref::sampled_lights::shade_vsgl` computes them (sampled VPLs are
    /// CPU-only), built where the RSMs lie ([`crate::vsgl::build`]): the Toksvig mipmaps
    /// (`vsgl_mip`), the bidirectional importance (`importance_map`; the flux importance is
    /// the mipmaps' own weight) and the filtered importance sampling of clusters
    /// (`light_sampling`), `σ_v²` floored at the square of the scene's ray offset as the CPU's
    /// `sigma2_floor` does; then the analytic shading of eq. (2)-(5) (`light_shading`). With
    /// `visibility` an imperfect shadow map per VSGL is rendered from the VSGLs' centres
    /// (`shadow_maps`) and the shading weighted by its visibility, where the CPU traces shadow
    /// rays. What comes back: the image and the frame's 32-byte fault record (which also
    /// counts the lights).
    fn shade_sampled(
        &self,
        scene: &Scene,
        loaded: &GpuLoadedScene,
        p: &GpuPrepared,
        lights: SampledLights,
        s: &LightSampling,
        seed: u32,
        visibility: bool,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        if lights == SampledLights::Vpl {
            let needs = Capabilities {
                sampled_vpls: true,
                ..Capabilities::NONE
            };
            return Err(self.unsupported("sampled VPLs", needs));
        }
        let ctx = &self.ctx;
        let build = &self.vsgl_build;
        let mut timings = Timings::default();
        let sampling = VsglSampling {
            count: s.count,
            seed,
            sigma2_floor: loaded.epsilon * loaded.epsilon,
            diffuse: s.diffuse,
        };
        // Checked between the dispatches.
        progress.check()?;
        let mut mip = timings.time("vsgl_mip", || {
            self.step("vsgl_mip", || build.mip(ctx, &p.maps))
        })?;
        progress.check()?;
        timings.time("importance_map", || {
            self.step("importance_map", || match s.importance {
                Importance::Flux => Ok(()),
                Importance::Bidirectional { camera_vsgls } => {
                    build.bidirectional(ctx, &mut mip, &p.maps, &p.gbuffer, camera_vsgls, &sampling)
                }
            })
        })?;
        progress.check()?;
        let vsgls = timings.time("light_sampling", || {
            self.step("light_sampling", || build.sample(ctx, mip, &sampling))
        })?;
        let g = &p.gbuffer;
        let shadow_maps = if visibility {
            // Sampled once per scene; the first frame's `ism_points` carries the cost.
            let (casters, settings) = timings.time("ism_points", || {
                loaded.casters.get_or_init(|| {
                    let settings = IsmSettings::paper(loaded.epsilon);
                    (caster_points(scene, &settings), settings)
                })
            });
            Some(timings.time("shadow_maps", || {
                self.step("shadow_maps", || {
                    self.ism
                        .render_at(ctx, casters, &vsgls.centres, &vsgls.count, settings)
                })
            })?)
        } else {
            None
        };
        progress.check()?;
        let (rgb, lights) = timings.time("light_shading", || {
            self.step("light_shading", || {
                self.vsgl_shader
                    .shade_gpu_gbuffer_on_gpu(ctx, g, &vsgls, shadow_maps.as_ref())
            })
        })?;
        let indirect = read_image(ctx, &rgb, g.width, g.height).map_err(gpu)?;
        progress.advance(u64::from(g.width) * u64::from(g.height));
        progress.check()?;
        Ok(Shaded {
            sampled_lights: Some(lights as usize),
            listed_pairs: None,
            ..Shaded::new(indirect, timings)
        })
    }

    fn profiled<T>(
        &self,
        f: impl FnOnce() -> Result<T, RenderError>,
    ) -> Result<(T, Option<Timings>), RenderError> {
        let ctx = &self.ctx;
        let profiling = ctx.timestamps_trusted && ctx.start_profiling();
        let out = f();
        let profile = ctx.finish_profiling().map_err(gpu)?;
        if let Ok(mut last) = self.last_passes.lock() {
            *last = profiling.then(|| {
                profile
                    .passes
                    .iter()
                    .map(|&(stage, pass, ms, count)| PassTime {
                        stage,
                        pass,
                        ms,
                        count,
                    })
                    .collect()
            });
        }
        Ok((out?, profiling.then_some(Timings(profile.stages))))
    }
}

impl GpuRenderer {
    /// `p`'s data read back where the CPU can read it: the G-buffer, the RSMs, the VPLs and
    /// the direct light (what a CPU pass takes of a GPU frame).
    pub fn read_frame(&self, p: &GpuPrepared) -> Result<PreparedData, RenderError> {
        Ok(PreparedData {
            camera: p.camera.clone(),
            gbuffer: self.cpu_gbuffer(p)?.clone(),
            maps: p
                .maps
                .iter()
                .map(|m| cpu_rsm(&self.ctx, m))
                .collect::<Result<_, _>>()
                .map_err(gpu)?,
            vpls: p.vpls()?.to_vec(),
            direct: p.direct.clone(),
            timings: p.timings.clone(),
        })
    }
}
