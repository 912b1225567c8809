//! GPU bounds against the CPU's (`slc_cull`'s `vpl_bounds.rs`, rebuilt here from the public
//! `slc_bounds` API in f64 exactly as that file does, since its `VplBound` is crate-private).
//!
//! Tolerance: relative 1e-5 of the magnitude each quantity is computed from, because the GPU
//! works in f32 and the CPU partly in f64 (f32 rounding is 6e-8, so 1e-5 leaves a factor
//! ~100 for the few dozen operations):
//! - sphere radius: 1e-5 r;
//! - sphere centre: 1e-5 (|c| + r + |p| + |eye|) (c is formed from p − eye and offsets up to
//!   r, whose f32 rounding scales with those magnitudes);
//! - BS entries: 1e-5 max|BS| (the largest entry; B and S are f32 on both sides);
//! - BS·c: 1e-5 |BS|_F (|c| + |p| + |eye|) (a matrix-vector product's rounding).
//!
//! Each tolerance also takes how far the CPU's own quantity moves when ωi turns by
//! [`DIRECTION_TURN`] (four roundings) towards or away from the normal: a GPU whose `normalize`, division and
//! square root are not correctly rounded (WGSL allows 2.5 ulp; NVIDIA's differ from lavapipe's)
//! sees directions a few ulps from the CPU's, and near grazing incidence `G1/cos` changes by
//! `δcos/(cos + α)` relative (the radius by half that: 2e-5 apart on an H100 at cos 1e-5,
//! α 1e-3). Away from grazing incidence the spread is well below 1e-5.
use crate::common::gpu;
use glam::{DMat3, DVec3, Vec3};
use slc_bounds::{Anisotropy, Brdf, Fresnel, Sphere, Spheroid, StochasticParams, TestSpace};
use slc_core::frame::LobeSelection;
use slc_core::{builtin, Camera, Interleaving, Vpl, VplLobe};
use slc_cpu_ref::rsm::{trace_rsm, TexelSample};
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::Tracer;
use slc_cull::{CullView, GlossyBound};
use slc_gpu_wgpu::cull::bounds::{BoundsPass, BoundsSettings};
use slc_gpu_wgpu::cull::records::{GpuBound, BOUND_ELLIPSOID, BOUND_EMPTY, BOUND_SPHERE};
use slc_gpu_wgpu::GpuContext;

const SLACK: f64 = 1e-3;
const TOL: f64 = 1e-5;
/// The turn of ωi, in radians, over which the CPU's quantities are spread: four units of f32
/// rounding.
const DIRECTION_TURN: f32 = 4.0 * (f32::EPSILON / 2.0);
const GLOSSY: [GlossyBound; 3] = [
    GlossyBound::Sphere,
    GlossyBound::EnclosingSphere,
    GlossyBound::Ellipsoid,
];

#[derive(Debug)]
pub enum Reference {
    Empty,
    Sphere {
        center: DVec3,
        radius: f64,
    },
    Ellipsoid {
        bs: DMat3,
        center: DVec3,
        view_center: DVec3,
    },
}

/// `VplBound::new` of `crates/cull/src/vpl_bounds.rs`, step for step.
pub fn reference(vpl: &Vpl, delta: f32, view: &CullView, glossy: GlossyBound) -> Reference {
    let params = StochasticParams::new(delta, vpl.xi).unwrap();
    let q = view.relative(vpl.position);
    let sphere = |s: Sphere| {
        if s.is_empty() {
            return Reference::Empty;
        }
        Reference::Sphere {
            center: view.rotate(q + s.center.as_dvec3()),
            radius: f64::from(s.radius) * (1.0 + SLACK),
        }
    };
    match vpl.lobe {
        VplLobe::Diffuse => {
            if vpl.normal.dot(vpl.omega_i) <= 0.0 {
                return Reference::Empty;
            }
            let lobe = vpl.diffuse_lobe().unwrap();
            sphere(Sphere::diffuse(&lobe, &params).unwrap())
        }
        VplLobe::Glossy => {
            let lobe = vpl.glossy_lobe().unwrap();
            match glossy {
                GlossyBound::Sphere => sphere(Sphere::around_vpl(&lobe, &params).unwrap()),
                GlossyBound::EnclosingSphere => {
                    sphere(Sphere::enclosing(&Spheroid::new(&lobe, &params).unwrap()))
                }
                // The tight strategies cull with the spheroid before their box bound.
                GlossyBound::Ellipsoid | GlossyBound::Tight => {
                    let spheroid = Spheroid::new(&lobe, &params).unwrap();
                    if spheroid.is_empty() {
                        return Reference::Empty;
                    }
                    let semi = (spheroid.semi_axes().as_dvec3() * (1.0 + SLACK)).as_vec3();
                    let rotation = view.rotation() * spheroid.rotation();
                    let bs = TestSpace::new(rotation, semi, Vec3::ZERO)
                        .unwrap()
                        .matrix()
                        .as_dmat3();
                    let view_center = view.rotate(q + spheroid.center().as_dvec3());
                    Reference::Ellipsoid {
                        bs,
                        center: bs * view_center,
                        view_center,
                    }
                }
            }
        }
    }
}

