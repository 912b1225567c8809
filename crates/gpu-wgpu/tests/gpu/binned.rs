//! The `binned` strategy on the GPU (`cull::binned`) against the CPU's `binned` and the
//! brute force of `slc_cull::metrics` (every pair with p > ξ, counted pair by pair): no pair is
//! ever missed, on the built-in scene and with its VPLs at the extremes (α 1e-4…1, anisotropic
//! lobes, Schlick and dielectric Fresnel, ξ near 0 and 1, flux over 12 decades) at δ from
//! 1e-9 (ranges far above a tile: lists of every VPL) to 1e3 (ranges far below a pixel); the
//! lists equal the CPU's tested per pixel (`BinnedCuller::per_pixel`) but for entries decided
//! within rounding at a bound's surface (the GPU tests in f32 with a limit above its rounding,
//! the CPU in f64), and lie within the CPU's default lists (whose large ranges are shared per
//! cell) but for such entries; shading the lists, the GPU's and the CPU's with shared lists, gives the unculled
//! estimate bit for bit; frames without pixels or VPLs give empty lists.
use crate::common::{cull_input, gpu};
use crate::tight::{extra, extreme};
use crate::tiled::frame;
use slc_core::{
    builtin, CullInput, Culler, GBuffer, Interleaving, LightLists, Strategy, Vpl, NO_LIST,
};
use slc_cull::metrics::measure;
use slc_cull::BinnedCuller;
use slc_gpu_wgpu::cull::frame::CullFrame;
use slc_gpu_wgpu::cull::room::settled;
use slc_gpu_wgpu::cull::{GpuCulling, ListCulling};
use slc_gpu_wgpu::shade::lists::ShadePass;
use slc_gpu_wgpu::GpuError;

/// Every list ascends in the VPL index (the CPU's order; no atomics decide it).
fn ascending(lists: &LightLists) -> bool {
    (0..lists.pixel_list.len()).all(|p| lists.for_pixel(p).windows(2).all(|w| w[0] < w[1]))
}

/// Blanks a rectangle and every 5th pixel of `g` (sky: no sample).
fn with_sky(g: &GBuffer) -> GBuffer {
    let mut g = g.clone();
    let w = g.width as usize;
    for (p, s) in g.samples.iter_mut().enumerate() {
        let (x, y) = (p % w, p / w);
        if p % 5 == 2 || (x < w / 3 && y < 11) {
            *s = None;
        }
    }
    g
}

