//! The tight strategies on the GPU (`cull::tight`, `cull/box_bound.wesl`): no pair
//! with p > ξ is ever missed (every pair counted by the CPU's brute force), on the built-in
//! scene and with its VPLs pushed to the extremes (α 1e-4…1, anisotropic lobes, Schlick and
//! dielectric Fresnel, ξ near 0 and 1, flux and δ over many decades); every refined list is a
//! subset of the pixel's list of the base strategy; and the lists stay within rounding of
//! the CPU's.
use crate::common::{cull_input, gpu};
use crate::tiled::frame;
use slc_bounds::{Anisotropy, Fresnel};
use slc_core::rng::Sequence;
use slc_core::{builtin, CullInput, Interleaving, LightLists, Strategy, Vpl, VplLobe};
use slc_gpu_wgpu::cull::GpuCulling;
use slc_gpu_wgpu::cull::ListCulling;
use slc_gpu_wgpu::GpuContext;

/// The tight strategies and the base strategy each refines.
const TIGHT: [(Strategy, Strategy); 2] = [
    (Strategy::Tight, Strategy::Ellipsoid),
    (Strategy::ClusteredTight, Strategy::Clustered),
];

/// `vpls` with random lobes at the extremes: α log-uniform in 1e-4…1 (a fifth anisotropic),
/// half the glossy ones dielectric, ξ near 0, near 1 or uniform, flux scaled by 1e-6…1e6.
pub fn extreme(vpls: &[Vpl], seed: u32) -> Vec<Vpl> {
    vpls.iter()
        .enumerate()
        .map(|(i, v)| {
            let mut r = Sequence::new(seed, i as u32, 0, 0);
            let mut v = *v;
            v.brdf.alpha = 10f32.powf(-4.0 * r.next_f32());
            v.lobe = if r.next_f32() < 0.3 {
                VplLobe::Diffuse
            } else {
                VplLobe::Glossy
            };
            if r.next_f32() < 0.5 {
                v.brdf.fresnel = Fresnel::Dielectric(1.05 + 1.5 * r.next_f32());
            }
            v.brdf.anisotropy = None;
            if r.next_f32() < 0.2 {
                let tangent = v.normal.any_orthonormal_vector();
                let alpha_t = (v.brdf.alpha + (1.0 - v.brdf.alpha) * r.next_f32()).max(1e-4);
                v.brdf.anisotropy = Some(Anisotropy { tangent, alpha_t });
            }
            v.xi = match (4.0 * r.next_f32()) as u32 {
                0 => 1e-6 * r.next_f32().max(1e-3),
                1 => 1.0 - 1e-6 * r.next_f32().max(0.1),
                _ => r.next_f32().clamp(1e-7, 1.0 - 1e-7),
            };
            v.flux *= 10f32.powf(12.0 * r.next_f32() - 6.0);
            v
        })
        .collect()
}

/// Lists of `strategy` on the GPU for `input`, read back.
fn gpu_lists(
    ctx: &GpuContext,
    culler: &GpuCulling,
    input: &CullInput,
    strategy: Strategy,
) -> LightLists {
    culler.cull(ctx, input, strategy).unwrap()
}

/// Entries of `a` not in `b`, over every pixel.
pub fn extra(a: &LightLists, b: &LightLists) -> usize {
    (0..a.pixel_list.len())
        .map(|p| {
            let theirs = b.for_pixel(p);
            a.for_pixel(p)
                .iter()
                .filter(|v| !theirs.contains(v))
                .count()
        })
        .sum()
}