/// `vpl` with ωi turned by `angle` in the plane of ωi and the normal (about any axis
/// normal to ωi at normal incidence).
fn turned(vpl: &Vpl, angle: f32) -> Vpl {
    let axis = vpl.normal.cross(vpl.omega_i);
    let axis = if axis.length_squared() > 1e-20 {
        axis.normalize()
    } else {
        vpl.omega_i.any_orthonormal_vector()
    };
    Vpl {
        omega_i: glam::Quat::from_axis_angle(axis, angle) * vpl.omega_i,
        ..*vpl
    }
}

/// How far each compared quantity (radius, sphere centre, BS, BS·c) moves from `a` to `b`
/// (0 where the two are not bounds of one kind).
fn spread(a: &Reference, b: &Reference) -> [f64; 4] {
    match (a, b) {
        (
            Reference::Sphere { center, radius },
            Reference::Sphere {
                center: c2,
                radius: r2,
            },
        ) => [(radius - r2).abs(), (*center - *c2).length(), 0.0, 0.0],
        (
            Reference::Ellipsoid { bs, center, .. },
            Reference::Ellipsoid {
                bs: bs2,
                center: c2,
                ..
            },
        ) => {
            let entries = (*bs - *bs2).to_cols_array();
            let worst = entries.iter().fold(0.0f64, |m, e| m.max(e.abs()));
            [0.0, 0.0, worst, (*center - *c2).length()]
        }
        _ => [0.0; 4],
    }
}

fn xyz(v: [f32; 4]) -> DVec3 {
    DVec3::new(v[0].into(), v[1].into(), v[2].into())
}

