//! The imperfect shadow maps' own guarantees (`vsgl::ism`): the pull-push hole filling only
//! fills (every splatted texel keeps its depth, holes narrower than 2^levels texels close,
//! maps without points stay empty), and per-map point subsets give each map its own points.
use crate::common::gpu;
use glam::Vec3;
use slc_core::builtin;
use slc_gpu_wgpu::vsgl::ism::{caster_points, IsmPass, IsmSettings};
use slc_gpu_wgpu::GpuContext;

/// The maps about `centres` of the default scene's caster points under `settings`.
fn maps(ctx: &GpuContext, settings: &IsmSettings, centres: &[Vec3]) -> Vec<f32> {
    let scene = builtin("default").unwrap();
    let casters = caster_points(&scene, settings);
    IsmPass::new(ctx)
        .unwrap()
        .render(ctx, &casters, centres, settings)
        .unwrap()
        .read_back(ctx)
        .unwrap()
}

/// One-texel points (no discs), few of them: the maps have holes to fill.
fn sparse() -> IsmSettings {
    IsmSettings {
        points: 2048,
        points_per_map: 2048,
        max_splat: 0,
        ..IsmSettings::paper(1e-4)
    }
}

#[test]
fn pull_push_only_fills_holes() {
    let Some(ctx) = gpu() else { return };
    let centres = [Vec3::new(0.1, 0.2, 0.3), Vec3::new(-0.3, 0.1, 0.0)];
    let plain = maps(&ctx, &sparse(), &centres);
    let empty = |m: &[f32]| m.iter().filter(|d| d.is_infinite()).count();
    let mut previous = empty(&plain);
    assert!(
        previous > plain.len() / 4,
        "{previous} of {} empty",
        plain.len()
    );
    for fill_levels in 1..=3 {
        let filled = maps(
            &ctx,
            &IsmSettings {
                fill_levels,
                ..sparse()
            },
            &centres,
        );
        for (a, b) in plain.iter().zip(&filled) {
            assert!(
                a.is_infinite() || a == b,
                "a splatted depth changed: {a} -> {b}"
            );
            assert!(b.is_infinite() || (*b > 0.0 && b.is_finite()));
        }
        let now = empty(&filled);
        println!(
            "fill levels {fill_levels}: {now} of {} texels empty",
            filled.len()
        );
        assert!(now < previous, "level {fill_levels} fills nothing more");
        previous = now;
    }
    // No points at all: nothing to fill from.
    let none = IsmPass::new(&ctx)
        .unwrap()
        .render(
            &ctx,
            &[],
            &centres,
            &IsmSettings {
                fill_levels: 3,
                ..sparse()
            },
        )
        .unwrap()
        .read_back(&ctx)
        .unwrap();
    assert!(none.iter().all(|d| d.is_infinite()));
}

#[test]
fn each_map_draws_its_own_points() {
    let Some(ctx) = gpu() else { return };
    let centre = Vec3::new(0.1, 0.2, 0.3);
    let texels = (sparse().resolution as usize).pow(2);
    let shared = maps(&ctx, &sparse(), &[centre, centre]);
    assert_eq!(shared[..texels], shared[texels..]);
    let subsets = IsmSettings {
        points: 16384,
        ..sparse()
    };
    let own = maps(&ctx, &subsets, &[centre, centre]);
    let differ = own[..texels]
        .iter()
        .zip(&own[texels..])
        .filter(|(a, b)| a != b)
        .count();
    assert!(differ > texels / 10, "{differ} of {texels} texels differ");
}

/// A disc's splat walks (2k + 1)² texels: on Mesa's llvmpipe, which ends a shader
/// invocation's loops after 65,535 iterations in all, a `max_splat` of 128 or more is refused
/// by name (127 is drawn); other adapters draw both.
#[test]
fn splats_beyond_the_adapters_loop_budget_are_refused() {
    use slc_gpu_wgpu::GpuError;
    let Some(ctx) = gpu() else { return };
    let scene = builtin("default").unwrap();
    let drawn = |max_splat: u32| {
        let settings = IsmSettings {
            max_splat,
            ..sparse()
        };
        let casters = caster_points(&scene, &settings);
        IsmPass::new(&ctx)
            .unwrap()
            .render(&ctx, &casters, &[Vec3::ZERO], &settings)
            .map(|_| ())
    };
    assert!(drawn(127).is_ok());
    match (drawn(128), ctx.loop_budget) {
        (Err(e @ GpuError::LoopBudget { .. }), Some(_)) => {
            assert!(e.to_string().contains("max_splat"), "{e}");
        }
        (Ok(()), None) => {}
        (got, budget) => panic!("with a loop budget {budget:?}: {got:?}"),
    }
}
