//! Direct light from the scene's lights, with shadow rays (traced eight at a time).
use crate::blocks::par_blocks;
use crate::tracer::{Rays8, Tracer};
use glam::Vec3;
use slc_core::{Emitter, GBuffer, GSample, Image, Light, Progress};

/// Radiance towards the camera reflected from every light at one surface point:
/// `Σ f(ωl, ωo) E cos θl V` with E = I / d² (or the directional irradiance).
pub fn direct_radiance(tracer: &Tracer, lights: &[Light], g: &GSample) -> Vec3 {
    let mut sum = Vec3::ZERO;
    let from = tracer.lift(g.position, g.geometric_normal);
    for light in lights {
        let Some(inc) = light.incident(g.position) else {
            continue;
        };
        let cos = g.normal.dot(inc.omega_i);
        if cos <= 0.0 || g.geometric_normal.dot(inc.omega_i) <= 0.0 {
            continue;
        }
        let visible = match light {
            Light::Directional { .. } => tracer.escapes(from, inc.omega_i),
            _ => tracer.unoccluded(from, g.position + inc.omega_i * inc.distance),
        };
        if visible {
            sum += g.brdf.eval(g.normal, inc.omega_i, g.omega_o) * inc.irradiance * cos;
        }
    }
    sum
}

/// The direct-light image of a G-buffer: [`direct_radiance`] of every pixel, the shadow rays
/// of each 4x2 block of pixels to one light traced together ([`Tracer::occluded8`]; each
/// ray's answer is the one it gets alone, and each pixel sums its lights in the same order,
/// so the image is the same).
pub fn shade_direct(tracer: &Tracer, lights: &[Light], gbuffer: &GBuffer) -> Image {
    shade_direct_watched(tracer, lights, gbuffer, &|_| {}, Vec::new())
}

/// [`shade_direct`] that stops once `progress` is cancelled: the blocks not yet shaded are
/// black (the caller checks `progress`). The pixels are written into `spare`'s memory
/// (`blocks::par_blocks`).
pub fn shade_direct_watched(
    tracer: &Tracer,
    lights: &[Light],
    gbuffer: &GBuffer,
    progress: Progress,
    spare: Vec<Vec3>,
) -> Image {
    let emitters: Vec<Emitter> = lights.iter().map(Light::emitter).collect();
    let pixels = par_blocks(gbuffer.width, gbuffer.height, spare, |block| {
        let samples: [Option<&GSample>; 8] = std::array::from_fn(|lane| {
            (block.used & (1 << lane) != 0)
                .then(|| gbuffer.samples[block.index(lane)].as_ref())
                .flatten()
        });
        let mut sums = [Vec3::ZERO; 8];
        if progress.cancelled() {
            return sums;
        }
        for emitter in &emitters {
            light_at_block(tracer, emitter, &samples, &mut sums);
        }
        sums
    });
    Image {
        width: gbuffer.width,
        height: gbuffer.height,
        pixels,
    }
}

/// Adds `emitter`'s reflected radiance to each sample's sum, its shadow rays traced together.
fn light_at_block(
    tracer: &Tracer,
    emitter: &Emitter,
    samples: &[Option<&GSample>; 8],
    sums: &mut [Vec3; 8],
) {
    let mut rays = Rays8::default();
    let mut lit = 0u8;
    let mut radiance = [Vec3::ZERO; 8];
    for (lane, g) in samples.iter().enumerate() {
        let Some(g) = g else {
            continue;
        };
        let Some(inc) = emitter.incident(g.position) else {
            continue;
        };
        let cos = g.normal.dot(inc.omega_i);
        if cos <= 0.0 || g.geometric_normal.dot(inc.omega_i) <= 0.0 {
            continue;
        }
        let from = tracer.lift(g.position, g.geometric_normal);
        let ray = match emitter.light() {
            Light::Directional { .. } => {
                let (tmin, tmax) = tracer.escape_range();
                Some((inc.omega_i, tmin, tmax))
            }
            _ => tracer.segment_ray(from, g.position + inc.omega_i * inc.distance),
        };
        if let Some((dir, tmin, tmax)) = ray {
            rays.origin[lane] = from;
            rays.dir[lane] = dir;
            rays.tmin[lane] = tmin;
            rays.tmax[lane] = tmax;
            rays.used |= 1 << lane;
        }
        lit |= 1 << lane;
        radiance[lane] = g.brdf.eval(g.normal, inc.omega_i, g.omega_o) * inc.irradiance * cos;
    }
    let visible = lit & !tracer.occluded8(&rays);
    for (lane, sum) in sums.iter_mut().enumerate() {
        if visible & (1 << lane) != 0 {
            *sum += radiance[lane];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gbuffer::{trace_gbuffer, PixelSample};
    use slc_core::builtin;

    /// The blocks' shadow rays traced together give every pixel the radiance it gets alone,
    /// bit for bit, with a spot, a point and a directional light (partial blocks included).
    #[test]
    fn blocks_equal_pixels_shaded_alone() {
        let mut scene = builtin("default").unwrap();
        scene.lights.push(Light::Point {
            position: glam::Vec3::new(0.3, 1.6, 0.2),
            intensity: glam::Vec3::splat(2.0),
        });
        scene.lights.push(Light::Directional {
            direction: glam::Vec3::new(0.2, -1.0, -0.3).normalize(),
            irradiance: glam::Vec3::splat(1.5),
        });
        let tracer = Tracer::new(&scene);
        let camera = scene.camera_or_default();
        let g = trace_gbuffer(&scene, &tracer, &camera, 41, 29, PixelSample::Centre);
        let image = shade_direct(&tracer, &scene.lights, &g);
        let mut lit = 0;
        for (p, s) in image.pixels.iter().zip(&g.samples) {
            let alone = s
                .as_ref()
                .map_or(Vec3::ZERO, |s| direct_radiance(&tracer, &scene.lights, s));
            assert_eq!(*p, alone);
            lit += usize::from(*p != Vec3::ZERO);
        }
        assert!(lit > 100, "{lit}");
    }
}