/// The scene's VPLs and extreme ones at δ 1e-9…1e3 and K 1…64, with and without sky, and on
/// an image whose subregion has more tiles than one workgroup bins at a time: 0 missed
/// pairs, the CPU's true positives, lists ascending; entries on the CPU only at most 1e-4 of
/// all or 10 (decided within rounding at a bound's surface), on the GPU only at most 1e-3 of
/// all (or 1) on the scene's VPLs and 5% with the extremes' sharp lobes: the GPU's f32 test allows
/// 1 + 36 ε along/across (`binned_footprint.wesl`), which at α = 1e-4 (along/across = 5000)
/// widens the spheroid by 1%. Seen: a few dozen entries on either side only among millions on
/// the scene's VPLs; up to 3% on the GPU only and none on the CPU only with the extremes.
#[test]
fn binned_lists_never_miss_a_pair_and_match_the_cpu_at_the_extremes() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, scene_vpls) = frame(&scene, &camera, (96, 64), 16);
    let sky = with_sky(&gbuffer);
    // 20 x 14 tiles in its one subregion at K = 1: the bins take them in two batches of 256.
    let (wide, _) = frame(&scene, &camera, (320, 224), 16);
    // 140,000 VPLs (the scene's again and again, new ids and ξ) at K = 8: about 2,190 per
    // subregion, nine rounds of 256, which the bins split into slices of two rounds
    // (`bin_slices`: 512 workgroups wanted); at K = 1 each of the others' rounds is a slice.
    let (small, _) = frame(&scene, &camera, (32, 16), 16);
    let many: Vec<Vpl> = (0..140_000u32)
        .map(|i| {
            let v = scene_vpls[i as usize % scene_vpls.len()];
            let xi = (v.xi + 0.618_034 * (i / scene_vpls.len() as u32) as f32).fract();
            Vpl {
                id: i,
                xi: xi.max(1e-6),
                ..v
            }
        })
        .collect();
    let cases: [(&str, Vec<Vpl>, f32, u32, &GBuffer); 12] = [
        // name, VPLs, δ, K, G-buffer
        ("scene", scene_vpls.clone(), 1e-3, 1, &gbuffer),
        ("scene, short ranges", scene_vpls.clone(), 0.3, 2, &gbuffer),
        ("scene, sky", scene_vpls.clone(), 1e-3, 2, &sky),
        ("extreme 1", extreme(&scene_vpls, 1), 1e-3, 2, &gbuffer),
        ("extreme 2", extreme(&scene_vpls, 2), 1e-9, 4, &gbuffer),
        ("extreme 3", extreme(&scene_vpls, 3), 1e3, 2, &gbuffer),
        ("extreme 4", extreme(&scene_vpls, 4), 1e-2, 3, &sky),
        ("extreme 5", extreme(&scene_vpls, 5), 1e-6, 1, &gbuffer),
        // 1,024 and 4,096 subregions, most with a VPL or none: the partition's sort.
        ("scene, K 32", scene_vpls.clone(), 1e-3, 32, &gbuffer),
        ("scene, K 64", scene_vpls.clone(), 1e-3, 64, &sky),
        (
            "scene, 320x224, short ranges",
            scene_vpls.clone(),
            0.3,
            1,
            &wide,
        ),
        ("scene x 140,000, 32x16", many, 1e-3, 8, &small),
    ];
    for (name, vpls, delta, k, g) in &cases {
        let input = CullInput {
            gbuffer: g,
            camera: &camera,
            vpls,
            delta: *delta,
            interleaving: Interleaving { k: *k, seed: 3 },
        };
        let label = format!("{name} δ {delta} K {k}");
        let gpu = culler.cull(&ctx, &input, Strategy::Binned).unwrap();
        let cpu = BinnedCuller::per_pixel().cull(&input).unwrap();
        let shared = slc_cull::culler(Strategy::Binned).cull(&input).unwrap();
        let m = measure(&input, &gpu).unwrap();
        let c = measure(&input, &cpu).unwrap();
        let entries = m.true_positive_pairs + m.false_positive_pairs;
        let (gpu_only, cpu_only) = (extra(&gpu, &cpu), extra(&cpu, &gpu));
        // Cells only add entries: the GPU's beyond the shared lists are the rounding's.
        assert!(
            extra(&gpu, &shared) <= gpu_only,
            "{label}: beyond the shared lists"
        );
        eprintln!(
            "{label}: TP {} FP {} (CPU {}) per pixel {:.2}, {gpu_only} on the GPU only, \
             {cpu_only} on the CPU only, missed {}",
            m.true_positive_pairs,
            m.false_positive_pairs,
            c.false_positive_pairs,
            m.lights_per_pixel_mean,
            m.missed_pairs
        );
        assert_eq!(m.missed_pairs, 0, "{label}");
        assert_eq!(m.true_positive_pairs, c.true_positive_pairs, "{label}");
        assert!(ascending(&gpu), "{label}: a list out of order");
        let gpu_share = if name.starts_with("scene") { 1_000 } else { 20 };
        assert!(
            cpu_only as u64 * 10_000 <= entries.max(100_000)
                && gpu_only as u64 * gpu_share <= entries.max(1_000),
            "{label}: {gpu_only} on the GPU only, {cpu_only} on the CPU only, of {entries}"
        );
        // Pixels without a sample have no list.
        for (p, s) in g.samples.iter().enumerate() {
            if s.is_none() {
                assert_eq!(gpu.pixel_list[p], NO_LIST, "{label}: pixel {p}");
            }
        }
    }
}

