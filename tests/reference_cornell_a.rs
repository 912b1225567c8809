//! Agreement with an independent renderer: `shared/reference/cornell-a` holds direct and
//! one-bounce indirect images that Mitsuba 3 rendered with 32768 spp from the same glTF scene
//! (box pixel filter, point light in W/sr, one-sided diffuse + GGX surfaces).
//!
//! "Within noise" is tested without trusting any fixed tolerance: each method renders two
//! independent images A and B (different seeds) and their mean M. For unbiased estimators,
//! E|A - B|² = 2σ² and E|M - truth|² = σ²/2, so the expected squared error of M against the
//! reference is |A - B|²/4 plus the reference's own squared standard error. A bias b anywhere
//! adds b² to the left side only. The test also bounds the error of the image means by five
//! standard errors of our mean.
use glam::Vec3;
use slc_core::frame::{LobeSelection, Method, RenderSettings};
use slc_core::{load_scene, Image};
use slc_cpu_ref::render;
use std::path::{Path, PathBuf};

fn reference_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/reference/cornell-a")
}

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
    rel_mean_error: Vec3,
    rmse: f64,
    expected_rmse: f64,
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

fn render_pair(
    method: Method,
    visibility: bool,
    width: u32,
    rsm: u32,
    spp: u32,
) -> [(Image, Image); 2] {
    let scene = load_scene(reference_dir().join("cornell-a.gltf").to_str().unwrap())
        .expect("reference scene loads");
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

#[test]
fn path_reference_agrees_with_mitsuba() {
    let dir = reference_dir();
    let [(da, db), (ia, ib)] = render_pair(Method::Path, true, 256, 1, 16);
    for (name, a, b, reference, stderr) in [
        ("direct", &da, &db, "direct.exr", "direct_stderr.exr"),
        ("indirect", &ia, &ib, "indirect.exr", "indirect_stderr.exr"),
    ] {
        let r = agreement(
            &format!("path {name}"),
            a,
            b,
            &read_exr(&dir.join(reference)),
            &read_exr(&dir.join(stderr)),
        );
        assert!(
            r.rmse <= 1.1 * r.expected_rmse,
            "path {name}: RMSE {} exceeds noise {}",
            r.rmse,
            r.expected_rmse
        );
        assert!(r.rel_mean_error.abs().max_element() < 0.01);
    }
}

#[test]
fn vpl_reference_with_visibility_agrees_with_mitsuba() {
    // 128 x 128 against the reference box-filtered 2 x 2: the same pixel filter at half the
    // resolution, so the VPL-to-pixel shadow rays stay affordable.
    let dir = reference_dir();
    let [(da, db), (ia, ib)] = render_pair(Method::VplReference, true, 128, 16, 8);
    for (name, a, b, reference, stderr) in [
        ("direct", &da, &db, "direct.exr", "direct_stderr.exr"),
        ("indirect", &ia, &ib, "indirect.exr", "indirect_stderr.exr"),
    ] {
        let reference = downsample(&read_exr(&dir.join(reference)), 2);
        let stderr = downsample_stderr(&read_exr(&dir.join(stderr)), 2);
        let r = agreement(&format!("vpl {name}"), a, b, &reference, &stderr);
        assert!(
            r.rmse <= 1.1 * r.expected_rmse,
            "vpl {name}: RMSE {} exceeds noise {}",
            r.rmse,
            r.expected_rmse
        );
        assert!(r.rel_mean_error.abs().max_element() < 0.02);
    }
}
