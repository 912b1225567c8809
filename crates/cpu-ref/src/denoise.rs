//! The cross bilateral filter that removes the noise of interleaved sampling (paper section 6,
//! after Petschnigg et al. 2004 and Eisemann and Durand 2004): a spatial Gaussian weighted by
//! how alike the neighbours' depth and normal are (the G-buffer guides the filter).
//!
//! The filter works on demodulated radiance: indirect light divided by the pixel's reflectance
//! (kd + F(1), clamped away from zero), and multiplies it back afterwards, so texture detail
//! is not blurred.
use glam::Vec3;
use rayon::prelude::*;
use slc_core::{GBuffer, GSample, Image, Progress};

/// Parameters of the cross bilateral filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BilateralParams {
    /// Kernel radius in pixels (8 in the paper).
    pub radius: u32,
    /// Spatial standard deviation in pixels.
    pub sigma_spatial: f32,
    /// Standard deviation of the relative depth difference |z - z'| / z.
    pub sigma_depth: f32,
    /// Exponent of the normal weight max(n·n', 0)^(2^k): k squarings.
    pub normal_squarings: u32,
}

impl Default for BilateralParams {
    fn default() -> Self {
        Self {
            radius: 8,
            sigma_spatial: 4.0,
            sigma_depth: 0.05,
            normal_squarings: 5,
        }
    }
}

fn reflectance(g: &GSample) -> Vec3 {
    (g.brdf.kd + g.brdf.fresnel.eval(1.0)).max(Vec3::splat(1e-3))
}

/// Filters `image` guided by `gbuffer`; pixels without a surface stay as they are.
///
/// The kernel is applied separably, a horizontal pass then a vertical one, each weighting its
/// 2r + 1 taps by the spatial Gaussian, the relative depth difference and the normals: 4r + 2
/// taps per pixel instead of (2r + 1)², the usual real-time approximation of the 2-D filter.
pub fn cross_bilateral(image: &Image, gbuffer: &GBuffer, params: BilateralParams) -> Image {
    cross_bilateral_watched(image, gbuffer, params, &|_| {})
}

/// [`cross_bilateral`] that stops once `progress` is cancelled: the pixels not yet filtered
/// keep wrong values (the caller checks `progress`).
pub fn cross_bilateral_watched(
    image: &Image,
    gbuffer: &GBuffer,
    params: BilateralParams,
    progress: Progress,
) -> Image {
    let demodulated: Vec<Vec3> = image
        .pixels
        .iter()
        .zip(&gbuffer.samples)
        .map(|(p, g)| g.as_ref().map_or(*p, |g| *p / reflectance(g)))
        .collect();
    let horizontal = filter_1d(&demodulated, gbuffer, params, (1, 0), progress);
    let vertical = filter_1d(&horizontal, gbuffer, params, (0, 1), progress);
    let pixels = vertical
        .iter()
        .zip(&gbuffer.samples)
        .zip(&image.pixels)
        .map(|((v, g), orig)| g.as_ref().map_or(*orig, |g| *v * reflectance(g)))
        .collect();
    Image {
        width: image.width,
        height: image.height,
        pixels,
    }
}

