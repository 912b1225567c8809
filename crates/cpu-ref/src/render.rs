//! One frame of the CPU reference: G-buffer, reflective shadow maps, VPLs, direct light and
//! indirect light by VPLs (exact, or stochastic with culling, interleaving and denoising), by
//! lights sampled from the RSMs (VSGLs, or VPLs at equal count), or by path tracing, averaged
//! over `spp` passes.
//!
//! The stages are public so that a comparison can prepare a frame once and shade it with
//! every culling strategy from the same G-buffer, VPLs and ξ ([`prepare`], [`shade_stochastic`]).
use crate::denoise::{cross_bilateral, BilateralParams};
use crate::direct::shade_direct;
use crate::gbuffer::{trace_gbuffer, PixelSample};
use crate::path::trace_pixel_sample;
use crate::rsm::{trace_rsm, Rsm, TexelSample};
use crate::sampled_lights::{shade_sampled_vpls, shade_vsgl, LightSampling};
use crate::tracer::Tracer;
use crate::vpl_shading::{shade_lists, shade_vpls, VplEstimator};
use crate::vpls::{generate_vpls, LobeSelection};
use crate::vsgl::VsglError;
use rayon::prelude::*;
use slc_core::rng::pcg_hash;
use slc_core::{
    Camera, CullError, CullInput, GBuffer, Image, Interleaving, Scene, SceneError, Vpl,
};
use slc_cull::metrics::{measure, CullMetrics};
use std::time::Instant;

/// The stochastic estimate of eq. (3) as the paper renders it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stochastic {
    /// δ of eq. (2).
    pub delta: f32,
    /// A name from `slc_cull::CULLER_NAMES`.
    pub culling: &'static str,
    /// K of K x K interleaved sampling (1: off).
    pub interleave: u32,
    /// Cross bilateral filter after shading.
    pub denoise: bool,
    /// Measure true/false positives and misses by brute force (costs a full pass over pairs).
    pub metrics: bool,
}

/// How indirect light is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Every VPL at every pixel with p = 1: the all-VPL reference.
    VplReference,
    /// The stochastic estimate with culling.
    Stochastic(Stochastic),
    /// Path-traced one-bounce reference (no VPLs).
    Path,
    /// Virtual spherical Gaussian lights sampled from the mipmapped RSMs (Tokuyoshi 2015,
    /// [`crate::sampled_lights::shade_vsgl`]).
    Vsgl(LightSampling),
    /// VPLs of texels sampled with the same importance and points as [`Method::Vsgl`], the
    /// equal-count VPL estimator ([`crate::sampled_lights::shade_sampled_vpls`]).
    SampledVpls(LightSampling),
}

/// The largest number of sampled lights (or camera-side VSGLs) a frame accepts.
pub const MAX_SAMPLED_LIGHTS: u32 = 1 << 24;

/// What to render.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// RSM resolution per face (texels per side).
    pub rsm_resolution: u32,
    pub seed: u32,
    pub method: Method,
    /// Shadow rays between VPLs and pixels (VPL methods; the path method always has visibility).
    pub visibility: bool,
    /// Passes averaged. With 1, primary rays go through pixel centres and RSM rays through texel
    /// centres (what a rasterizer does); with more, both are jittered, each pass with its own
    /// VPLs and ξ, so the average converges to the one-bounce solution (box pixel filter).
    pub spp: u32,
    pub lobes: LobeSelection,
}

/// A rendered frame with what it cost.
#[derive(Clone, Debug)]
pub struct Frame {
    pub direct: Image,
    pub indirect: Image,
    /// VPLs per pass (0 for the path method).
    pub vpl_count: usize,
    /// Milliseconds per pass, summed over the passes, in the order they ran.
    pub timings: Timings,
    /// Culling metrics of the last pass, when asked for.
    pub metrics: Option<CullMetrics>,
    /// Distinct sampled lights shaded in the last pass (VSGL and sampled-VPL methods).
    pub sampled_lights: Option<usize>,
}