/// Compares every GPU bound with the CPU's; panics naming the VPL and quantity that differ.
fn compare(
    ctx: &GpuContext,
    pass: &BoundsPass,
    camera: &Camera,
    vpls: &[Vpl],
    delta: f32,
) -> [usize; 3] {
    let (w, h) = (64, 48);
    let view = CullView::new(camera, w, h).unwrap();
    let eye = camera.position.as_dvec3().length();
    let mut kinds = [0; 3];
    let interleaving = Interleaving { k: 4, seed: 77 };
    // Largest observed error over its tolerance scale, per quantity: radius, sphere centre,
    // BS, BS·c.
    let mut worst_seen = [0.0f64; 4];
    for glossy in GLOSSY {
        let settings = BoundsSettings {
            camera,
            width: w,
            height: h,
            delta,
            glossy,
            interleaving,
            shapes: false,
        };
        let gpu: Vec<GpuBound> = pass.compute(ctx, vpls, &settings).unwrap();
        assert_eq!(gpu.len(), vpls.len());
        for (i, (g, vpl)) in gpu.iter().zip(vpls).enumerate() {
            assert_eq!(g.index as usize, i);
            assert_eq!(g.subregion, interleaving.vpl_subregion(vpl.id), "VPL {i}");
            let at = format!("VPL {i} ({:?}, {glossy:?}, {vpl:?})", vpl.lobe);
            let p = vpl.position.as_dvec3().length();
            let exact = reference(vpl, delta, &view, glossy);
            let mut cond = [0.0f64; 4];
            for angle in [DIRECTION_TURN, -DIRECTION_TURN] {
                let moved = spread(
                    &exact,
                    &reference(&turned(vpl, angle), delta, &view, glossy),
                );
                cond = core::array::from_fn(|k| cond[k].max(moved[k]));
            }
            match exact {
                Reference::Empty => {
                    assert_eq!(
                        g.kind, BOUND_EMPTY,
                        "{at}: CPU bound empty, GPU kind {}",
                        g.kind
                    );
                    kinds[0] += 1;
                }
                Reference::Sphere { center, radius } => {
                    assert_eq!(
                        g.kind, BOUND_SPHERE,
                        "{at}: CPU sphere, GPU kind {}",
                        g.kind
                    );
                    let r = f64::from(g.center[3]).sqrt();
                    worst_seen[0] = worst_seen[0].max((r - radius).abs() / radius);
                    assert!(
                        (r - radius).abs() <= TOL * radius + cond[0],
                        "{at}: radius GPU {r} CPU {radius} (spread {})",
                        cond[0]
                    );
                    let d = (xyz(g.center) - center).length();
                    let scale = center.length() + radius + p + eye;
                    worst_seen[1] = worst_seen[1].max(d / scale);
                    assert!(
                        d <= TOL * scale + cond[1],
                        "{at}: centre GPU {:?} CPU {center} (|d| {d})",
                        g.center
                    );
                    kinds[1] += 1;
                }
                Reference::Ellipsoid {
                    bs,
                    center,
                    view_center,
                } => {
                    assert_eq!(
                        g.kind, BOUND_ELLIPSOID,
                        "{at}: CPU ellipsoid, GPU kind {}",
                        g.kind
                    );
                    let gbs = DMat3::from_cols(xyz(g.bs[0]), xyz(g.bs[1]), xyz(g.bs[2]));
                    let cols = |m: DMat3| [m.x_axis, m.y_axis, m.z_axis];
                    let largest = cols(bs)
                        .iter()
                        .map(|c| c.abs().max_element())
                        .fold(0.0, f64::max);
                    let worst = (0..3)
                        .map(|k| (cols(gbs)[k] - cols(bs)[k]).abs().max_element())
                        .fold(0.0, f64::max);
                    worst_seen[2] = worst_seen[2].max(worst / largest);
                    assert!(
                        worst <= TOL * largest + cond[2],
                        "{at}: BS GPU {gbs} CPU {bs} (worst {worst}, max {largest})"
                    );
                    let frob = cols(bs)
                        .iter()
                        .map(|c| c.length_squared())
                        .sum::<f64>()
                        .sqrt();
                    let d = (xyz(g.center) - center).length();
                    let scale = frob * (view_center.length() + p + eye);
                    worst_seen[3] = worst_seen[3].max(d / scale);
                    assert!(
                        d <= TOL * scale + cond[3],
                        "{at}: BS·c GPU {:?} CPU {center} (|d| {d}, scale {scale})",
                        g.center
                    );
                    kinds[2] += 1;
                }
            }
        }
    }
    eprintln!(
        "delta {delta}: {kinds:?} (empty, sphere, ellipsoid) bounds; worst relative error \
         radius {:.1e}, centre {:.1e}, BS {:.1e}, BS·c {:.1e}",
        worst_seen[0], worst_seen[1], worst_seen[2], worst_seen[3]
    );
    kinds
}

#[test]
fn bounds_of_the_default_scene_match_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let pass = BoundsPass::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let tracer = Tracer::new(&scene);
    let maps: Vec<_> = scene
        .lights
        .iter()
        .map(|l| trace_rsm(&scene, &tracer, l, 24, TexelSample::Centre))
        .collect();
    let vpls = generate_vpls(&maps, 11, LobeSelection::Both);
    assert!(vpls.len() > 500, "{} VPLs", vpls.len());
    for delta in [1e-3, 1e-1] {
        let kinds = compare(&ctx, &pass, &camera, &vpls, delta);
        assert!(kinds[1] > 0 && kinds[2] > 0, "{kinds:?}");
    }
}

