//! A CPU frame up to its VPLs and direct light: the ray-traced G-buffer, the reflective
//! shadow maps, the VPLs with their ξ and the direct light, which every indirect method
//! starts from. A comparison prepares a frame once and shades it with every culling strategy
//! from the same G-buffer, VPLs and ξ.
use crate::direct::shade_direct_watched;
use crate::gbuffer::{trace_gbuffer_watched, PixelSample};
use crate::rsm::{trace_rsm, Rsm, TexelSample};
use crate::tracer::Tracer;
use crate::vpls::generate_vpls;
use slc_core::frame::{PreparedData, RenderError, RenderSettings, Timings};
use slc_core::render::pass_seed;
use slc_core::{
    Camera, CullInput, GBuffer, Image, Interleaving, PreparedFrame, Progress, Scene, Vpl,
};
use std::sync::Arc;

/// A CPU frame up to its VPLs and direct light.
#[derive(Clone)]
pub struct CpuPrepared {
    pub camera: Camera,
    /// The scene's BVH, shared by every frame of the scene.
    pub tracer: Arc<Tracer>,
    pub gbuffer: GBuffer,
    /// The reflective shadow maps, one per light in the scene's order.
    pub maps: Vec<Rsm>,
    pub vpls: Vec<Vpl>,
    pub direct: Image,
    pub timings: Timings,
}

impl CpuPrepared {
    /// A frame another backend prepared ([`PreparedData`]), with `tracer`, the BVH of its scene.
    pub fn from_data(data: PreparedData, tracer: Arc<Tracer>) -> Self {
        let PreparedData {
            camera,
            gbuffer,
            maps,
            vpls,
            direct,
            timings,
        } = data;
        Self {
            camera,
            tracer,
            gbuffer,
            maps,
            vpls,
            direct,
            timings,
        }
    }

    /// What culling and shading read of this frame: its G-buffer, camera and VPLs with the
    /// roulette's δ and the interleaving.
    pub fn cull_input(&self, delta: f32, interleaving: Interleaving) -> CullInput<'_> {
        CullInput {
            gbuffer: &self.gbuffer,
            camera: &self.camera,
            vpls: &self.vpls,
            delta,
            interleaving,
        }
    }
}

impl PreparedFrame for CpuPrepared {
    fn camera(&self) -> &Camera {
        &self.camera
    }

    fn vpl_count(&self) -> Result<usize, RenderError> {
        Ok(self.vpls.len())
    }

    fn vpls(&self) -> Result<&[Vpl], RenderError> {
        Ok(&self.vpls)
    }

    fn direct(&self) -> &Image {
        &self.direct
    }

    fn timings(&self) -> &Timings {
        &self.timings
    }
}

/// Traces the G-buffer and the RSMs, makes the VPLs (ξ from the seed) and the direct light.
/// `pass` = `None` samples pixel and texel centres; `Some(p)` jitters both for pass p.
pub fn prepare(
    scene: &Scene,
    settings: &RenderSettings,
    tracer: impl Into<Arc<Tracer>>,
    pass: Option<u32>,
) -> CpuPrepared {
    prepare_watched(scene, settings, tracer, pass, &|_| {})
}

/// [`prepare`] that stops tracing once `progress` is cancelled: the G-buffer's and the direct
/// light's pixels not yet begun are left empty (the caller checks `progress`).
pub fn prepare_watched(
    scene: &Scene,
    settings: &RenderSettings,
    tracer: impl Into<Arc<Tracer>>,
    pass: Option<u32>,
    progress: Progress,
) -> CpuPrepared {
    let tracer = tracer.into();
    let (w, h) = (settings.width, settings.height);
    let camera = scene.camera_or_default();
    let mut timings = Timings::default();
    let (sample, texel_sample) = match pass {
        None => (PixelSample::Centre, TexelSample::Centre),
        Some(p) => (
            PixelSample::Jittered {
                seed: settings.seed,
                index: p,
            },
            TexelSample::Jittered {
                seed: settings.seed,
                pass: p,
            },
        ),
    };
    let gbuffer = timings.time("gbuffer", || {
        trace_gbuffer_watched(scene, &tracer, &camera, (w, h), sample, progress)
    });
    let maps: Vec<_> = timings.time("rsm", || {
        scene
            .lights
            .iter()
            .map(|l| trace_rsm(scene, &tracer, l, settings.rsm_resolution, texel_sample))
            .collect()
    });
    let vpls = timings.time("vpl_generation", || {
        generate_vpls(&maps, pass_seed(settings.seed, pass), settings.lobes)
    });
    let direct = timings.time("direct", || {
        shade_direct_watched(&tracer, &scene.lights, &gbuffer, progress)
    });
    CpuPrepared {
        camera,
        tracer,
        gbuffer,
        maps,
        vpls,
        direct,
        timings,
    }
}
