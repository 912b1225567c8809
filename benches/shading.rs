//! Brute-force shading without visibility: VPL-pixel evaluations per second, with the exact sum
//! and with the stochastic estimate of eq. (3), and VSGL-pixel evaluations per second (VSGL
//! eq. 2-5, eight VSGLs per vector where the CPU has AVX2) with both diffuse emissions.
mod common;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use slc_bounds::sg::MeanMap;
use slc_core::frame::DiffuseEmission;
use slc_core::{GBuffer, Scene};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::sampled_lights::{sample_vsgls, sigma2_floor};
use slc_cpu_ref::vpl_shading::shade_vpls;
use slc_cpu_ref::vsgl::{shade_vsgls, ImportanceMap, MipRsm};
use slc_cpu_ref::{Tracer, VplEstimator};
use std::hint::black_box;

/// The 128² G-buffer of `scene`'s camera, one sample at each pixel's centre.
fn gbuffer(scene: &Scene, tracer: &Tracer) -> GBuffer {
    trace_gbuffer(
        scene,
        tracer,
        &scene.camera_or_default(),
        128,
        128,
        PixelSample::Centre,
    )
}

/// The pixels of `gbuffer` with a surface.
fn covered(gbuffer: &GBuffer) -> u64 {
    gbuffer.samples.iter().filter(|s| s.is_some()).count() as u64
}

fn shading(c: &mut Criterion) {
    let (scene, tracer, vpls) = common::default_scene_vpls(16);
    let gbuffer = gbuffer(&scene, &tracer);
    let pairs = vpls.len() as u64 * covered(&gbuffer);
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

/// 1024 VSGLs sampled by flux from the default scene's 64² RSMs, shaded at 128² pixels.
fn vsgl_shading(c: &mut Criterion) {
    let (scene, tracer, maps) = common::default_scene_maps(64);
    let gbuffer = gbuffer(&scene, &tracer);
    let mips: Vec<MipRsm> = maps
        .iter()
        .map(|m| MipRsm::build(m, MeanMap::Toksvig).unwrap())
        .collect();
    let importance: Vec<ImportanceMap> = maps
        .iter()
        .map(|m| ImportanceMap::flux(m).unwrap())
        .collect();
    let floor = sigma2_floor(&tracer);
    let vsgls = sample_vsgls(&mips, &importance, 1024, 0, floor).unwrap();
    let pixels = covered(&gbuffer);
    let mut g = c.benchmark_group("vsgl_shading");
    g.sample_size(10);
    g.throughput(Throughput::Elements(vsgls.len() as u64 * pixels));
    for (name, diffuse) in [
        ("clamped_cosine", DiffuseEmission::ClampedCosine),
        ("sg", DiffuseEmission::Sg),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                black_box(shade_vsgls(&tracer, &gbuffer, &vsgls, diffuse, false, &|_| {}).unwrap())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, shading, vsgl_shading);
criterion_main!(benches);
