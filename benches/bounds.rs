//! Bound generation per VPL: the GGX spheroid (eq. 12-15) with its test space (eq. 16-17),
//! the diffuse sphere (section 6) and the two baseline spheres (section 7).
mod common;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Affine3A;
use slc_bounds::{DiffuseLobe, GlossyLobe, Sphere, Spheroid, StochasticParams, TestSpace};
use slc_core::{Vpl, VplLobe};
use std::hint::black_box;

/// A glossy VPL's lobe, its (δ, ξ) and its spheroid (eq. 12-15).
fn glossy_bound(v: &Vpl, delta: f32) -> (GlossyLobe, StochasticParams, Spheroid) {
    let lobe = GlossyLobe::new(
        v.position,
        v.normal,
        v.omega_i,
        v.brdf.alpha,
        v.flux,
        v.brdf.fresnel,
    )
    .unwrap();
    let params = StochasticParams::new(delta, v.xi).unwrap();
    let spheroid = Spheroid::new(&lobe, &params).unwrap();
    (lobe, params, spheroid)
}

fn bounds(c: &mut Criterion) {
    let (_, _, vpls) = common::default_scene_vpls(64);
    let delta = 1e-3;
    let glossy: Vec<_> = vpls.iter().filter(|v| v.lobe == VplLobe::Glossy).collect();
    let diffuse: Vec<_> = vpls.iter().filter(|v| v.lobe == VplLobe::Diffuse).collect();
    let view = Affine3A::from_translation(glam::Vec3::new(0.0, -1.0, -3.4));
    let mut g = c.benchmark_group("bound_generation");
    g.throughput(Throughput::Elements(glossy.len() as u64));
    g.bench_function("spheroid_and_test_space", |b| {
        b.iter(|| {
            for v in &glossy {
                let (_, _, s) = glossy_bound(v, delta);
                black_box(TestSpace::from_spheroid(&s, view).unwrap());
            }
        })
    });
    g.bench_function("baseline_spheres", |b| {
        b.iter(|| {
            for v in &glossy {
                let (lobe, params, s) = glossy_bound(v, delta);
                black_box((
                    Sphere::around_vpl(&lobe, &params).unwrap(),
                    Sphere::enclosing(&s),
                ));
            }
        })
    });
    g.throughput(Throughput::Elements(diffuse.len() as u64));
    g.bench_function("diffuse_sphere", |b| {
        b.iter(|| {
            for v in &diffuse {
                let lobe = DiffuseLobe::new(v.position, v.normal, v.flux, v.brdf.kd).unwrap();
                let params = StochasticParams::new(delta, v.xi).unwrap();
                black_box(Sphere::diffuse(&lobe, &params).unwrap());
            }
        })
    });
    g.finish();
}

criterion_group!(benches, bounds);
criterion_main!(benches);
