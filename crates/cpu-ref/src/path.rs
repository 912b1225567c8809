//! The path-traced one-bounce reference: camera hit, one BRDF-sampled bounce, and direct light
//! at the second surface with a shadow ray. Unbiased for exactly one indirect bounce.
use crate::direct::direct_radiance;
use crate::gbuffer::PIXEL_DIMENSIONS;
use crate::sampling;
use crate::tracer::Tracer;
use glam::Vec3;
use slc_core::rng::{stream, Sequence};
use slc_core::{Camera, GSample, Scene};

/// Direct and one-bounce indirect radiance of sample `index` of pixel number `pixel` of a
/// `width` x `height` image.
pub fn trace_pixel_sample(
    scene: &Scene,
    tracer: &Tracer,
    camera: &Camera,
    pixel: u32,
    (width, height): (u32, u32),
    seed: u32,
    index: u32,
) -> (Vec3, Vec3) {
    let mut rng = Sequence::new(seed, pixel, stream::PIXEL, index * PIXEL_DIMENSIONS);
    // The first two numbers are the camera jitter, as for a jittered G-buffer.
    let (s, t) = rng.next_2d();
    let dir = camera.ray_direction(pixel % width, pixel / width, s, t, width, height);
    let Some(x) = tracer
        .intersect(scene, camera.position, dir, f32::INFINITY)
        .filter(|h| h.front)
    else {
        return (Vec3::ZERO, Vec3::ZERO);
    };
    let gx = GSample {
        position: x.position,
        normal: x.shading_normal,
        geometric_normal: x.geometric_normal,
        omega_o: -dir,
        depth: 0.0,
        brdf: x.brdf,
    };
    let direct = direct_radiance(tracer, &scene.lights, &gx);
    let u = [rng.next_f32(), rng.next_f32(), rng.next_f32()];
    let Some((omega_i, pdf)) = sampling::sample(&gx.brdf, gx.normal, gx.omega_o, u) else {
        return (direct, Vec3::ZERO);
    };
    if gx.geometric_normal.dot(omega_i) <= 0.0 {
        return (direct, Vec3::ZERO);
    }
    let from = tracer.lift(gx.position, gx.geometric_normal);
    let Some(y) = tracer
        .intersect(scene, from, omega_i, f32::INFINITY)
        .filter(|h| h.front)
    else {
        return (direct, Vec3::ZERO);
    };
    let gy = GSample {
        position: y.position,
        normal: y.shading_normal,
        geometric_normal: y.geometric_normal,
        omega_o: -omega_i,
        depth: 0.0,
        brdf: y.brdf,
    };
    let incoming = direct_radiance(tracer, &scene.lights, &gy);
    let throughput = gx.brdf.eval(gx.normal, omega_i, gx.omega_o) * (gx.normal.dot(omega_i) / pdf);
    (direct, throughput * incoming)
}