/// Errors of rendering.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Bounds(#[from] slc_bounds::BoundsError),
    #[error(transparent)]
    Cull(#[from] CullError),
    #[error(transparent)]
    Vsgl(#[from] VsglError),
    #[error("invalid render settings: {0}")]
    Settings(String),
}

impl RenderSettings {
    /// Checks every number is in its domain.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |m: &str| Err(RenderError::Settings(m.to_string()));
        if self.width == 0 || self.height == 0 || self.width > 16384 || self.height > 16384 {
            return bad("width and height must be in 1..=16384");
        }
        if self.rsm_resolution == 0 || self.rsm_resolution > 4096 {
            return bad("the RSM resolution must be in 1..=4096");
        }
        if self.spp == 0 {
            return bad("spp must be at least 1");
        }
        if let Method::Stochastic(s) = self.method {
            if !(s.delta.is_finite() && s.delta > 0.0) {
                return bad("delta must be finite and positive");
            }
            if s.interleave == 0 || s.interleave > 64 {
                return bad("the interleaving K must be in 1..=64");
            }
            if slc_cull::culler_by_name(s.culling).is_none() {
                return Err(RenderError::Settings(format!(
                    "unknown culling strategy '{}' (one of {})",
                    s.culling,
                    slc_cull::CULLER_NAMES.join(", ")
                )));
            }
        }
        if let Method::Vsgl(l) | Method::SampledVpls(l) = self.method {
            if l.count > MAX_SAMPLED_LIGHTS {
                return Err(RenderError::Settings(format!(
                    "at most {MAX_SAMPLED_LIGHTS} sampled lights"
                )));
            }
            if let crate::sampled_lights::Importance::Bidirectional { camera_vsgls } = l.importance
            {
                if camera_vsgls == 0 || camera_vsgls > MAX_SAMPLED_LIGHTS {
                    return Err(RenderError::Settings(format!(
                        "the bidirectional importance needs 1..={MAX_SAMPLED_LIGHTS} camera VSGLs"
                    )));
                }
            }
            if self.lobes != LobeSelection::Both {
                return bad("sampled lights (VSGLs) carry both lobes: the lobes must be both");
            }
        }
        Ok(())
    }
}

