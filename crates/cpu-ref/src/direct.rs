//! Direct light from the scene's lights, with shadow rays.
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_core::{GBuffer, GSample, Image, Light, Progress};

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

/// The direct-light image of a G-buffer.
pub fn shade_direct(tracer: &Tracer, lights: &[Light], gbuffer: &GBuffer) -> Image {
    shade_direct_watched(tracer, lights, gbuffer, &|_| {})
}

/// [`shade_direct`] that stops once `progress` is cancelled: the pixels not yet shaded are
/// black (the caller checks `progress`).
pub fn shade_direct_watched(
    tracer: &Tracer,
    lights: &[Light],
    gbuffer: &GBuffer,
    progress: Progress,
) -> Image {
    let pixels = gbuffer
        .samples
        .par_iter()
        .map(|g| match g {
            Some(g) if !progress.cancelled() => direct_radiance(tracer, lights, g),
            _ => Vec3::ZERO,
        })
        .collect();
    Image {
        width: gbuffer.width,
        height: gbuffer.height,
        pixels,
    }
}