/// Built-in scene and extreme VPLs at several δ, K and seeds: 0 missed pairs, each list a
/// subset of the base strategy's, and at least a tenth fewer false positives than the base
/// (on the scene's own VPLs at δ 1e-3 about 70% fewer).
#[test]
fn tight_lists_never_miss_a_pair_and_refine_their_base() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, scene_vpls) = frame(&scene, &camera, (96, 64), 16);
    let cases = [
        (scene_vpls.clone(), 1e-3, 1),
        (extreme(&scene_vpls, 1), 1e-3, 2),
        (extreme(&scene_vpls, 2), 1e-9, 4),
        (extreme(&scene_vpls, 3), 1e3, 2),
        (extreme(&scene_vpls, 4), 1e-2, 3),
    ];
    for (vpls, delta, k) in &cases {
        let input = CullInput {
            gbuffer: &gbuffer,
            camera: &camera,
            vpls,
            delta: *delta,
            interleaving: Interleaving { k: *k, seed: 3 },
        };
        for (tight, base) in TIGHT {
            let label = format!("{} δ {delta} K {k}", tight.name());
            let lists = gpu_lists(&ctx, &culler, &input, tight);
            let base_lists = gpu_lists(&ctx, &culler, &input, base);
            let m = slc_cull::metrics::measure(&input, &lists).unwrap();
            let b = slc_cull::metrics::measure(&input, &base_lists).unwrap();
            eprintln!(
                "{label}: TP {} FP {} (base {}) missed {}",
                m.true_positive_pairs,
                m.false_positive_pairs,
                b.false_positive_pairs,
                m.missed_pairs
            );
            assert_eq!(m.missed_pairs, 0, "{label}");
            assert_eq!(m.true_positive_pairs, b.true_positive_pairs, "{label}");
            assert_eq!(extra(&lists, &base_lists), 0, "{label}: not a subset");
            if b.false_positive_pairs > 1000 {
                assert!(
                    10 * m.false_positive_pairs < 9 * b.false_positive_pairs,
                    "{label}: {} vs {}",
                    m.false_positive_pairs,
                    b.false_positive_pairs
                );
            }
        }
    }
}

/// A bound that keeps too little is caught: the same lists with δ grown tenfold on the GPU
/// (every VPL's range shrunk) miss pairs of the true δ, so the no-miss tests of the tight
/// strategies (above) and of `binned` (`binned.rs`) can fail.
#[test]
fn a_shrunk_bound_misses_pairs() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (64, 48), 16);
    let input = |delta| CullInput {
        gbuffer: &gbuffer,
        camera: &camera,
        vpls: &vpls,
        delta,
        interleaving: Interleaving { k: 2, seed: 3 },
    };
    for strategy in TIGHT
        .map(|(tight, _)| tight)
        .into_iter()
        .chain([Strategy::Binned])
    {
        let shrunk = gpu_lists(&ctx, &culler, &input(1e-2), strategy);
        let m = slc_cull::metrics::measure(&input(1e-3), &shrunk).unwrap();
        assert!(
            m.missed_pairs > 100,
            "{}: {}",
            strategy.name(),
            m.missed_pairs
        );
    }
}

/// `vpls` with every other glossy lobe a dielectric of η 1.5 (Fresnel of supplemental
/// eq. 3-6, far below 1 near normal incidence).
fn dielectric(vpls: &[Vpl]) -> Vec<Vpl> {
    vpls.iter()
        .enumerate()
        .map(|(i, v)| {
            let mut v = *v;
            if i % 2 == 0 {
                v.brdf.fresnel = Fresnel::Dielectric(1.5);
            }
            v
        })
        .collect()
}

/// The GPU's lists against the CPU's on the same input, the scene's VPLs and half of them
/// dielectric: entries on one side only are at most 1%, from the f32 bound's slacks and the
/// f32 depth splits (a Fresnel factor the GPU dropped would show here).
#[test]
fn tight_lists_are_within_rounding_of_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, scene_vpls) = frame(&scene, &camera, (72, 50), 16);
    for (label, vpls) in [
        ("scene", scene_vpls.clone()),
        ("dielectric", dielectric(&scene_vpls)),
    ] {
        let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (2, 4));
        for (tight, _) in TIGHT {
            let name = format!("{} ({label})", tight.name());
            let gpu = gpu_lists(&ctx, &culler, &input, tight);
            let cpu = slc_cull::culler(tight).cull(&input).unwrap();
            let entries: usize = (0..cpu.pixel_list.len())
                .map(|p| cpu.for_pixel(p).len())
                .sum();
            let (gpu_only, cpu_only) = (extra(&gpu, &cpu), extra(&cpu, &gpu));
            eprintln!("{name}: {entries} CPU entries, {gpu_only} on the GPU only, {cpu_only} on the CPU only");
            assert!(
                (gpu_only + cpu_only) * 100 <= entries,
                "{name}: {gpu_only} + {cpu_only} of {entries}"
            );
        }
    }
}