/// Milliseconds per named pass, summed when a pass runs again.
#[derive(Clone, Debug, Default)]
pub struct Timings(pub Vec<(&'static str, f64)>);

impl Timings {
    pub fn time<T>(&mut self, name: &'static str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        self.add(name, start.elapsed().as_secs_f64() * 1e3);
        out
    }

    pub fn add(&mut self, name: &'static str, ms: f64) {
        match self.0.iter_mut().find(|(n, _)| *n == name) {
            Some((_, t)) => *t += ms,
            None => self.0.push((name, ms)),
        }
    }

    pub fn merge(&mut self, other: &Timings) {
        for &(n, t) in &other.0 {
            self.add(n, t);
        }
    }

    /// The sum of every pass.
    pub fn total(&self) -> f64 {
        self.0.iter().map(|(_, t)| t).sum()
    }
}

/// A frame up to its VPLs and direct light: what every indirect method starts from.
pub struct Prepared {
    pub camera: Camera,
    pub tracer: Tracer,
    pub gbuffer: GBuffer,
    /// The reflective shadow maps, one per light in the scene's order.
    pub maps: Vec<Rsm>,
    pub vpls: Vec<Vpl>,
    pub direct: Image,
    pub timings: Timings,
}

/// Traces the G-buffer and the RSMs, makes the VPLs (ξ from `seed`) and the direct light.
/// `pass` = `None` samples pixel and texel centres; `Some(p)` jitters both for pass p.
pub fn prepare(
    scene: &Scene,
    settings: &RenderSettings,
    tracer: Tracer,
    pass: Option<u32>,
) -> Prepared {
    let (w, h) = (settings.width, settings.height);
    let camera = scene.camera_or_default();
    let mut timings = Timings::default();
    let (sample, texel_sample, seed) = match pass {
        None => (PixelSample::Centre, TexelSample::Centre, settings.seed),
        Some(p) => (
            PixelSample::Jittered {
                seed: settings.seed,
                index: p,
            },
            TexelSample::Jittered {
                seed: settings.seed,
                pass: p,
            },
            settings.seed ^ pcg_hash(p),
        ),
    };
    let gbuffer = timings.time("gbuffer", || {
        trace_gbuffer(scene, &tracer, &camera, w, h, sample)
    });
    let maps: Vec<_> = timings.time("rsm", || {
        scene
            .lights
            .iter()
            .map(|l| trace_rsm(scene, &tracer, l, settings.rsm_resolution, texel_sample))
            .collect()
    });
    let vpls = timings.time("vpl_generation", || {
        generate_vpls(&maps, seed, settings.lobes)
    });
    let direct = timings.time("direct", || shade_direct(&tracer, &scene.lights, &gbuffer));
    Prepared {
        camera,
        tracer,
        gbuffer,
        maps,
        vpls,
        direct,
        timings,
    }
}

/// The result of shading a prepared frame stochastically.
pub struct StochasticFrame {
    pub indirect: Image,
    pub metrics: Option<CullMetrics>,
    pub timings: Timings,
}

/// Culls and shades a prepared frame with the stochastic estimate, then denoises.
pub fn shade_stochastic(
    p: &Prepared,
    s: &Stochastic,
    seed: u32,
    visibility: bool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<StochasticFrame, RenderError> {
    let culler = slc_cull::culler_by_name(s.culling).ok_or_else(|| {
        RenderError::Settings(format!("unknown culling strategy '{}'", s.culling))
    })?;
    let interleaving = Interleaving {
        k: s.interleave,
        seed,
    };
    let input = CullInput {
        gbuffer: &p.gbuffer,
        camera: &p.camera,
        vpls: &p.vpls,
        delta: s.delta,
        interleaving,
    };
    let mut timings = Timings::default();
    let lists = timings.time("culling", || culler.cull(&input))?;
    let mut indirect = timings.time("shading", || {
        shade_lists(&p.tracer, &input, &lists, visibility, progress)
    })?;
    if s.denoise {
        indirect = timings.time("denoise", || {
            cross_bilateral(&indirect, &p.gbuffer, BilateralParams::default())
        });
    }
    let metrics = s.metrics.then(|| measure(&input, &lists)).transpose()?;
    Ok(StochasticFrame {
        indirect,
        metrics,
        timings,
    })
}

/// Renders `scene`. `progress` is called with the number of pixel-passes finished; the total is
/// `width * height * spp`.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Frame, RenderError> {
    settings.validate()?;
    scene.validate_for_render()?;
    let (w, h) = (settings.width, settings.height);
    let mut timings = Timings::default();
    let mut tracer = Some(timings.time("bvh", || Tracer::new(scene)));
    let mut direct = Image::new(w, h);
    let mut indirect = Image::new(w, h);
    let (mut vpl_count, mut metrics, mut sampled_lights) = (0, None, None);
    for pass in 0..settings.spp {
        if settings.method == Method::Path {
            let camera = scene.camera_or_default();
            let tracer = tracer.as_ref().expect("the tracer is kept for path passes");
            let pixels: Vec<_> = timings.time("path", || {
                (0..h)
                    .into_par_iter()
                    .flat_map_iter(|j| {
                        let row: Vec<_> = (0..w)
                            .map(|i| {
                                trace_pixel_sample(
                                    scene,
                                    tracer,
                                    &camera,
                                    j * w + i,
                                    (w, h),
                                    settings.seed,
                                    pass,
                                )
                            })
                            .collect();
                        progress(w as u64);
                        row
                    })
                    .collect()
            });
            for (k, (d, ind)) in pixels.into_iter().enumerate() {
                direct.pixels[k] += d;
                indirect.pixels[k] += ind;
            }
            continue;
        }
        let jitter = (settings.spp > 1).then_some(pass);
        let p = prepare(
            scene,
            settings,
            tracer
                .take()
                .expect("the tracer comes back after each pass"),
            jitter,
        );
        timings.merge(&p.timings);
        vpl_count = p.vpls.len();
        let seed = jitter.map_or(settings.seed, |j| settings.seed ^ pcg_hash(j));
        let ind = match settings.method {
            Method::Stochastic(s) => {
                let f = shade_stochastic(&p, &s, seed, settings.visibility, progress)?;
                timings.merge(&f.timings);
                metrics = f.metrics;
                f.indirect
            }
            Method::Vsgl(l) | Method::SampledVpls(l) => {
                let shade = if matches!(settings.method, Method::Vsgl(_)) {
                    shade_vsgl
                } else {
                    shade_sampled_vpls
                };
                let f = shade(&p, &l, seed, settings.visibility, progress)?;
                timings.merge(&f.timings);
                sampled_lights = Some(f.lights);
                f.indirect
            }
            _ => timings.time("vpl_shading", || {
                shade_vpls(
                    &p.tracer,
                    &p.gbuffer,
                    &p.vpls,
                    VplEstimator::Exact,
                    settings.visibility,
                    progress,
                )
            })?,
        };
        direct = direct.add(&p.direct);
        indirect = indirect.add(&ind);
        tracer = Some(p.tracer);
    }
    let inv = 1.0 / settings.spp as f32;
    for p in direct.pixels.iter_mut().chain(indirect.pixels.iter_mut()) {
        *p *= inv;
    }
    Ok(Frame {
        direct,
        indirect,
        vpl_count,
        timings,
        metrics,
        sampled_lights,
    })
}
