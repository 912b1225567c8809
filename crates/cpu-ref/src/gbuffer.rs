//! The ray-traced G-buffer: primary rays of 4x2 pixel blocks traced as packets
//! ([`Tracer::intersect8`]), each pixel's sample written in place (`blocks::par_blocks`).
use crate::blocks::par_blocks;
use crate::tracer::{Rays8, Tracer};
use glam::Vec3;
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

/// [`Camera::ray_direction`] for one image size, its constants formed once: the same
/// operations per pixel, so the same directions bit for bit.
#[derive(Clone, Copy, Debug)]
pub struct PrimaryRays {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    tan_half: f32,
    aspect: f32,
    width: f32,
    height: f32,
}

impl PrimaryRays {
    pub fn new(camera: &Camera, width: u32, height: u32) -> Self {
        Self {
            forward: camera.forward,
            right: camera.right,
            up: camera.up,
            tan_half: (0.5 * camera.yfov).tan(),
            aspect: width as f32 / height as f32,
            width: width as f32,
            height: height as f32,
        }
    }

    /// The unit direction through (i + s, j + t) in pixels.
    #[inline]
    pub fn direction(&self, i: u32, j: u32, s: f32, t: f32) -> Vec3 {
        let x = (2.0 * (i as f32 + s) / self.width - 1.0) * self.aspect * self.tan_half;
        let y = (1.0 - 2.0 * (j as f32 + t) / self.height) * self.tan_half;
        (self.forward + x * self.right + y * self.up).normalize()
    }
}

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
    let size = (width, height);
    trace_gbuffer_watched(scene, tracer, camera, size, sample, &|_| {}, Vec::new())
}

/// [`trace_gbuffer`] that stops once `progress` is cancelled: the blocks not yet traced are
/// misses (the caller checks `progress`). The samples are written into `spare`'s memory
/// (`blocks::par_blocks`).
pub fn trace_gbuffer_watched(
    scene: &Scene,
    tracer: &Tracer,
    camera: &Camera,
    (width, height): (u32, u32),
    sample: PixelSample,
    progress: Progress,
    spare: Vec<Option<GSample>>,
) -> GBuffer {
    let rays = PrimaryRays::new(camera, width, height);
    let samples = par_blocks(width, height, spare, |block| {
        if progress.cancelled() {
            return [None; 8];
        }
        let mut packet = Rays8 {
            used: block.used,
            ..Rays8::default()
        };
        for lane in block.lanes() {
            let (i, j) = block.pixel(lane);
            let (s, t) = sample.offset(block.index(lane) as u32);
            packet.dir[lane] = rays.direction(i, j, s, t);
        }
        let hits = tracer.intersect8(scene, camera.position, &packet);
        std::array::from_fn(|lane| {
            let hit = hits[lane]?;
            hit.front.then(|| GSample {
                position: hit.position,
                normal: hit.shading_normal,
                geometric_normal: hit.geometric_normal,
                omega_o: -packet.dir[lane],
                depth: camera.view_depth(hit.position),
                brdf: hit.brdf,
            })
        })
    });
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

#[cfg(test)]
mod tests {
    use super::*;
    use slc_core::builtin;

    /// The constants formed once give `Camera::ray_direction`'s directions bit for bit.
    #[test]
    fn primary_rays_are_the_cameras() {
        let camera = builtin("default").unwrap().camera_or_default();
        for (w, h) in [(1, 1), (640, 360), (33, 77)] {
            let rays = PrimaryRays::new(&camera, w, h);
            for (i, j, s, t) in [
                (0, 0, 0.5, 0.5),
                (w - 1, h - 1, 0.99, 0.01),
                (w / 2, h / 3, 0.3, 0.7),
            ] {
                assert_eq!(
                    rays.direction(i, j, s, t),
                    camera.ray_direction(i, j, s, t, w, h)
                );
            }
        }
    }

    /// The packets give each pixel the sample a ray traced alone gives it, on the built-in
    /// scene at pixel centres and jittered, at a size that leaves partial blocks.
    #[test]
    fn packets_equal_rays_traced_alone() {
        let scene = builtin("default").unwrap();
        let tracer = Tracer::new(&scene);
        let camera = scene.camera_or_default();
        let (w, h) = (37, 23);
        for sample in [
            PixelSample::Centre,
            PixelSample::Jittered { seed: 3, index: 1 },
        ] {
            let g = trace_gbuffer(&scene, &tracer, &camera, w, h, sample);
            assert_eq!(g.samples.len(), (w * h) as usize);
            let mut surfaces = 0;
            for (p, got) in g.samples.iter().enumerate() {
                let (i, j) = (p as u32 % w, p as u32 / w);
                let (s, t) = sample.offset(p as u32);
                let dir = camera.ray_direction(i, j, s, t, w, h);
                let alone = tracer
                    .intersect(&scene, camera.position, dir, f32::INFINITY)
                    .filter(|hit| hit.front);
                assert_eq!(
                    got.map(|g| g.position),
                    alone.map(|h| h.position),
                    "{i},{j}"
                );
                assert_eq!(got.map(|g| g.brdf), alone.map(|h| h.brdf), "{i},{j}");
                surfaces += usize::from(got.is_some());
            }
            assert!(surfaces > (w * h) as usize / 2, "{surfaces}");
        }
    }
}
