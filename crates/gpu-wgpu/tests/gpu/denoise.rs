//! The GPU cross bilateral filter against `slc_cpu_ref::denoise::cross_bilateral` for
//! identical inputs (image, G-buffer, parameters): every pixel must agree within 1e-4
//! relative, `max_c |gpu − cpu| <= 1e-4 · max_c |cpu|` (each output is a positively weighted
//! average of its taps, so a relative bound holds down to zero, where both are exactly 0);
//! pixels without a sample must keep their value exactly. On the default scene's noisy
//! stochastic image (interleaved sampling, K = 4) and on synthetic frames of extremes.
use crate::common::{cull_input, gpu};
use crate::tiled::frame;
use glam::Vec3;
use slc_bounds::{Brdf, Fresnel};
use slc_core::{builtin, Camera, GBuffer, GSample, Image};
use slc_cpu_ref::denoise::{cross_bilateral, BilateralParams};
use slc_cpu_ref::vpl_shading::shade_lists;
use slc_cpu_ref::Tracer;
use slc_gpu_wgpu::device::buffers::{output, upload};
use slc_gpu_wgpu::frame::denoise::{DenoisePass, Guide};
use slc_gpu_wgpu::{GpuContext, GpuError};

const TOLERANCE: f32 = 1e-4;

/// Parameter sets: the defaults (the paper's radius 8) and a narrow, sharp one.
fn settings() -> [BilateralParams; 2] {
    [
        BilateralParams::default(),
        BilateralParams {
            radius: 3,
            sigma_spatial: 1.5,
            sigma_depth: 0.2,
            normal_squarings: 2,
        },
    ]
}

/// The largest relative error over the image; panics naming the first pixel beyond the
/// tolerance or a pixel without a sample that changed.
fn compare(label: &str, g: &GBuffer, image: &Image, gpu: &Image, cpu: &Image) -> f32 {
    assert_eq!((gpu.width, gpu.height), (cpu.width, cpu.height));
    let mut worst = 0.0f32;
    for (p, ((a, b), s)) in gpu
        .pixels
        .iter()
        .zip(&cpu.pixels)
        .zip(&g.samples)
        .enumerate()
    {
        let (x, y) = (p as u32 % g.width, p as u32 / g.width);
        if s.is_none() {
            assert_eq!(*a, image.pixels[p], "{label}: sky pixel ({x}, {y}) changed");
            continue;
        }
        let err = (*a - *b).abs().max_element();
        let scale = b.abs().max_element();
        assert!(
            err <= TOLERANCE * scale,
            "{label}: pixel ({x}, {y}): GPU {a} CPU {b} (input {})",
            image.pixels[p]
        );
        if scale > 0.0 {
            worst = worst.max(err / scale);
        }
    }
    worst
}

fn filter_both(
    ctx: &GpuContext,
    pass: &DenoisePass,
    label: &str,
    image: &Image,
    g: &GBuffer,
    camera: &Camera,
) -> f32 {
    let mut worst = 0.0f32;
    for s in settings() {
        let gpu = pass.filter(ctx, image, g, camera, &s).unwrap();
        let cpu = cross_bilateral(image, g, s).unwrap();
        worst = worst.max(compare(&format!("{label} {s:?}"), g, image, &gpu, &cpu));
    }
    worst
}

/// The default scene's stochastic indirect light with interleaved sampling (K = 4, no
/// culling), the noise the filter is for.
#[test]
fn filter_matches_the_cpu_on_the_default_scene() {
    let Some(ctx) = gpu() else { return };
    let pass = DenoisePass::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let tracer = Tracer::new(&scene);
    for (size, k) in [((96, 64), 4), ((53, 31), 3)] {
        let (gbuffer, vpls) = frame(&scene, &camera, size, 16);
        let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (k, 1));
        let lists = slc_cull::culler(slc_core::Strategy::None)
            .cull(&input)
            .unwrap();
        let noisy = shade_lists(&tracer, &input, &lists, false, &|_| ()).unwrap();
        let worst = filter_both(&ctx, &pass, "default scene", &noisy, &gbuffer, &camera);
        // The filter did its job: most pixels changed noticeably.
        let cpu = cross_bilateral(&noisy, &gbuffer, BilateralParams::default()).unwrap();
        let changed = cpu
            .pixels
            .iter()
            .zip(&noisy.pixels)
            .filter(|(a, b)| (**a - **b).abs().max_element() > 0.01 * b.max_element())
            .count();
        eprintln!(
            "default scene {size:?} K {k}: largest relative error {worst:.2e}, {changed} of {} \
             pixels changed by more than 1%",
            noisy.pixels.len()
        );
        assert!(changed * 2 > noisy.pixels.len(), "{changed}");
    }
}

#[path = "../../../../tests/fixtures/rng.rs"]
mod rng;
use rng::Rng;

