//! Reflective shadow maps traced from the light: the surface points the light's photons reach
//! first, with the flux each texel carries, on the faces of [`RsmLayout`] (`slc_core::rsm`,
//! which the GPU's rasterized maps share).
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_core::rng::{stream, Sequence};
pub use slc_core::rsm::{rectangle_solid_angle, Rsm, RsmLayout, RsmTexel};
use slc_core::{Light, Scene};

/// Where inside each texel the light's ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexelSample {
    /// Through the texel centre, with the texel's exact solid angle (as a rasterizer would).
    Centre,
    /// At a uniformly random point of the texel (pass `pass` of `seed`), with the flux divided
    /// by that point's density: an unbiased estimate of the light's one-bounce transport.
    Jittered { seed: u32, pass: u32 },
}

/// Traces the reflective shadow map of `light`.
pub fn trace_rsm(
    scene: &Scene,
    tracer: &Tracer,
    light: &Light,
    resolution: u32,
    sample: TexelSample,
) -> Rsm {
    let n = resolution;
    let bounds = scene.bounds().unwrap_or((Vec3::splat(-1.0), Vec3::ONE));
    let RsmLayout {
        faces,
        origin,
        orthographic,
    } = RsmLayout::new(light, bounds);
    let orthographic = orthographic.is_some();
    let emitter = light.emitter();
    let texel_size = 2.0 / n as f32;
    let texels = (0..faces.len() as u32 * n * n)
        .into_par_iter()
        .map(|index| {
            let face = faces[(index / (n * n)) as usize];
            let (i, j) = (index % n, (index / n) % n);
            let (s, t) = match sample {
                TexelSample::Centre => (0.5, 0.5),
                TexelSample::Jittered { seed, pass } => {
                    Sequence::new(seed, index, stream::RSM_JITTER, 2 * pass).next_2d()
                }
            };
            let e = face.extent;
            let x = (-1.0 + (i as f32 + s) * texel_size) * e;
            let y = (1.0 - (j as f32 + t) * texel_size) * e;
            // The beam's cross-section is `beam` (orthographic) or `beam` times the squared
            // distance (perspective, `beam` a solid angle).
            let (ray_origin, dir, flux, beam) = if orthographic {
                let area = (texel_size * e) * (texel_size * e);
                let irradiance = match *light {
                    Light::Directional { irradiance, .. } => irradiance,
                    _ => unreachable!("only directional lights are orthographic"),
                };
                (
                    origin + x * face.right + y * face.up,
                    face.forward,
                    irradiance * area,
                    area,
                )
            } else {
                let dir = (face.forward + x * face.right + y * face.up).normalize();
                let solid_angle = match sample {
                    TexelSample::Centre => {
                        let (x0, y1) = (
                            (-1.0 + i as f32 * texel_size) * e,
                            (1.0 - j as f32 * texel_size) * e,
                        );
                        rectangle_solid_angle(x0, x0 + texel_size * e, y1 - texel_size * e, y1)
                    }
                    // Density of a uniform point on the texel, in solid angle:
                    // dω = dA / (1 + x² + y²)^{3/2} on the plane at unit distance.
                    TexelSample::Jittered { .. } => {
                        (texel_size * e).powi(2) / (1.0 + x * x + y * y).powf(1.5)
                    }
                };
                let intensity = match *light {
                    Light::Point { intensity, .. } => intensity,
                    Light::Spot { intensity, .. } => intensity * emitter.spot_falloff(dir),
                    Light::Directional { .. } => {
                        unreachable!("directional lights are orthographic")
                    }
                };
                (origin, dir, intensity * solid_angle, solid_angle)
            };
            if flux.max_element() <= 0.0 {
                return None;
            }
            let hit = tracer.intersect(scene, ray_origin, dir, f32::INFINITY)?;
            let cross_section = if orthographic {
                beam
            } else {
                beam * hit.distance * hit.distance
            };
            hit.front.then_some(RsmTexel {
                position: hit.position,
                normal: hit.shading_normal,
                geometric_normal: hit.geometric_normal,
                normal_mapped: hit.normal_mapped,
                omega_i: -dir,
                flux,
                cross_section,
                brdf: hit.brdf,
            })
        })
        .collect();
    Rsm {
        resolution: n,
        faces: faces.len() as u32,
        texels,
    }
}