/// One pass of the cross bilateral filter along `step` (one pixel in x or in y).
fn filter_1d(
    values: &[Vec3],
    gbuffer: &GBuffer,
    params: BilateralParams,
    step: (i64, i64),
    progress: Progress,
) -> Vec<Vec3> {
    let (w, h) = (gbuffer.width as i64, gbuffer.height as i64);
    let r = params.radius as i64;
    let inv_2ss = 1.0 / (2.0 * params.sigma_spatial * params.sigma_spatial);
    let inv_2sd = 1.0 / (2.0 * params.sigma_depth * params.sigma_depth);
    let spatial: Vec<f32> = (-r..=r)
        .map(|d| (-((d * d) as f32) * inv_2ss).exp())
        .collect();
    (0..w * h)
        .into_par_iter()
        .map(|p| {
            let Some(g) = &gbuffer.samples[p as usize] else {
                return values[p as usize];
            };
            if progress.cancelled() {
                return values[p as usize];
            }
            let (x, y) = (p % w, p / w);
            let mut sum = Vec3::ZERO;
            let mut weight = 0.0f32;
            for d in -r..=r {
                let (xx, yy) = (x + d * step.0, y + d * step.1);
                if xx < 0 || yy < 0 || xx >= w || yy >= h {
                    continue;
                }
                let q = (yy * w + xx) as usize;
                let Some(gq) = &gbuffer.samples[q] else {
                    continue;
                };
                let dz = (gq.depth - g.depth) / g.depth.max(1e-6);
                let mut wn = g.normal.dot(gq.normal).max(0.0);
                for _ in 0..params.normal_squarings {
                    wn *= wn;
                }
                let wq = spatial[(d + r) as usize] * wn * (-dz * dz * inv_2sd).exp();
                sum += values[q] * wq;
                weight += wq;
            }
            // The centre tap always has weight 1, so `weight` > 0.
            sum / weight
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_bounds::{Brdf, Fresnel};

    fn sample(depth: f32, normal: Vec3) -> Option<GSample> {
        Some(GSample {
            position: Vec3::ZERO,
            normal,
            geometric_normal: normal,
            omega_o: normal,
            depth,
            brdf: Brdf {
                kd: Vec3::splat(0.5),
                fresnel: Fresnel::Schlick(Vec3::ZERO),
                alpha: 1.0,
                anisotropy: None,
            },
        })
    }

    /// Noise on one surface is averaged, the mean is kept, and an edge in depth stops the blur.
    #[test]
    fn smooths_within_surfaces_and_keeps_edges() {
        let (w, h) = (32u32, 16u32);
        let mut samples = Vec::new();
        let mut img = Image::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let near = x < w / 2;
                samples.push(sample(if near { 1.0 } else { 5.0 }, Vec3::Z));
                let base = if near { 1.0 } else { 10.0 };
                let noise = if (x + y) % 2 == 0 { 0.5 } else { -0.5 };
                img.pixels.push(Vec3::splat(base + noise));
            }
        }
        img.pixels.drain(..(w * h) as usize);
        let g = GBuffer {
            width: w,
            height: h,
            samples,
        };
        let out = cross_bilateral(&img, &g, BilateralParams::default());
        for y in 2..h - 2 {
            // Far from the edge the checkerboard noise is gone.
            assert!((out.get(4, y).x - 1.0).abs() < 0.05, "{}", out.get(4, y).x);
            assert!((out.get(28, y).x - 10.0).abs() < 0.05);
            // Next to the edge, the other side does not leak in.
            assert!(out.get(w / 2 - 1, y).x < 1.6 && out.get(w / 2, y).x > 9.4);
        }
    }

    #[test]
    fn constant_images_are_unchanged_and_sky_is_untouched() {
        let (w, h) = (9u32, 7u32);
        let samples = (0..w * h)
            .map(|i| if i == 5 { None } else { sample(2.0, Vec3::Y) })
            .collect();
        let mut img = Image::new(w, h);
        img.pixels
            .iter_mut()
            .for_each(|p| *p = Vec3::new(0.2, 0.3, 0.4));
        img.pixels[5] = Vec3::splat(7.0);
        let out = cross_bilateral(
            &img,
            &GBuffer {
                width: w,
                height: h,
                samples,
            },
            BilateralParams::default(),
        );
        for (i, p) in out.pixels.iter().enumerate() {
            let want = if i == 5 {
                Vec3::splat(7.0)
            } else {
                Vec3::new(0.2, 0.3, 0.4)
            };
            assert!((*p - want).abs().max_element() < 1e-5, "{i}: {p}");
        }
    }
}