/// Extreme VPLs: α 1e-3 and 1, grazing and normal incidence, zero flux, light from below,
/// dielectric Fresnel, tiny ξ and δ, far from the origin.
#[test]
fn bounds_of_extreme_vpls_match_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let pass = BoundsPass::new(&ctx).unwrap();
    let camera = Camera::look_at(
        Vec3::new(0.3, 1.2, 4.0),
        Vec3::new(0.0, 0.5, 0.0),
        Vec3::Y,
        0.9,
    )
    .unwrap();
    let mut vpls = Vec::new();
    let normals = [
        Vec3::Y,
        Vec3::X,
        Vec3::new(0.2, 0.9, -0.3).normalize(),
        Vec3::NEG_Z,
    ];
    let mut id = 0;
    for (ni, &n) in normals.iter().enumerate() {
        let t = n.any_orthonormal_vector();
        for cos in [1.0f32, 0.7, 0.1, 1e-3, 1e-5, 0.0, -0.2] {
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let wi = (cos * n + sin * t).normalize();
            for alpha in [1e-3f32, 0.05, 0.5, 1.0] {
                for flux in [Vec3::ZERO, Vec3::new(3.0, 0.5, 0.0), Vec3::splat(1e4)] {
                    for fresnel in [
                        Fresnel::Schlick(Vec3::new(0.9, 0.6, 0.04)),
                        Fresnel::Dielectric(1.5),
                    ] {
                        for lobe in [VplLobe::Diffuse, VplLobe::Glossy] {
                            let xi = [0.5, 3e-8, 0.999_999][id % 3];
                            vpls.push(Vpl {
                                position: Vec3::new(0.4 * ni as f32 - 0.5, 0.3, -0.2 * ni as f32),
                                normal: n,
                                geometric_normal: n,
                                omega_i: wi,
                                flux,
                                brdf: Brdf {
                                    kd: Vec3::new(0.7, 0.2, 0.0),
                                    fresnel,
                                    alpha,
                                    // Every fourth lobe anisotropic: the GPU's α = max(α, α_t)
                                    // and the CPU's bound factor.
                                    anisotropy: (id % 4 == 1).then(|| Anisotropy {
                                        tangent: n.cross(t).normalize(),
                                        alpha_t: [0.8, 2e-3, 0.1][id % 3],
                                    }),
                                },
                                lobe,
                                id: id as u32,
                                xi,
                            });
                            id += 1;
                        }
                    }
                }
            }
        }
    }
    let kinds = compare(&ctx, &pass, &camera, &vpls, 1e-3);
    assert!(kinds.iter().all(|&k| k > 0), "{kinds:?}");
    let kinds = compare(&ctx, &pass, &camera, &vpls, 1e-7);
    assert!(kinds.iter().all(|&k| k > 0), "{kinds:?}");
    // Far from the origin: f32 positions of magnitude 1e3 around a camera there.
    let far = Vec3::new(1000.0, 20.0, -500.0);
    let moved: Vec<Vpl> = vpls
        .iter()
        .map(|v| Vpl {
            position: v.position + far,
            ..*v
        })
        .collect();
    let cam = Camera {
        position: camera.position + far,
        ..camera
    };
    compare(&ctx, &pass, &cam, &moved, 1e-3);
}

/// Invalid VPLs are errors (as on the CPU), not NaN bounds.
#[test]
fn invalid_vpls_are_errors() {
    let Some(ctx) = gpu() else { return };
    let pass = BoundsPass::new(&ctx).unwrap();
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO, Vec3::Y, 0.9).unwrap();
    let good = Vpl {
        position: Vec3::ZERO,
        normal: Vec3::Y,
        geometric_normal: Vec3::Y,
        omega_i: Vec3::Y,
        flux: Vec3::ONE,
        brdf: Brdf {
            kd: Vec3::splat(0.5),
            fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
            alpha: 0.3,
            anisotropy: None,
        },
        lobe: VplLobe::Glossy,
        id: 0,
        xi: 0.5,
    };
    let settings = BoundsSettings {
        camera: &camera,
        width: 8,
        height: 8,
        delta: 1e-3,
        glossy: GlossyBound::Ellipsoid,
        interleaving: Interleaving { k: 1, seed: 0 },
        shapes: false,
    };
    let bad = [
        Vpl { xi: 0.0, ..good },
        Vpl {
            position: Vec3::NAN,
            ..good
        },
        Vpl {
            brdf: Brdf {
                alpha: 0.0,
                ..good.brdf
            },
            ..good
        },
        Vpl {
            flux: Vec3::NEG_ONE,
            ..good
        },
    ];
    for b in bad {
        assert!(pass.compute(&ctx, &[good, b], &settings).is_err(), "{b:?}");
    }
    assert!(pass
        .compute(
            &ctx,
            &[good],
            &BoundsSettings {
                delta: 0.0,
                ..settings
            }
        )
        .is_err());
    assert!(pass.compute(&ctx, &[], &settings).unwrap().is_empty());
}
