//! A CPU frame up to its VPLs and direct light: the ray-traced G-buffer, the reflective
//! shadow maps, the VPLs with their ξ and the direct light, which every indirect method
//! starts from. A comparison prepares a frame once and shades it with every culling strategy
//! from the same G-buffer, VPLs and ξ.
use crate::direct::shade_direct_watched;
use crate::frame_images::Spare;
use crate::gbuffer::{trace_gbuffer_watched, PixelSample};
use crate::rsm::{trace_rsm, Rsm, TexelSample};
use crate::tracer::Tracer;
use crate::vpls::generate_vpls_into;
use glam::Vec3;
use slc_core::frame::{PreparedData, RenderError, RenderSettings, Timings};
use slc_core::render::pass_seed;
use slc_core::{
    Camera, CullInput, GBuffer, GSample, Image, Interleaving, PreparedFrame, Progress, Scene, Vpl,
};
use std::sync::Arc;

/// A CPU frame up to its VPLs and direct light. Made with [`FrameSpares`], it leaves its
/// largest buffers there when dropped, for the next frame. (It implements `Drop` for that,
/// so a field is moved out with `std::mem::take`; a clone leaves nothing.)
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
    spares: Option<FrameSpares>,
}

/// Where a renderer's prepared frames leave their largest buffers (the G-buffer's samples,
/// the VPLs and the direct light's pixels) when dropped, for the next frame to write into
/// (`blocks::par_blocks`): at 1920x1080 the samples alone are 216 MB, about 40 ms of page
/// faults a frame on two threads where memory written before costs none. A frame of another
/// size or light count reuses what fits (`frame_images::emptied`). The memory stays held
/// until the next frame takes it or [`FrameSpares::release`]. A clone starts empty and on
/// its own.
#[derive(Debug, Default)]
pub struct FrameSpares(Arc<Spare<FrameMemory>>);

impl Clone for FrameSpares {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// A dropped frame's buffers, emptied by the next frame that takes them.
#[derive(Default)]
struct FrameMemory {
    samples: Vec<Option<GSample>>,
    vpls: Vec<Vpl>,
    direct: Vec<Vec3>,
}

impl FrameSpares {
    /// A handle on the same memory (`Clone` gives new, empty spares).
    fn share(&self) -> Self {
        Self(Arc::clone(&self.0))
    }

    /// Frees the memory kept: the next frame is made in fresh memory, as the first is.
    pub fn release(&self) {
        self.0.take();
    }
}

impl Clone for CpuPrepared {
    fn clone(&self) -> Self {
        Self {
            camera: self.camera.clone(),
            tracer: Arc::clone(&self.tracer),
            gbuffer: self.gbuffer.clone(),
            maps: self.maps.clone(),
            vpls: self.vpls.clone(),
            direct: self.direct.clone(),
            timings: self.timings.clone(),
            spares: None,
        }
    }
}

impl Drop for CpuPrepared {
    fn drop(&mut self) {
        if let Some(spares) = &self.spares {
            spares.0.keep(FrameMemory {
                samples: std::mem::take(&mut self.gbuffer.samples),
                vpls: std::mem::take(&mut self.vpls),
                direct: std::mem::take(&mut self.direct.pixels),
            });
        }
    }
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
            spares: None,
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
    prepare_watched(scene, settings, tracer, pass, &|_| {}, None)
}

/// [`prepare`] that stops tracing once `progress` is cancelled: the G-buffer's and the direct
/// light's pixels not yet begun are left empty (the caller checks `progress`). With `spares`,
/// the frame is written into the memory of the last frame dropped there, and leaves its own
/// there when dropped.
pub fn prepare_watched(
    scene: &Scene,
    settings: &RenderSettings,
    tracer: impl Into<Arc<Tracer>>,
    pass: Option<u32>,
    progress: Progress,
    spares: Option<&FrameSpares>,
) -> CpuPrepared {
    let memory = spares.and_then(|s| s.0.take()).unwrap_or_default();
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
        let spare = memory.samples;
        trace_gbuffer_watched(scene, &tracer, &camera, (w, h), sample, progress, spare)
    });
    let maps: Vec<_> = timings.time("rsm", || {
        scene
            .lights
            .iter()
            .map(|l| trace_rsm(scene, &tracer, l, settings.rsm_resolution, texel_sample))
            .collect()
    });
    let vpls = timings.time("vpl_generation", || {
        let seed = pass_seed(settings.seed, pass);
        generate_vpls_into(&maps, seed, settings.lobes, memory.vpls)
    });
    let direct = timings.time("direct", || {
        shade_direct_watched(&tracer, &scene.lights, &gbuffer, progress, memory.direct)
    });
    CpuPrepared {
        camera,
        tracer,
        gbuffer,
        maps,
        vpls,
        direct,
        timings,
        spares: spares.map(FrameSpares::share),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_core::builtin;
    use slc_core::frame::Method;

    fn settings(width: u32, height: u32, rsm: u32) -> RenderSettings {
        RenderSettings {
            seed: 3,
            ..RenderSettings::new(width, height, rsm, Method::VplReference)
        }
    }

    /// A frame made in the memory a dropped frame left equals one made fresh, whether the
    /// memory was larger or smaller than it needs; a clone of the spares shares nothing.
    #[test]
    fn frames_in_a_dropped_frames_memory_equal_fresh_ones() {
        let scene = builtin("default").unwrap();
        let tracer = Arc::new(Tracer::new(&scene));
        let fresh = |s: &RenderSettings| prepare(&scene, s, Arc::clone(&tracer), Some(1));
        let spares = FrameSpares::default();
        let kept = |s: &RenderSettings| {
            prepare_watched(
                &scene,
                s,
                Arc::clone(&tracer),
                Some(1),
                &|_| {},
                Some(&spares),
            )
        };
        let first = kept(&settings(40, 30, 16));
        let memory = (first.gbuffer.samples.as_ptr(), first.vpls.as_ptr());
        drop(first);
        for s in [
            settings(40, 30, 16),
            settings(17, 9, 8),
            settings(64, 48, 32),
        ] {
            let (got, want) = (kept(&s), fresh(&s));
            assert_eq!(got.gbuffer.samples, want.gbuffer.samples);
            assert_eq!(got.vpls, want.vpls);
            assert_eq!(got.direct.pixels, want.direct.pixels);
            if s.width == 40 {
                assert_eq!(memory, (got.gbuffer.samples.as_ptr(), got.vpls.as_ptr()));
            }
        }
        assert!(spares.clone().0.take().is_none());
        assert!(spares.0.take().is_some());
    }
}
