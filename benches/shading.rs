//! Brute-force VPL shading: VPL-pixel evaluations per second, with the exact sum and with the
//! stochastic estimate of eq. (3), without visibility.
mod common;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::vpl_shading::shade_vpls;
use slc_cpu_ref::VplEstimator;
use std::hint::black_box;

fn shading(c: &mut Criterion) {
    let (scene, tracer, vpls) = common::default_scene_vpls(16);
    let gbuffer = trace_gbuffer(
        &scene,
        &tracer,
        &scene.camera_or_default(),
        128,
        128,
        PixelSample::Centre,
    );
    let pairs = vpls.len() as u64 * gbuffer.samples.iter().filter(|s| s.is_some()).count() as u64;
    let mut g = c.benchmark_group("vpl_shading");
    g.sample_size(10);
    g.throughput(Throughput::Elements(pairs));
    for (name, estimator) in [
        ("exact", VplEstimator::Exact),
        (
            "stochastic_delta_1e-3",
            VplEstimator::Stochastic { delta: 1e-3 },
        ),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                black_box(shade_vpls(&tracer, &gbuffer, &vpls, estimator, false, &|_| {}).unwrap())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, shading);
criterion_main!(benches);
