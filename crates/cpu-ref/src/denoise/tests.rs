//! The filter against the scalar filter it replaced (kept here as the oracle), on images
//! with and without surfaces, borders and sizes that are not whole vectors.
use super::*;
use glam::Vec3;
use lanes::Width;
use slc_bounds::{Brdf, Fresnel};
use slc_core::rng::uniform;
use slc_core::GSample;

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
    let out = cross_bilateral(&img, &g, BilateralParams::default()).unwrap();
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
    )
    .unwrap();
    for (i, p) in out.pixels.iter().enumerate() {
        let want = if i == 5 {
            Vec3::splat(7.0)
        } else {
            Vec3::new(0.2, 0.3, 0.4)
        };
        assert!((*p - want).abs().max_element() < 1e-5, "{i}: {p}");
    }
}

/// The scalar filter the vectorized one replaced: the oracle of
/// [`equals_the_scalar_filter_within_rounding`].
fn scalar_filter(image: &Image, gbuffer: &GBuffer, params: BilateralParams) -> Image {
    let reflectance = |g: &GSample| (g.brdf.kd + g.brdf.fresnel.eval(1.0)).max(Vec3::splat(1e-3));
    let demodulated: Vec<Vec3> = image
        .pixels
        .iter()
        .zip(&gbuffer.samples)
        .map(|(p, g)| g.as_ref().map_or(*p, |g| *p / reflectance(g)))
        .collect();
    let horizontal = scalar_1d(&demodulated, gbuffer, params, (1, 0));
    let vertical = scalar_1d(&horizontal, gbuffer, params, (0, 1));
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

fn scalar_1d(
    values: &[Vec3],
    gbuffer: &GBuffer,
    params: BilateralParams,
    step: (i64, i64),
) -> Vec<Vec3> {
    let (w, h) = (gbuffer.width as i64, gbuffer.height as i64);
    let r = params.radius as i64;
    let inv_2ss = 1.0 / (2.0 * params.sigma_spatial * params.sigma_spatial);
    let inv_2sd = 1.0 / (2.0 * params.sigma_depth * params.sigma_depth);
    let spatial: Vec<f32> = (-r..=r)
        .map(|d| (-((d * d) as f32) * inv_2ss).exp())
        .collect();
    (0..w * h)
        .map(|p| {
            let Some(g) = &gbuffer.samples[p as usize] else {
                return values[p as usize];
            };
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
            sum / weight
        })
        .collect()
}

/// A random frame: surfaces in depth layers with edges, normals around a few directions,
/// about a sixth of the pixels without a surface, positive noisy values.
fn random_frame(w: u32, h: u32, seed: u32) -> (Image, GBuffer) {
    let u = |i: u32, k: u32| uniform(seed, i, 7, k);
    let mut samples = Vec::new();
    let mut pixels = Vec::new();
    for i in 0..w * h {
        let (x, y) = ((i % w) as f32, (i / w) as f32);
        let layer = ((x * 0.3 + y * 0.2 + 3.0 * u(i, 0)) as u32 % 3) as f32;
        let normal = Vec3::new(u(i, 1) - 0.5, u(i, 2) - 0.5, 2.0 + layer).normalize();
        let mut g = sample(1.0 + layer * 0.08 + 0.01 * u(i, 3), normal);
        if let Some(g) = &mut g {
            g.brdf.kd = Vec3::new(u(i, 4), u(i, 5), 0.5);
            g.brdf.fresnel = Fresnel::Schlick(Vec3::splat(0.04 * u(i, 6)));
        }
        samples.push(if u(i, 7) < 0.17 { None } else { g });
        pixels.push(Vec3::new(u(i, 8), 2.0 * u(i, 9), 0.1 + u(i, 10)) * 3.0);
    }
    let image = Image {
        width: w,
        height: h,
        pixels,
    };
    (
        image,
        GBuffer {
            width: w,
            height: h,
            samples,
        },
    )
}

/// The vectorized filter is the scalar filter within float rounding (its exponential is
/// within 2 ulp of `expf`), at sizes from one pixel to several vectors and strips, with the
/// paper's radius and a smaller one; one filter kept across all of them (its working set
/// refitted at each size) gives what a fresh one gives.
/// A radius smaller than the paper's, so that the rows' taps start off the vectors' grid.
fn small_params() -> BilateralParams {
    BilateralParams {
        radius: 3,
        sigma_spatial: 1.5,
        sigma_depth: 0.02,
        normal_squarings: 2,
    }
}

#[test]
fn equals_the_scalar_filter_within_rounding() {
    let small = small_params();
    let mut kept = CrossBilateral::default();
    for (k, (w, h)) in [
        (1, 1),
        (7, 3),
        (8, 8),
        (13, 9),
        (37, 21),
        (300, 40),
        (8, 30),
    ]
    .into_iter()
    .enumerate()
    {
        for params in [BilateralParams::default(), small] {
            let (image, gbuffer) = random_frame(w, h, k as u32);
            let want = scalar_filter(&image, &gbuffer, params);
            let got = kept.filter(&image, &gbuffer, params).unwrap();
            assert_eq!(got, cross_bilateral(&image, &gbuffer, params).unwrap());
            for (i, (a, b)) in got.pixels.iter().zip(&want.pixels).enumerate() {
                let err = ((*a - *b).abs() / b.abs().max(Vec3::splat(1e-6))).max_element();
                assert!(err < 1e-5, "{w}x{h} pixel {i}: {a} against {b}");
            }
            // Where there is no surface the pixel is the image's, bit for bit.
            for ((a, b), g) in got.pixels.iter().zip(&image.pixels).zip(&gbuffer.samples) {
                if g.is_none() {
                    assert_eq!(a, b);
                }
            }
        }
    }
}

/// The filter in AVX-512, AVX2 and plain-array lanes gives the same image bit for bit
/// (whichever of them this CPU has), at widths that are and are not whole vectors of eight
/// and sixteen, strips included.
#[test]
fn every_width_of_lanes_gives_the_same_bits() {
    for (k, (w, h)) in [(1, 1), (9, 4), (16, 5), (24, 3), (37, 21), (300, 40)]
        .into_iter()
        .enumerate()
    {
        let (image, gbuffer) = random_frame(w, h, 40 + k as u32);
        for params in [BilateralParams::default(), small_params()] {
            let each = [Width::Arrays, Width::Avx2, Width::Avx512].map(|widest| {
                let mut filter = CrossBilateral::default();
                let pixels = filter
                    .filter_in(widest, &image, &gbuffer, params)
                    .unwrap()
                    .pixels;
                pixels
                    .iter()
                    .flat_map(|p| p.to_array().map(f32::to_bits))
                    .collect::<Vec<_>>()
            });
            let r = params.radius;
            assert_eq!(each[0], each[1], "{w}x{h}, radius {r}: AVX2 against arrays");
            assert_eq!(
                each[0], each[2],
                "{w}x{h}, radius {r}: AVX-512 against arrays"
            );
        }
    }
}

/// Surfaces whose reflectance is out of range (NaN or infinite kd: `reflectance` clamps NaN
/// to 1e-3) are filtered and multiplied back as the scalar filter does: the vertical pass
/// takes the reflectance from the guide's planes, where NaN marks a pixel without a surface.
#[test]
fn surfaces_with_nan_or_infinite_kd_are_filtered_as_the_scalar_filter_does() {
    let (image, mut gbuffer) = random_frame(37, 21, 9);
    for (i, g) in gbuffer.samples.iter_mut().enumerate() {
        if let Some(g) = g.as_mut().filter(|_| i % 5 == 0) {
            g.brdf.kd = if i % 10 == 0 {
                Vec3::new(f32::NAN, 0.2, f32::NAN)
            } else {
                Vec3::new(0.3, f32::INFINITY, 0.1)
            };
        }
    }
    for params in [BilateralParams::default(), small_params()] {
        let want = scalar_filter(&image, &gbuffer, params);
        let got = cross_bilateral(&image, &gbuffer, params).unwrap();
        for (i, (a, b)) in got.pixels.iter().zip(&want.pixels).enumerate() {
            for c in 0..3 {
                let (a, b) = (a[c], b[c]);
                let same = a == b
                    || (a.is_nan() && b.is_nan())
                    || (a - b).abs() / b.abs().max(1e-6) < 1e-5;
                assert!(same, "pixel {i} channel {c}: {a} against {b}");
            }
        }
        // The NaN-kd surfaces are filtered: not left as the image's pixel.
        let filtered = (0..got.pixels.len())
            .filter(|i| i % 10 == 0 && gbuffer.samples[*i].is_some())
            .filter(|&i| got.pixels[i] != image.pixels[i] && got.pixels[i].is_finite())
            .count();
        assert!(filtered > 5, "{filtered} NaN-kd surfaces filtered");
    }
}

#[test]
fn an_image_of_another_size_is_an_error() {
    let (image, _) = random_frame(4, 3, 1);
    let (_, gbuffer) = random_frame(3, 4, 1);
    let e = cross_bilateral(&image, &gbuffer, BilateralParams::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        "the filter's image is 4x3 but its G-buffer 3x4"
    );
}
