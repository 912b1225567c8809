//! The rasterization baselines of the paper's Table 2 (`cull::raster::splat` [DS06],
//! `cull::raster::clusters` [OP16]): no pair with p > ξ is ever missed (every pair counted by the
//! CPU's brute force), with the scene's VPLs and with VPLs at the extremes (bounds that hold
//! the camera, α 1e-4…1, ξ near 0 and 1, δ over twelve decades), at several K; they cull
//! (fewer pairs than no culling); and the renderer's images equal the tiled ellipsoid's up to
//! f32 rounding of the sums' order, with the same true positives.
use crate::common::{cull_input, gpu, small_frame};
use crate::tight::extreme;
use crate::tiled::frame_sampled;
use slc_core::render::render;
use slc_core::{builtin, Camera, GBuffer, Strategy, Vpl};
use slc_cpu_ref::gbuffer::PixelSample;
use slc_gpu_wgpu::cull::GpuCulling;
use slc_gpu_wgpu::cull::ListCulling;
use slc_gpu_wgpu::GpuRenderer;

/// The built-in scene's camera, G-buffer of `size` and VPLs from RSMs of `rsm`², sampled at
/// pixel centres: splatting rasterizes the rays through them.
fn centred_frame(size: (u32, u32), rsm: u32) -> (Camera, GBuffer, Vec<Vpl>) {
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame_sampled(&scene, &camera, size, rsm, PixelSample::Centre);
    (camera, gbuffer, vpls)
}

#[test]
fn raster_baselines_miss_no_pair() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let (camera, gbuffer, vpls) = centred_frame((64, 48), 16);
    let wild = extreme(&vpls, 3);
    let cases: Vec<(&str, &[Vpl], f32, u32)> = vec![
        ("scene", &vpls, 1e-3, 1),
        ("scene", &vpls, 1e-3, 3),
        ("scene", &vpls, 1e-2, 8),
        ("extreme", &wild, 1e-9, 1),
        ("extreme", &wild, 1e-3, 4),
        ("extreme", &wild, 1e3, 2),
    ];
    for (name, vpls, delta, k) in cases {
        let input = cull_input(&gbuffer, &camera, vpls, delta, (k, 4));
        let none = culler.cull(&ctx, &input, Strategy::None).unwrap();
        let all = slc_cull::metrics::measure(&input, &none).unwrap();
        for strategy in Strategy::RASTER {
            let lists = culler.cull(&ctx, &input, strategy).unwrap();
            let m = slc_cull::metrics::measure(&input, &lists).unwrap();
            let label = format!("{strategy} {name} δ {delta} K {k}");
            println!(
                "{label}: TP {} FP {} (none {}) missed {}",
                m.true_positive_pairs,
                m.false_positive_pairs,
                all.false_positive_pairs,
                m.missed_pairs
            );
            assert_eq!(m.missed_pairs, 0, "{label}");
            assert_eq!(m.true_positive_pairs, all.true_positive_pairs, "{label}");
            if name == "scene" {
                assert!(
                    10 * m.false_positive_pairs < 9 * all.false_positive_pairs,
                    "{label}: {} of {} false positives",
                    m.false_positive_pairs,
                    all.false_positive_pairs
                );
            }
        }
    }
}

