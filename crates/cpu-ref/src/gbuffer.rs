//! The ray-traced G-buffer.
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_core::rng::{stream, Sequence};
use slc_core::{Camera, GBuffer, GSample, Progress, Scene};

/// Where inside each pixel the primary ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelSample {
    /// Through the pixel centre.
    Centre,
    /// At a uniformly random point of the pixel: sample `index` of the pixel's sequence for `seed`.
    Jittered { seed: u32, index: u32 },
}

impl PixelSample {
    /// The sub-pixel offset (s, t) in [0, 1)^2 for pixel number `pixel`.
    pub fn offset(&self, pixel: u32) -> (f32, f32) {
        match *self {
            PixelSample::Centre => (0.5, 0.5),
            PixelSample::Jittered { seed, index } => {
                Sequence::new(seed, pixel, stream::PIXEL, index * PIXEL_DIMENSIONS).next_2d()
            }
        }
    }
}

/// Random numbers each pixel sample may draw (camera jitter first, then path sampling).
pub const PIXEL_DIMENSIONS: u32 = 8;

/// Traces one primary ray per pixel and records the visible surface; the backs of one-sided
/// surfaces and misses are `None`.
pub fn trace_gbuffer(
    scene: &Scene,
    tracer: &Tracer,
    camera: &Camera,
    width: u32,
    height: u32,
    sample: PixelSample,
) -> GBuffer {
    trace_gbuffer_watched(scene, tracer, camera, (width, height), sample, &|_| {})
}

/// [`trace_gbuffer`] that stops once `progress` is cancelled: the pixels not yet traced are
/// misses (the caller checks `progress`).
pub fn trace_gbuffer_watched(
    scene: &Scene,
    tracer: &Tracer,
    camera: &Camera,
    (width, height): (u32, u32),
    sample: PixelSample,
    progress: Progress,
) -> GBuffer {
    let samples = (0..width * height)
        .into_par_iter()
        .map(|pixel| {
            if progress.cancelled() {
                return None;
            }
            let (i, j) = (pixel % width, pixel / width);
            let (s, t) = sample.offset(pixel);
            let dir = camera.ray_direction(i, j, s, t, width, height);
            let hit = tracer.intersect(scene, camera.position, dir, f32::INFINITY)?;
            hit.front.then(|| GSample {
                position: hit.position,
                normal: hit.shading_normal,
                geometric_normal: hit.geometric_normal,
                omega_o: -dir,
                depth: camera.view_depth(hit.position),
                brdf: hit.brdf,
            })
        })
        .collect();
    GBuffer {
        width,
        height,
        samples,
    }
}

/// Unit direction and squared distance from `from` to `to`; `None` when they coincide.
#[inline]
pub fn direction_to(from: Vec3, to: Vec3) -> Option<(Vec3, f32)> {
    let d = to - from;
    let l2 = d.length_squared();
    (l2 > 0.0).then(|| (d / l2.sqrt(), l2))
}