/// Shading the binned lists on the GPU gives the unculled estimate bit for bit: a VPL left
/// out contributes exactly 0 (p <= ξ), and the lists keep the VPLs' order.
#[test]
fn binned_shading_equals_the_unculled_estimate() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let shade = ShadePass::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, scene_vpls) = frame(&scene, &camera, (64, 40), 16);
    for (name, vpls, delta, k) in [
        ("scene", scene_vpls.clone(), 1e-3, 2),
        ("extreme", extreme(&scene_vpls, 7), 1e-2, 3),
    ] {
        let input = cull_input(&gbuffer, &camera, &vpls, delta, (k, 5));
        let frame = CullFrame::upload(&ctx, &input).unwrap();
        let image = |strategy| {
            let lists = settled(&ctx, || culler.cull_frame(&ctx, &frame, strategy)).unwrap();
            shade.shade_read_back(&ctx, &input, &lists).unwrap()
        };
        let binned = image(Strategy::Binned);
        let unculled = image(Strategy::None);
        // The CPU's lists with shared ones, uploaded as one list per pixel.
        let cpu = slc_cull::culler(Strategy::Binned).cull(&input).unwrap();
        assert_eq!(
            shade.shade(&ctx, &input, &cpu).unwrap().pixels,
            unculled.pixels,
            "{name}: CPU lists"
        );
        let lit = binned
            .pixels
            .iter()
            .filter(|p| p.max_element() > 0.0)
            .count();
        assert!(lit * 2 > binned.pixels.len(), "{name}: {lit} lit pixels");
        assert_eq!(binned.pixels, unculled.pixels, "{name}");
    }
}

/// Frames without pixels or without VPLs: empty lists, every pixel without one.
#[test]
fn empty_frames_give_empty_lists() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (24, 16), 8);
    let none: Vec<Vpl> = Vec::new();
    let empty = GBuffer {
        width: 0,
        height: 0,
        samples: Vec::new(),
    };
    let all_sky = GBuffer {
        samples: vec![None; gbuffer.samples.len()],
        ..gbuffer.clone()
    };
    for (name, g, v) in [
        ("no VPLs", &gbuffer, &none),
        ("no pixels", &empty, &vpls),
        ("no samples", &all_sky, &vpls),
    ] {
        let input = cull_input(g, &camera, v, 1e-3, (2, 1));
        let lists = culler.cull(&ctx, &input, Strategy::Binned).unwrap();
        assert!(lists.indices.is_empty(), "{name}");
        assert_eq!(lists.pixel_list.len(), g.samples.len(), "{name}");
        assert!(lists.pixel_list.iter().all(|&l| l == NO_LIST), "{name}");
        let cpu = slc_cull::culler(Strategy::Binned).cull(&input).unwrap();
        assert!(cpu.indices.is_empty(), "{name}");
    }
}

/// Lists beyond one storage binding (every VPL in every pixel's list at δ 1e-9, K 1: about
/// 6,000 pixels × 11,000 VPLs, 204 MB) are refused with the typed error naming the light
/// lists and what to lower, never truncated and never a panic; an adapter whose binding holds
/// them returns them whole.
#[test]
fn lists_beyond_one_binding_are_refused_by_name() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (96, 64), 32);
    let input = cull_input(&gbuffer, &camera, &vpls, 1e-9, (1, 1));
    let limit = ctx.storage_limit();
    match culler.cull(&ctx, &input, Strategy::Binned) {
        Err(e @ GpuError::BufferTooLarge { .. }) => {
            let text = e.to_string();
            eprintln!("{} VPLs: {text}", vpls.len());
            assert!(
                text.contains("light lists") && text.contains("--backend cpu"),
                "{text}"
            );
        }
        Ok(lists) => {
            assert!(lists.indices.len() as u64 * 4 <= limit);
            assert_eq!(measure(&input, &lists).unwrap().missed_pairs, 0);
        }
        Err(e) => panic!("{e}"),
    }
}