/// clustered-raster's shell pass rasterized conservatively by the adapter (where it can:
/// `Features::CONSERVATIVE_RASTERIZATION`) lists exactly what the software form lists, on the
/// scene's VPLs and on extreme ones (bounds that hold the camera, which the hardware form
/// draws as the whole viewport, as the software form does). Without the feature the
/// hardware form cannot be chosen.
#[test]
fn hardware_conservative_rasterization_lists_the_software_forms_cells() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let rasterizer = culler.rasterizer();
    if !ctx.conservative_raster {
        eprintln!(
            "notice: {} has no conservative rasterization; only the software form runs",
            ctx.adapter_name
        );
        assert!(!rasterizer.hardware() && !rasterizer.set_hardware(true));
        return;
    }
    assert!(
        rasterizer.hardware(),
        "hardware is the default where the adapter has it"
    );
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame_sampled(&scene, &camera, (96, 64), 16, PixelSample::Centre);
    let wild = extreme(&vpls, 5);
    for (name, vpls, delta, k) in [
        ("scene", &vpls, 1e-3, 1),
        ("scene", &vpls, 1e-3, 4),
        ("extreme", &wild, 1e-9, 1),
        ("extreme", &wild, 1e-3, 3),
    ] {
        let input = cull_input(&gbuffer, &camera, vpls, delta, (k, 8));
        assert!(rasterizer.set_hardware(true));
        let hardware = culler
            .cull(&ctx, &input, Strategy::ClusteredRaster)
            .unwrap();
        assert!(!rasterizer.set_hardware(false));
        let software = culler
            .cull(&ctx, &input, Strategy::ClusteredRaster)
            .unwrap();
        assert!(rasterizer.set_hardware(true));
        let differing = (0..input.gbuffer.samples.len())
            .filter(|&p| hardware.for_pixel(p) != software.for_pixel(p))
            .count();
        println!(
            "{name} δ {delta} K {k}: {} entries in hardware, {} in software, {differing} \
             pixels differ",
            hardware.indices.len(),
            software.indices.len()
        );
        assert_eq!(differing, 0, "{name} δ {delta} K {k}");
    }
}

/// Every frame of the renderer with a raster baseline: the tiled ellipsoid's image up to the
/// rounding of a different summation order, and its true positives.
#[test]
fn raster_baselines_render_the_tiled_image() {
    let Some(ctx) = gpu() else { return };
    let renderer = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    let settings = |strategy| small_frame(strategy, false);
    let want = render(&renderer, &scene, &settings(Strategy::Ellipsoid), &|_| {}).unwrap();
    let lit = want
        .indirect
        .pixels
        .iter()
        .filter(|p| p.max_element() > 0.0)
        .count();
    assert!(lit * 2 > want.indirect.pixels.len(), "{lit} lit");
    for strategy in Strategy::RASTER {
        let got = render(&renderer, &scene, &settings(strategy), &|_| {}).unwrap();
        for (p, (a, b)) in got
            .indirect
            .pixels
            .iter()
            .zip(&want.indirect.pixels)
            .enumerate()
        {
            let tolerance = 1e-4 * a.max_element().max(b.max_element()) + 1e-9;
            assert!(
                (*a - *b).abs().max_element() <= tolerance,
                "{strategy} pixel {p}: {a} against {b}"
            );
        }
        let (m, w) = (got.metrics.unwrap(), want.metrics.as_ref().unwrap());
        assert_eq!(m.missed_pairs, 0, "{strategy}");
        assert_eq!(m.true_positive_pairs, w.true_positive_pairs, "{strategy}");
    }
}

/// An image whose size K does not divide, and no VPL at all: nothing missed, and without
/// VPLs empty lists and no error.
#[test]
fn raster_baselines_at_odd_sizes_and_without_vpls() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let (camera, gbuffer, vpls) = centred_frame((37, 23), 8);
    for (vpls, k) in [(&vpls[..], 3), (&vpls[..], 5), (&[][..], 2)] {
        let input = cull_input(&gbuffer, &camera, vpls, 1e-3, (k, 1));
        for strategy in Strategy::RASTER {
            let lists = culler.cull(&ctx, &input, strategy).unwrap();
            let m = slc_cull::metrics::measure(&input, &lists).unwrap();
            assert_eq!(m.missed_pairs, 0, "{strategy} K {k}");
            if vpls.is_empty() {
                assert!(lists.indices.is_empty(), "{strategy}");
            }
        }
    }
    // One draw per subregion: K beyond 64 is refused, not drawn 4,225 times.
    let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (65, 1));
    for strategy in Strategy::RASTER {
        match culler.cull(&ctx, &input, strategy) {
            Err(e) => assert!(e.to_string().contains("exceeds 64"), "{strategy}: {e}"),
            Ok(_) => panic!("{strategy} drew K = 65"),
        }
    }
}