/// A frame of extremes: sky pixels, depth jumps by factors of 100, normals turned away from
/// each other, black and white surfaces, Schlick F0 of 0 and 1 and dielectrics (η 1 gives
/// F(1) = 0, so reflectance 1e-3 where kd = 0), and pixel values of 0, 1e-30, 1 and 1e30.
fn extremes(camera: &Camera, w: u32, h: u32, seed: u64) -> (GBuffer, Image) {
    let mut rng = Rng(seed);
    let mut samples = Vec::new();
    let mut image = Image::new(w, h);
    for p in 0..w * h {
        let (x, y) = (p % w, p / w);
        let value = Vec3::new(
            rng.pick(&[0.0, 1e-30, 1.0, 0.37, 1e30]),
            rng.pick(&[0.0, 1.0, 2.5]),
            rng.pick(&[0.0, 1e30, 0.1]),
        );
        image.pixels[p as usize] = value;
        if rng.f32() < 0.2 {
            samples.push(None);
            continue;
        }
        let dir = camera.ray_direction(x, y, 0.5, 0.5, w, h);
        let t = rng.pick(&[0.5, 0.52, 1.0, 3.0, 3.1, 50.0, 5000.0]);
        let position = camera.position + dir * t;
        let normal = rng
            .pick(&[-dir, Vec3::Y, -Vec3::Y, Vec3::X, Vec3::new(0.6, 0.8, 0.0)])
            .normalize();
        let brdf = Brdf {
            kd: Vec3::splat(rng.pick(&[0.0, 0.5, 1.0])),
            fresnel: rng.pick(&[
                Fresnel::Schlick(Vec3::ZERO),
                Fresnel::Schlick(Vec3::ONE),
                Fresnel::Schlick(Vec3::new(0.95, 0.64, 0.54)),
                Fresnel::Dielectric(1.5),
                Fresnel::Dielectric(1.0),
            ]),
            alpha: 0.3,
            anisotropy: None,
        };
        samples.push(Some(GSample {
            position,
            normal,
            geometric_normal: normal,
            omega_o: -dir,
            depth: camera.view_depth(position),
            brdf,
        }));
    }
    (
        GBuffer {
            width: w,
            height: h,
            samples,
        },
        image,
    )
}

#[test]
fn filter_matches_the_cpu_on_extremes() {
    let Some(ctx) = gpu() else { return };
    let pass = DenoisePass::new(&ctx).unwrap();
    let camera = Camera::look_at(Vec3::new(0.3, 1.0, 4.0), Vec3::ZERO, Vec3::Y, 0.9).unwrap();
    let mut worst = 0.0f32;
    for (i, (w, h)) in [(1, 1), (7, 5), (33, 17), (2, 40), (40, 1)]
        .into_iter()
        .enumerate()
    {
        let (g, image) = extremes(&camera, w, h, 0x9e37_79b9 + i as u64);
        worst = worst.max(filter_both(
            &ctx,
            &pass,
            &format!("{w}x{h}"),
            &image,
            &g,
            &camera,
        ));
    }
    // Only sky: everything is kept.
    let (mut g, image) = extremes(&camera, 9, 4, 5);
    g.samples.iter_mut().for_each(|s| *s = None);
    filter_both(&ctx, &pass, "sky", &image, &g, &camera);
    eprintln!("extremes: largest relative error {worst:.2e}");
}

#[test]
fn filter_rejects_bad_input() {
    let Some(ctx) = gpu() else { return };
    let pass = DenoisePass::new(&ctx).unwrap();
    let camera = Camera::look_at(Vec3::new(0.3, 1.0, 4.0), Vec3::ZERO, Vec3::Y, 0.9).unwrap();
    let (g, image) = extremes(&camera, 6, 5, 77);
    let fine = BilateralParams::default();
    let is_input = |r: Result<Image, GpuError>| matches!(r, Err(GpuError::Input(_)));
    for s in [
        BilateralParams {
            sigma_spatial: 0.0,
            ..fine
        },
        BilateralParams {
            sigma_depth: f32::NAN,
            ..fine
        },
        BilateralParams {
            sigma_depth: 1e-25,
            ..fine
        },
        BilateralParams {
            radius: 100_000,
            ..fine
        },
        BilateralParams {
            normal_squarings: 1000,
            ..fine
        },
    ] {
        assert!(
            is_input(pass.filter(&ctx, &image, &g, &camera, &s)),
            "{s:?}"
        );
    }
    let small = Image::new(5, 5);
    assert!(is_input(pass.filter(&ctx, &small, &g, &camera, &fine)));
    let mut nan = image.clone();
    nan.pixels[7] = Vec3::new(0.0, f32::NAN, 0.0);
    let e = pass.filter(&ctx, &nan, &g, &camera, &fine).unwrap_err();
    assert!(e.to_string().contains("(1, 1)"), "{e}");
    let mut odd = g.clone();
    let p = odd.samples.iter().position(Option::is_some).unwrap();
    odd.samples[p].as_mut().unwrap().depth *= 1.01;
    assert!(is_input(pass.filter(&ctx, &image, &odd, &camera, &fine)));
    // Buffers smaller than the image.
    let samples = upload(
        &ctx,
        "samples",
        &[slc_gpu_wgpu::frame::raster::records::GpuSample::EMPTY; 29],
    )
    .unwrap();
    let rgb = output::<f32>(&ctx, "image", 90).unwrap();
    let positions = output::<[f32; 4]>(&ctx, "positions", 30).unwrap();
    let guide = Guide {
        samples: &samples,
        positions: &positions,
        width: 6,
        height: 5,
        camera: &camera,
    };
    assert!(matches!(
        pass.filter_on_gpu(&ctx, &rgb, &guide, &fine),
        Err(GpuError::Input(_))
    ));
}
