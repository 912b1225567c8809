//! What the agreement tests with Mitsuba 3 share: reading its EXR images, box-filtering them
//! down, and comparing the mean of two independent renders of ours with a reference.
//!
//! "Within noise" is tested without trusting any fixed tolerance: each method renders two
//! independent images A and B (different seeds) and their mean M. For unbiased estimators,
//! E|A - B|² = 2σ² and E|M - truth|² = σ²/2, so the expected squared error of M against the
//! reference is |A - B|²/4 plus the reference's own squared standard error. A bias b anywhere
//! adds b² to the left side only. [`agreement`] also bounds the error of the image means by
//! five standard errors of our mean.
use glam::Vec3;
use slc_core::frame::{LobeSelection, Method, RenderSettings};
use slc_core::{load_scene, Image};
use slc_cpu_ref::render;
use std::path::Path;

fn read_exr(path: &Path) -> Image {
    use exr::prelude::*;
    let img = read_first_rgba_layer_from_file(
        path,
        |res, _| (res.width(), vec![Vec3::ZERO; res.width() * res.height()]),
        |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b)
        },
    )
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let size = img.layer_data.size;
    slc_core::Image {
        width: size.width() as u32,
        height: size.height() as u32,
        pixels: img.layer_data.channel_data.pixels.1,
    }
}

/// Box-filters an image down by an integer factor: exactly the reference's pixel filter at a
/// coarser resolution (each coarse pixel averages radiance over its square).
fn downsample(img: &Image, f: u32) -> Image {
    let (w, h) = (img.width / f, img.height / f);
    let mut out = Image::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let mut s = Vec3::ZERO;
            for dy in 0..f {
                for dx in 0..f {
                    s += img.get(x * f + dx, y * f + dy);
                }
            }
            out.pixels[(y * w + x) as usize] = s / (f * f) as f32;
        }
    }
    out
}

/// Standard errors add in quadrature when averaging f x f pixels.
fn downsample_stderr(img: &Image, f: u32) -> Image {
    let sq = Image {
        pixels: img.pixels.iter().map(|p| *p * *p).collect(),
        ..img.clone()
    };
    let mut d = downsample(&sq, f);
    for p in &mut d.pixels {
        *p = (*p / (f * f) as f32).max(Vec3::ZERO).map(f32::sqrt);
    }
    d
}

fn mean_sq(img: &Image) -> f64 {
    img.pixels
        .iter()
        .map(|p| p.length_squared() as f64)
        .sum::<f64>()
        / (3.0 * img.pixels.len() as f64)
}

struct Agreement {
    pub rel_mean_error: Vec3,
    pub rmse: f64,
    pub expected_rmse: f64,
}

/// Compares the mean of two independent renders with the reference (see the module doc).
fn agreement(
    name: &str,
    a: &Image,
    b: &Image,
    reference: &Image,
    reference_stderr: &Image,
) -> Agreement {
    let m = Image {
        pixels: a
            .pixels
            .iter()
            .zip(&b.pixels)
            .map(|(x, y)| 0.5 * (*x + *y))
            .collect(),
        ..a.clone()
    };
    assert!(
        m.is_finite_non_negative(),
        "{name}: NaN, Inf or negative radiance"
    );
    let ab_sq = a.rmse(b).powi(2) as f64;
    let expected_sq = ab_sq / 4.0 + mean_sq(reference_stderr);
    let rmse = m.rmse(reference) as f64;
    let (mm, rm) = (m.mean(), reference.mean());
    let rel_mean_error = (mm - rm) / rm;
    // Standard error of our image mean, per channel, from the spread of A - B.
    let n = a.pixels.len() as f64;
    let se = (ab_sq / 4.0 / n).sqrt() as f32;
    println!(
        "{name}: mean ours {mm:.5} vs reference {rm:.5} (relative error {:+.3}%, {:+.3}%, {:+.3}%), \
         RMSE {rmse:.5}, expected from noise {:.5}, standard error of our mean {se:.2e}",
        100.0 * rel_mean_error.x,
        100.0 * rel_mean_error.y,
        100.0 * rel_mean_error.z,
        expected_sq.sqrt()
    );
    for c in 0..3 {
        assert!(
            (mm[c] - rm[c]).abs() <= 5.0 * se + 1e-4 * rm[c],
            "{name}: channel {c} mean {} vs reference {} (5 standard errors: {})",
            mm[c],
            rm[c],
            5.0 * se
        );
    }
    Agreement {
        rel_mean_error,
        rmse,
        expected_rmse: expected_sq.sqrt(),
    }
}

/// The direct and indirect images of `scene` (a glTF path) rendered with seeds 1 and 2:
/// `[(direct A, direct B), (indirect A, indirect B)]`.
pub fn render_pair(
    scene: &Path,
    method: Method,
    visibility: bool,
    width: u32,
    rsm: u32,
    spp: u32,
) -> [(Image, Image); 2] {
    let scene = load_scene(scene.to_str().unwrap()).expect("reference scene loads");
    let run = |seed| {
        let s = RenderSettings {
            width,
            height: width,
            rsm_resolution: rsm,
            seed,
            method,
            visibility,
            spp,
            lobes: LobeSelection::Both,
        };
        let f = render(&scene, &s, &|_| {}).expect("renders");
        (f.direct, f.indirect)
    };
    let (da, ia) = run(1);
    let (db, ib) = run(2);
    [(da, db), (ia, ib)]
}

/// Checks `[(direct A, direct B), (indirect A, indirect B)]` against `dir`'s `direct.exr` and
/// `indirect.exr` with their standard errors, box-filtered down by `factor`: the RMSE of the
/// mean within 1.1 times what noise explains, image means within five standard errors (in
/// [`agreement`]) and within `max_rel_mean_error` relative.
#[allow(dead_code)] // Each test file compiles this module; the narrow spot's compares one image.
pub fn assert_agrees(
    label: &str,
    [(da, db), (ia, ib)]: [(Image, Image); 2],
    dir: &Path,
    factor: u32,
    max_rel_mean_error: f32,
) {
    let images = [("direct", &da, &db), ("indirect", &ia, &ib)];
    assert_images_agree(label, &images, dir, factor, max_rel_mean_error);
}

/// [`assert_agrees`] for the images `(name, A, B)` given, each against `dir`'s `name.exr`
/// and `name_stderr.exr`.
pub fn assert_images_agree(
    label: &str,
    images: &[(&str, &Image, &Image)],
    dir: &Path,
    factor: u32,
    max_rel_mean_error: f32,
) {
    for &(name, a, b) in images {
        let reference = downsample(&read_exr(&dir.join(format!("{name}.exr"))), factor);
        let stderr = downsample_stderr(&read_exr(&dir.join(format!("{name}_stderr.exr"))), factor);
        let r = agreement(&format!("{label} {name}"), a, b, &reference, &stderr);
        assert!(
            r.rmse <= 1.1 * r.expected_rmse,
            "{label} {name}: RMSE {} exceeds noise {}",
            r.rmse,
            r.expected_rmse
        );
        assert!(
            r.rel_mean_error.abs().max_element() < max_rel_mean_error,
            "{label} {name}: relative mean error {}",
            r.rel_mean_error
        );
    }
}
