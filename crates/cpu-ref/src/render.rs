//! One frame of the CPU reference: G-buffer, reflective shadow maps, VPLs, direct light and
//! indirect light by VPLs or by path tracing, averaged over `spp` passes.
use crate::direct::shade_direct;
use crate::gbuffer::{trace_gbuffer, PixelSample};
use crate::path::trace_pixel_sample;
use crate::rsm::{trace_rsm, TexelSample};
use crate::tracer::Tracer;
use crate::vpl_shading::{shade_vpls, VplEstimator};
use crate::vpls::{generate_vpls, LobeSelection};
use rayon::prelude::*;
use slc_core::rng::pcg_hash;
use slc_core::{Image, Scene, SceneError};
use std::time::Instant;

/// How indirect light is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// VPLs from reflective shadow maps, every VPL at every pixel.
    Vpl(VplEstimator),
    /// Path-traced one-bounce reference (no VPLs).
    Path,
}

/// What to render.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// RSM resolution per face (texels per side).
    pub rsm_resolution: u32,
    pub seed: u32,
    pub method: Method,
    /// Shadow rays between VPLs and pixels (VPL method only; the path method always has visibility).
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
    /// Milliseconds per pass name, summed over the passes, in the order they ran.
    pub timings_ms: Vec<(&'static str, f64)>,
}

/// Errors of rendering.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Bounds(#[from] slc_bounds::BoundsError),
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
        if let Method::Vpl(VplEstimator::Stochastic { delta }) = self.method {
            if !(delta.is_finite() && delta > 0.0) {
                return bad("delta must be finite and positive");
            }
        }
        Ok(())
    }
}

struct Timer(Vec<(&'static str, f64)>);

impl Timer {
    fn time<T>(&mut self, name: &'static str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        let ms = start.elapsed().as_secs_f64() * 1e3;
        match self.0.iter_mut().find(|(n, _)| *n == name) {
            Some((_, t)) => *t += ms,
            None => self.0.push((name, ms)),
        }
        out
    }
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
    let camera = scene.camera_or_default();
    let mut timer = Timer(Vec::new());
    let tracer = timer.time("bvh", || Tracer::new(scene));
    let mut direct = Image::new(w, h);
    let mut indirect = Image::new(w, h);
    let mut vpl_count = 0;
    let jitter = settings.spp > 1;
    for pass in 0..settings.spp {
        let pass_seed = settings.seed ^ pcg_hash(pass);
        match settings.method {
            Method::Path => {
                let pixels: Vec<_> = timer.time("path", || {
                    (0..h)
                        .into_par_iter()
                        .flat_map_iter(|j| {
                            let row: Vec<_> = (0..w)
                                .map(|i| {
                                    trace_pixel_sample(
                                        scene,
                                        &tracer,
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
            }
            Method::Vpl(estimator) => {
                let sample = if jitter {
                    PixelSample::Jittered {
                        seed: settings.seed,
                        index: pass,
                    }
                } else {
                    PixelSample::Centre
                };
                let gbuffer = timer.time("gbuffer", || {
                    trace_gbuffer(scene, &tracer, &camera, w, h, sample)
                });
                let texel_sample = if jitter {
                    TexelSample::Jittered {
                        seed: settings.seed,
                        pass,
                    }
                } else {
                    TexelSample::Centre
                };
                let maps: Vec<_> = timer.time("rsm", || {
                    scene
                        .lights
                        .iter()
                        .map(|l| {
                            trace_rsm(scene, &tracer, l, settings.rsm_resolution, texel_sample)
                        })
                        .collect()
                });
                let vpls = timer.time("vpl_generation", || {
                    generate_vpls(&maps, pass_seed, settings.lobes)
                });
                vpl_count = vpls.len();
                let d = timer.time("direct", || shade_direct(&tracer, &scene.lights, &gbuffer));
                let ind = timer.time("vpl_shading", || {
                    shade_vpls(
                        &tracer,
                        &gbuffer,
                        &vpls,
                        estimator,
                        settings.visibility,
                        progress,
                    )
                })?;
                direct = direct.add(&d);
                indirect = indirect.add(&ind);
            }
        }
    }
    let inv = 1.0 / settings.spp as f32;
    for p in direct.pixels.iter_mut().chain(indirect.pixels.iter_mut()) {
        *p *= inv;
    }
    let total: f64 = timer.0.iter().map(|(_, t)| t).sum();
    timer.0.push(("total", total));
    Ok(Frame {
        direct,
        indirect,
        vpl_count,
        timings_ms: timer.0,
    })
}
