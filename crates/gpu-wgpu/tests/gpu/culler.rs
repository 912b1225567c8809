//! `GpuCulling`: every strategy of `slc_core::Strategy::ALL`, also bound as a
//! `slc_core::Culler`, and its lists left on the GPU read by the shading pass.
use crate::common::{cull_input, gpu};
use crate::tiled::frame;
use glam::Vec3;
use slc_core::{builtin, CullInput, Culler, GlossyBound, Interleaving, Strategy, VplLobe};
use slc_gpu_wgpu::cull::frame::CullFrame;
use slc_gpu_wgpu::cull::lists::read_lists;
use slc_gpu_wgpu::cull::GpuCulling;
use slc_gpu_wgpu::cull::ListCulling;
use slc_gpu_wgpu::device::context::GpuError;
use slc_gpu_wgpu::shade::lists::ShadePass;
use std::cell::RefCell;

/// The built-in default scene and its camera.
fn default_scene() -> (slc_core::Scene, slc_core::Camera) {
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    (scene, camera)
}

/// A cull input with δ = 1e-3 and K = 2.
fn input_k2<'a>(
    gbuffer: &'a slc_core::GBuffer,
    camera: &'a slc_core::Camera,
    vpls: &'a [slc_core::Vpl],
) -> CullInput<'a> {
    CullInput {
        gbuffer,
        camera,
        vpls,
        delta: 1e-3,
        interleaving: Interleaving { k: 2, seed: 4 },
    }
}

/// Each name runs its own strategy: the GPU's lists by name equal the CPU strategy's of the
/// same name but for a few entries decided within rounding (classified in `tiled.rs` and
/// `clustered.rs`; the tight ones, whose bound the GPU forms in f32 with wider slacks, within
/// 1%: `tight.rs`); every other strategy's lists differ in hundreds of entries or more. The
/// CPU forms most bounds in f32 lanes grown by 1e-5 (`slc_cull`'s `vpl_lanes`), so it may
/// list a few more pairs at a bound's edge (26 of 1.17 M for `clustered` here); the GPU
/// lists at most ten the CPU does not.
#[test]
fn every_strategy_by_name_matches_the_cpu_strategy_of_that_name() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let (scene, camera) = default_scene();
    let (gbuffer, vpls) = frame(&scene, &camera, (72, 50), 16);
    let input = input_k2(&gbuffer, &camera, &vpls);
    let strategies = Strategy::ALL;
    // `binned` as the GPU culls it: every VPL per pixel, no shared lists.
    let cpu: Vec<_> = strategies
        .iter()
        .map(|&s| match s {
            Strategy::Binned => slc_cull::BinnedCuller::per_pixel().cull(&input),
            s => slc_cull::culler(s).cull(&input),
        })
        .map(Result::unwrap)
        .collect();
    for (i, &name) in strategies.iter().enumerate() {
        let gpu = culler.cull(&ctx, &input, name).unwrap();
        // The same strategy bound as a `Culler` of frames on the GPU.
        let bound = culler.culler(&ctx, name);
        assert_eq!(bound.strategy(), name);
        let frame = CullFrame::upload(&ctx, &input).unwrap();
        assert_eq!(read_lists(&ctx, &bound.cull(&frame).unwrap()).unwrap(), gpu);
        let differing = |other: &slc_core::LightLists| -> usize {
            (0..gpu.pixel_list.len())
                .map(|p| {
                    let (a, b) = (gpu.for_pixel(p), other.for_pixel(p));
                    a.iter().filter(|v| !b.contains(v)).count()
                        + b.iter().filter(|v| !a.contains(v)).count()
                })
                .sum()
        };
        let own = differing(&cpu[i]);
        let gpu_only: usize = (0..gpu.pixel_list.len())
            .map(|p| {
                let cpu = cpu[i].for_pixel(p);
                gpu.for_pixel(p).iter().filter(|v| !cpu.contains(v)).count()
            })
            .sum();
        let entries: usize = (0..gbuffer.samples.len())
            .map(|p| cpu[i].for_pixel(p).len())
            .sum();
        eprintln!("{name}: {entries} pairs on the CPU, {own} differing, {gpu_only} GPU-only");
        if name.parts().1 == GlossyBound::Tight {
            assert!(own * 100 <= entries, "{name}: {own}");
        } else {
            assert!(
                gpu_only <= 10 && own * 10_000 <= entries,
                "{name}: {own}, {gpu_only}"
            );
        }
        for (j, other) in strategies.iter().enumerate().filter(|&(j, _)| j != i) {
            let d = differing(&cpu[j]);
            assert!(d > 100, "{name} looks like {other}: {d} differing entries");
        }
    }
}

