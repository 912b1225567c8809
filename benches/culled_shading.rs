//! Culling per strategy (pixels per second) and the stochastic shading of the ellipsoid's
//! light lists (listed pairs per second) on the built-in default scene: every listed pair
//! evaluated in full (no early exit); with the scalar early exits (`VplReach::may_reach`:
//! bound and signs, one pair at a time, then the shader's own roulette); with the eight-lane
//! early exits (`ReachChunks`: bound, signs and the roulette, eight VPLs at a time); with
//! the receivers in lanes (`ReceiverChunks`: each list's pixels, eight at a time, VPL by VPL,
//! the accepted pairs' ωo, l² and I(ωo) handed to the contribution where they are the
//! shader's); and the whole `shade_lists` (tile order, every thread).
mod common;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use slc_bounds::StochasticParams;
use slc_core::{CullInput, GSample, Interleaving, Strategy, NO_LIST};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::vpl_shading::{received, shade_lists, vpl_contribution};
use slc_cull::{culler, ReachChunks, ReceiverChunks, VplReach};
use std::hint::black_box;

fn culled_shading(c: &mut Criterion) {
    let (scene, tracer, vpls) = common::default_scene_vpls(32);
    let camera = scene.camera_or_default();
    let gbuffer = trace_gbuffer(&scene, &tracer, &camera, 256, 256, PixelSample::Centre);
    let input = CullInput {
        gbuffer: &gbuffer,
        camera: &camera,
        vpls: &vpls,
        delta: 1e-3,
        interleaving: Interleaving { k: 4, seed: 0 },
    };

    let mut g = c.benchmark_group("culling");
    g.sample_size(10);
    g.throughput(Throughput::Elements(gbuffer.samples.len() as u64));
    for s in [Strategy::Sphere, Strategy::Ellipsoid, Strategy::Clustered] {
        g.bench_function(s.name(), |b| {
            b.iter(|| black_box(culler(s).cull(&input).unwrap()))
        });
    }
    g.finish();

    let lists = culler(Strategy::Ellipsoid).cull(&input).unwrap();
    let roulette: Vec<_> = vpls
        .iter()
        .map(|v| StochasticParams::new(input.delta, v.xi).unwrap())
        .collect();
    let reach: Vec<_> = vpls
        .iter()
        .zip(&roulette)
        .map(|(v, r)| VplReach::new(v, r).unwrap())
        .collect();
    let groups = || {
        lists
            .offsets
            .windows(2)
            .map(|w| &lists.indices[w[0] as usize..w[1] as usize])
    };
    let chunks = ReachChunks::new(&vpls, &reach, groups());
    let pixels = || {
        gbuffer
            .samples
            .iter()
            .zip(&lists.pixel_list)
            .filter_map(|(s, &l)| Some((s.as_ref()?, l)).filter(|_| l != NO_LIST))
    };
    let pairs: usize = pixels()
        .map(|(_, l)| groups().nth(l as usize).unwrap().len())
        .sum();
    let listed = |l: u32| {
        &lists.indices[lists.offsets[l as usize] as usize..lists.offsets[l as usize + 1] as usize]
    };

    let mut g = c.benchmark_group("ellipsoid_list_shading");
    g.sample_size(10);
    g.throughput(Throughput::Elements(pairs as u64));
    g.bench_function("full_evaluation", |b| {
        b.iter(|| {
            let mut sum = Vec3::ZERO;
            for (s, l) in pixels() {
                for &k in listed(l) {
                    sum += vpl_contribution(s, &vpls[k as usize], Some(&roulette[k as usize]));
                }
            }
            black_box(sum)
        })
    });
    g.bench_function("scalar_exits", |b| {
        b.iter(|| {
            let mut sum = Vec3::ZERO;
            for (s, l) in pixels() {
                for &k in listed(l) {
                    let v = &vpls[k as usize];
                    if reach[k as usize].may_reach(s.position - v.position, s.normal) {
                        sum += vpl_contribution(s, v, Some(&roulette[k as usize]));
                    }
                }
            }
            black_box(sum)
        })
    });
    g.bench_function("eight_lane_exits", |b| {
        b.iter(|| {
            let mut sum = Vec3::ZERO;
            for (s, l) in pixels() {
                chunks.for_each_passing(l as usize, s.position, Some(s.normal), |k| {
                    sum += vpl_contribution(s, &vpls[k as usize], Some(&roulette[k as usize]));
                });
            }
            black_box(sum)
        })
    });
    // Each list's pixels as one group of receivers.
    let mut by_list: Vec<Vec<&GSample>> = vec![Vec::new(); lists.len()];
    for (s, l) in pixels() {
        by_list[l as usize].push(s);
    }
    let receivers: Vec<ReceiverChunks> = by_list
        .iter()
        .map(|px| {
            let mut r = ReceiverChunks::default();
            r.refill(px.iter().map(|s| (s.position, s.normal)));
            r
        })
        .collect();
    g.bench_function("receiver_lanes", |b| {
        let mut passing = Vec::new();
        b.iter(|| {
            let mut sum = Vec3::ZERO;
            for (l, (px, r)) in by_list.iter().zip(&receivers).enumerate() {
                r.passing(&reach, listed(l as u32), true, &mut passing);
                for chunk in &passing {
                    let k = chunk.vpl as usize;
                    let (v, roulette) = (&vpls[k], Some(&roulette[k]));
                    for lane in (0..8).filter(|&lane| chunk.bits & (1 << lane) != 0) {
                        let s = px[chunk.chunk * 8 + lane];
                        sum += match chunk.exact(lane) {
                            Some((omega, l2, i)) => received(s, omega, l2, || i, roulette),
                            None => vpl_contribution(s, v, roulette),
                        };
                    }
                }
            }
            black_box(sum)
        })
    });
    g.bench_function("shade_lists", |b| {
        b.iter(|| black_box(shade_lists(&tracer, &input, &lists, false, &|_| {}).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, culled_shading);
criterion_main!(benches);