/// The lists of every strategy left on the GPU (32 per tile for the clustered ones, one per
/// subregion without culling) shade exactly like the same lists read back and uploaded.
#[test]
fn shading_reads_every_strategys_lists_on_the_gpu() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let shade = ShadePass::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (40, 23), 16);
    for k in [1, 3] {
        let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (k, 2));
        for strategy in Strategy::ALL {
            let name = strategy.name();
            let frame = CullFrame::upload(&ctx, &input).unwrap();
            let on_gpu = culler.cull_frame(&ctx, &frame, strategy).unwrap();
            let direct = shade.shade_read_back(&ctx, &input, &on_gpu).unwrap();
            let lists = culler.cull(&ctx, &input, strategy).unwrap();
            let uploaded = shade.shade(&ctx, &input, &lists).unwrap();
            assert_eq!(direct.pixels, uploaded.pixels, "{name} K {k}");
            let lit = direct
                .pixels
                .iter()
                .filter(|p| p.max_element() > 0.0)
                .count();
            assert!(
                lit * 2 > direct.pixels.len(),
                "{name} K {k}: {lit} lit pixels"
            );
        }
    }
}

/// Lists that outgrew the room their culler left are refused when read back (a typed error,
/// never truncated lists); used through `use_lists` they are culled again until complete:
/// once more for a list culler, twice for the tight ones with both rooms too small (the
/// base lists, then the refined ones) and for binned (its tiles' bins, then the lists). The
/// complete lists equal those culled with room.
#[test]
fn outgrown_lists_are_refused_or_culled_again() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let (scene, camera) = default_scene();
    let (gbuffer, vpls) = frame(&scene, &camera, (72, 50), 16);
    let input = input_k2(&gbuffer, &camera, &vpls);
    let frame = CullFrame::upload(&ctx, &input).unwrap();
    for (strategy, uses) in [
        (Strategy::Sphere, 2),
        (Strategy::Clustered, 2),
        (Strategy::Tight, 3),
        (Strategy::ClusteredTight, 3),
        (Strategy::Binned, 3),
    ] {
        culler.set_list_room(1 << 20);
        let roomy = culler.cull(&ctx, &input, strategy).unwrap();
        culler.set_list_room(1);
        let cramped = culler.cull_frame(&ctx, &frame, strategy).unwrap();
        assert!(
            matches!(read_lists(&ctx, &cramped), Err(GpuError::ListsOutgrown(_))),
            "{strategy}"
        );
        culler.set_list_room(1);
        let cramped = RefCell::new(culler.cull_frame(&ctx, &frame, strategy).unwrap());
        let mut used = 0;
        let read = culler
            .use_lists(&ctx, &frame, strategy, &cramped, |lists| {
                used += 1;
                Ok(lists.entries)
            })
            .unwrap();
        let settled = cramped.into_inner();
        assert_eq!(used, uses, "{strategy}");
        assert_eq!(read, settled.entries, "{strategy}");
        assert_eq!(read_lists(&ctx, &settled).unwrap(), roomy, "{strategy}");
        // Learnt: the next frame's lists fit at once.
        let next = culler.cull_frame(&ctx, &frame, strategy).unwrap();
        assert_eq!(read_lists(&ctx, &next).unwrap(), roomy, "{strategy}");
    }
}

/// Bad input is an error on every list layout, as on the CPU: K = 0 and a G-buffer of the
/// wrong size (also unculled), a sample behind the camera, a VPL with ξ outside (0, 1) and a
/// bound beyond f32 (r/α of a huge flux at δ near the smallest normal f32), each naming
/// the pixel or the VPL.
#[test]
fn list_cullers_reject_bad_input() {
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let (scene, camera) = default_scene();
    let (gbuffer, vpls) = frame(&scene, &camera, (16, 16), 4);
    let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (1, 0));
    let mut short = gbuffer.clone();
    short.samples.pop();
    let mut behind = gbuffer.clone();
    behind.samples[37].as_mut().unwrap().position = camera.position - camera.forward;
    let mut odd = vpls.clone();
    odd[3].xi = 1.5;
    let mut huge = vpls.clone();
    let glossy = huge.iter().position(|v| v.lobe == VplLobe::Glossy).unwrap();
    huge[glossy].flux = Vec3::splat(3e38);
    huge[glossy].brdf.alpha = 1e-3;
    let k0 = Interleaving { k: 0, seed: 0 };
    let of_any_input = [
        CullInput {
            interleaving: k0,
            ..input
        },
        CullInput {
            gbuffer: &short,
            ..input
        },
    ];
    let bounded = [
        Strategy::Sphere,
        Strategy::Ellipsoid,
        Strategy::ClusteredSphere,
        Strategy::Clustered,
        Strategy::Binned,
    ];
    for strategy in bounded.into_iter().chain([Strategy::None]) {
        for bad in &of_any_input {
            let e = culler.cull(&ctx, bad, strategy);
            assert!(matches!(e, Err(GpuError::Input(_))), "{strategy:?}: {e:?}");
        }
    }
    let named = format!("VPL {glossy}");
    let of_bounds = [
        (
            CullInput {
                gbuffer: &behind,
                ..input
            },
            "pixel (5, 2)",
        ),
        (
            CullInput {
                vpls: &odd,
                ..input
            },
            "VPL 3",
        ),
        (
            CullInput {
                vpls: &huge,
                delta: 1e-37,
                ..input
            },
            named.as_str(),
        ),
    ];
    for strategy in bounded {
        for (bad, names) in &of_bounds {
            assert!(
                slc_cull::culler(strategy).cull(bad).is_err(),
                "{strategy:?}"
            );
            let e = culler.cull(&ctx, bad, strategy).unwrap_err();
            assert!(e.to_string().contains(names), "{strategy:?}: {e}");
        }
    }
}
