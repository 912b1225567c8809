//! Tests of the mipmapped RSM and the VSGL parameters against independent computations.
use super::*;
use crate::rsm::{trace_rsm, Rsm, RsmTexel, TexelSample};
use crate::Tracer;
use core::f64::consts::PI;
use glam::{DVec3, Vec3};
use slc_bounds::sg::{exact_mean_length, ggx_mixture, sg_integral, MeanMap};
use slc_bounds::{Brdf, Fresnel};

const FLOOR: f32 = 1e-6;

fn default_rsms(resolution: u32) -> Vec<Rsm> {
    let scene = slc_core::builtin("default").unwrap();
    let tracer = Tracer::new(&scene);
    scene
        .lights
        .iter()
        .map(|l| trace_rsm(&scene, &tracer, l, resolution, TexelSample::Centre))
        .collect()
}

/// `∫_{S²} f(ω) dω` in polar coordinates about `axis`, `θ = π u²` (dense near the axis).
fn sphere_integral(axis: Vec3, f: impl Fn(Vec3) -> f64) -> f64 {
    let (nu, nphi) = (1500, 400);
    let (t, b) = axis.any_orthonormal_pair();
    let mut sum = 0.0;
    for i in 0..nu {
        let u = (i as f64 + 0.5) / nu as f64;
        let theta = PI * u * u;
        let jac = theta.sin() * 2.0 * PI * u / nu as f64 * (2.0 * PI / nphi as f64);
        for j in 0..nphi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / nphi as f64;
            let d = theta.sin() * (phi.cos() * t.as_dvec3() + phi.sin() * b.as_dvec3())
                + theta.cos() * axis.as_dvec3();
            sum += f(d.as_vec3().normalize()) * jac;
        }
    }
    sum
}

/// The VSGL of the level-0 texels `[x0, x1) × [y0, y1)` of `face`, straight from VSGL section
/// 3.1 (no `ClusterSums`, no `ToksvigSum`).
fn direct_vsgl(rsm: &Rsm, face: u32, x: [u32; 2], y: [u32; 2], map: MeanMap) -> Vsgl {
    let n = rsm.resolution;
    let (mut wd, mut ws, mut md, mut ms) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    let (mut normals, mut specular_normals) = (DVec3::ZERO, DVec3::ZERO);
    let (mut w, mut wx, mut wxx) = (0.0, DVec3::ZERO, 0.0);
    for row in y[0]..y[1].min(n) {
        for col in x[0]..x[1].min(n) {
            let Some(t) = &rsm.texels[((face * n + row) * n + col) as usize] else {
                continue;
            };
            let l = TexelLobes::new(t).unwrap();
            let (d, s) = (
                (t.flux * l.diffuse_reflectance).as_dvec3(),
                (t.flux * l.specular_reflectance).as_dvec3(),
            );
            wd += d;
            ws += s;
            let mean = |sg: slc_bounds::SphericalGaussian| {
                sg.axis.as_dvec3() * f64::from(map.length(sg.sharpness))
            };
            md += d.element_sum() * mean(l.diffuse_lobe);
            normals += d.element_sum() * t.normal.as_dvec3();
            ms += s.element_sum() * mean(l.specular_lobe);
            specular_normals += s.element_sum() * t.normal.as_dvec3();
            let wi = (d + s).element_sum();
            let p = t.position.as_dvec3();
            // The patch of a texel of cross-section a² at incidence c: (a² + a²/c²)/12.
            let c = f64::from(t.geometric_normal.dot(t.omega_i).abs()).max(0.01);
            let patch = f64::from(t.cross_section) * (1.0 + 1.0 / (c * c)) / 12.0;
            w += wi;
            wx += wi * p;
            wxx += wi * (p.length_squared() + patch);
        }
    }
    let lobe = |m: DVec3, rgb: DVec3| {
        let m = if rgb.element_sum() > 0.0 {
            m / rgb.element_sum()
        } else {
            m
        };
        let r = m.length();
        let lambda = map.sharpness(r as f32);
        let axis = if r > 0.0 { (m / r).as_vec3() } else { Vec3::Z };
        (axis, lambda, rgb.as_vec3() / sg_integral(lambda))
    };
    let (xi_diffuse, lambda_diffuse, c_diffuse) = lobe(md, wd);
    let (xi_specular, lambda_specular, c_specular) = lobe(ms, ws);
    let mu = if w > 0.0 { wx / w } else { DVec3::ZERO };
    let sigma2 = if w > 0.0 {
        wxx / w - mu.length_squared()
    } else {
        0.0
    };
    let mean_normal = if wd.element_sum() > 0.0 {
        (normals / wd.element_sum()).length() as f32
    } else {
        0.0
    };
    Vsgl {
        c_diffuse,
        xi_diffuse,
        lambda_diffuse,
        normal_concentration: slc_bounds::sg::exact_sharpness(mean_normal),
        c_specular,
        xi_specular,
        lambda_specular,
        specular_normal: specular_normals.normalize_or_zero().as_vec3(),
        mu: mu.as_vec3(),
        sigma2: (sigma2 as f32).max(FLOOR),
        weight: w as f32,
    }
}

fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()) + abs
}

fn close3(a: Vec3, b: Vec3, rel: f32, abs: f32) -> bool {
    (a - b).abs().max_element() <= rel * a.abs().max(b.abs()).max_element() + abs
}

fn assert_vsgl_eq(a: &Vsgl, b: &Vsgl, scale: f32, what: &str) {
    let ok = close3(a.c_diffuse, b.c_diffuse, 1e-4, 1e-9)
        && close3(a.c_specular, b.c_specular, 1e-4, 1e-9)
        && close(a.lambda_diffuse, b.lambda_diffuse, 1e-3, 1e-5)
        && close(a.lambda_specular, b.lambda_specular, 1e-3, 1e-5)
        && (a.lambda_diffuse < 1e-3 || close3(a.xi_diffuse, b.xi_diffuse, 0.0, 1e-4))
        && (a.lambda_specular < 1e-3 || close3(a.xi_specular, b.xi_specular, 0.0, 1e-4))
        && close3(a.mu, b.mu, 0.0, 1e-5 * scale)
        && close(a.sigma2, b.sigma2, 1e-3, 1e-6 * scale * scale)
        && close(a.weight, b.weight, 1e-5, 1e-9)
        && close(
            exact_mean_length(a.normal_concentration),
            exact_mean_length(b.normal_concentration),
            0.0,
            1e-5,
        );
    assert!(ok, "{what}: mip {a:?} != direct {b:?}");
}

#[test]
fn mip_texels_equal_the_vsgl_of_the_texels_they_cover() {
    // (a) Every texel of every level and face, for a power-of-two and an odd-sized RSM, and
    // both mean-vector maps.
    for (resolution, map) in [
        (8, MeanMap::Toksvig),
        (6, MeanMap::Toksvig),
        (5, MeanMap::Exact),
    ] {
        for rsm in default_rsms(resolution) {
            let mip = MipRsm::build(&rsm, map).unwrap();
            assert_eq!(mip.map(), map);
            assert_eq!(mip.resolution(), resolution);
            assert_eq!(mip.size(mip.levels() - 1), 1);
            let scale = rsm
                .texels
                .iter()
                .flatten()
                .map(|t| t.position.length())
                .fold(1.0, f32::max);
            for face in 0..mip.faces() {
                for level in 0..mip.levels() {
                    let size = mip.size(level);
                    for y in 0..size {
                        for x in 0..size {
                            let s = 1 << level;
                            let direct = direct_vsgl(
                                &rsm,
                                face,
                                [x * s, x * s + s],
                                [y * s, y * s + s],
                                map,
                            );
                            let vsgl = mip.vsgl(face, level, x, y, FLOOR).unwrap();
                            let what =
                                format!("N={resolution} face {face} level {level} ({x},{y})");
                            assert_vsgl_eq(&vsgl, &direct, scale, &what);
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn a_single_texel_is_its_vpl() {
    // (b) Level 0: μ is the position, σ² the variance of its patch (or the floor), c·A(λ) the
    // texel's RGB weights.
    let rsm = &default_rsms(8)[0];
    let mip = MipRsm::build(rsm, MeanMap::Toksvig).unwrap();
    let mut lit = 0;
    for (k, texel) in rsm.texels.iter().enumerate() {
        let Some(t) = texel else { continue };
        let k = k as u32;
        let (face, y, x) = (k / 64, (k / 8) % 8, k % 8);
        let v = mip.vsgl(face, 0, x, y, FLOOR).unwrap();
        let l = TexelLobes::new(t).unwrap();
        if v.weight == 0.0 {
            continue;
        }
        lit += 1;
        assert!(close3(v.mu, t.position, 1e-6, 1e-6), "{v:?} {t:?}");
        let patch = footprint_variance(t) as f32;
        assert!(
            patch > 0.0 && close(v.sigma2, patch.max(FLOOR), 1e-3, 0.0),
            "{v:?}"
        );
        let cd = v.c_diffuse * sg_integral(v.lambda_diffuse);
        let cs = v.c_specular * sg_integral(v.lambda_specular);
        assert!(
            close3(cd, t.flux * l.diffuse_reflectance, 1e-4, 1e-9),
            "{cd} {t:?}"
        );
        assert!(
            close3(cs, t.flux * l.specular_reflectance, 1e-4, 1e-9),
            "{cs} {t:?}"
        );
        // One lobe back-converts to itself (the Toksvig map and its inverse round-trip).
        if l.diffuse_reflectance.max_element() > 0.0 {
            assert!(close(v.lambda_diffuse, l.diffuse_lobe.sharpness, 1e-3, 0.0));
            assert!(close3(v.xi_diffuse, t.normal, 0.0, 1e-4));
        }
        if l.specular_reflectance.max_element() > 0.0 {
            assert!(close(
                v.lambda_specular,
                l.specular_lobe.sharpness,
                1e-3,
                0.0
            ));
            assert!(close3(v.xi_specular, l.specular_lobe.axis, 0.0, 1e-4));
        }
        let [ed, es] = v.emitted_coefficients();
        let k = 1.0 / (2.0 * core::f32::consts::PI * v.sigma2);
        assert!(close3(ed, v.c_diffuse * k, 1e-6, 0.0) && close3(es, v.c_specular * k, 1e-6, 0.0));
    }
    assert!(lit > 10, "{lit} lit texels");
}

fn plane_texel(position: Vec3, flux: f32) -> RsmTexel {
    RsmTexel {
        position,
        normal: Vec3::Z,
        geometric_normal: Vec3::Z,
        normal_mapped: false,
        omega_i: Vec3::new(0.3, 0.0, 1.0).normalize(),
        flux: Vec3::splat(flux),
        cross_section: 0.0,
        brdf: Brdf {
            kd: Vec3::new(0.5, 0.4, 0.3),
            fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
            alpha: 0.3,
            anisotropy: None,
        },
    }
}

#[test]
fn plane_clusters_have_the_closed_form_mean_and_variance() {
    // (c) A 4×4 grid x = (i, j, 2) of equal texels: μ = (1.5, 1.5, 2), σ² = 2 · 1.25 (the
    // variance of {0, 1, 2, 3} per axis); the 2×2 quadrant at (1, 0) has μ = (2.5, 0.5, 2),
    // σ² = 2 · 0.25.
    let texels = (0..16)
        .map(|k| {
            Some(plane_texel(
                Vec3::new((k % 4) as f32, (k / 4) as f32, 2.0),
                1.0,
            ))
        })
        .collect();
    let rsm = Rsm {
        resolution: 4,
        faces: 1,
        texels,
    };
    let mip = MipRsm::build(&rsm, MeanMap::Toksvig).unwrap();
    let top = mip.vsgl(0, 2, 0, 0, 0.0).unwrap();
    assert!(
        close3(top.mu, Vec3::new(1.5, 1.5, 2.0), 0.0, 1e-5),
        "{top:?}"
    );
    assert!(close(top.sigma2, 2.5, 1e-5, 0.0), "{top:?}");
    let quadrant = mip.vsgl(0, 1, 1, 0, 0.0).unwrap();
    assert!(
        close3(quadrant.mu, Vec3::new(2.5, 0.5, 2.0), 0.0, 1e-5),
        "{quadrant:?}"
    );
    assert!(close(quadrant.sigma2, 0.5, 1e-5, 0.0), "{quadrant:?}");
    // Equal normals: the filtered diffuse lobe is the texels' lobe.
    let one = TexelLobes::new(&rsm.texels[0].unwrap()).unwrap();
    assert!(close(
        top.lambda_diffuse,
        one.diffuse_lobe.sharpness,
        1e-4,
        0.0
    ));

    // Two lit texels of fluxes 1 and 3, 3 apart, among empty ones: μ at 3/4 of the way,
    // σ² = w1 w2 d² / (w1 + w2)² = 3 · 9 / 16.
    let mut texels = vec![None; 16];
    texels[0] = Some(plane_texel(Vec3::new(1.0, 1.0, 0.0), 1.0));
    texels[15] = Some(plane_texel(Vec3::new(4.0, 1.0, 0.0), 3.0));
    let top = top_vsgl(texels, 0.0);
    assert!(
        close3(top.mu, Vec3::new(3.25, 1.0, 0.0), 0.0, 1e-5),
        "{top:?}"
    );
    assert!(close(top.sigma2, 27.0 / 16.0, 1e-5, 0.0), "{top:?}");
    let l = TexelLobes::new(&rsm.texels[0].unwrap()).unwrap();
    let w = 4.0 * (l.diffuse_reflectance + l.specular_reflectance).element_sum();
    assert!(close(top.weight, w, 1e-5, 0.0), "{} {w}", top.weight);
}

#[test]
fn the_top_level_conserves_energy() {
    // (d) The 1×1 level of every face holds the whole face: its RGB weights are the sums of
    // Φ R over the texels, and c·A(λ) keeps them.
    for resolution in [8, 7] {
        for rsm in default_rsms(resolution) {
            let mip = MipRsm::build(&rsm, MeanMap::Toksvig).unwrap();
            let n = resolution * resolution;
            for face in 0..rsm.faces {
                let (mut d, mut s) = (Vec3::ZERO, Vec3::ZERO);
                for t in rsm.texels[(face * n) as usize..((face + 1) * n) as usize]
                    .iter()
                    .flatten()
                {
                    let l = TexelLobes::new(t).unwrap();
                    d += t.flux * l.diffuse_reflectance;
                    s += t.flux * l.specular_reflectance;
                }
                let v = mip.vsgl(face, mip.levels() - 1, 0, 0, FLOOR).unwrap();
                assert!(close(v.weight, (d + s).element_sum(), 1e-5, 1e-9), "{v:?}");
                let cd = v.c_diffuse * sg_integral(v.lambda_diffuse);
                let cs = v.c_specular * sg_integral(v.lambda_specular);
                assert!(
                    close3(cd, d, 1e-4, 1e-9) && close3(cs, s, 1e-4, 1e-9),
                    "{v:?}"
                );
            }
        }
    }
}

#[test]
fn the_diffuse_lobe_integrates_like_the_true_intensity() {
    // (d) ∫ Φ kd/π max(ω·n, 0) dω = Φ kd, and R_d G/A integrates to the same by construction;
    // the pointwise L1 error of the shape is the cosine fit's (measured: 27 %, much of it the SG's tail below the horizon).
    let t = plane_texel(Vec3::ZERO, 2.0);
    let rsm = Rsm {
        resolution: 1,
        faces: 1,
        texels: vec![Some(t)],
    };
    let v = MipRsm::build(&rsm, MeanMap::Toksvig)
        .unwrap()
        .vsgl(0, 0, 0, 0, FLOOR)
        .unwrap();
    let exact = |w: Vec3| f64::from(t.flux.x * t.brdf.kd.x) / PI * f64::from(w.z.max(0.0));
    let lobe =
        slc_bounds::SphericalGaussian::new(v.xi_diffuse, v.lambda_diffuse, v.c_diffuse.x).unwrap();
    let sg = |w: Vec3| f64::from(lobe.eval(w));
    assert!(v.intensity(Vec3::Z).x >= lobe.eval(Vec3::Z));
    let truth = sphere_integral(Vec3::Z, exact);
    let approx = sphere_integral(Vec3::Z, sg);
    let l1 = sphere_integral(Vec3::Z, |w| (exact(w) - sg(w)).abs()) / truth;
    let target = f64::from(t.flux.x * t.brdf.kd.x);
    println!("diffuse: truth {truth} SG {approx} (Φkd {target}), relative L1 shape error {l1}");
    assert!((truth - target).abs() < 1e-4 * target);
    assert!((approx - target).abs() < 1e-4 * target);
    assert!(l1 < 0.3, "{l1}");
}

#[test]
fn the_specular_lobe_approximates_the_true_intensity() {
    // (e) One glossy texel: R_s (the SG's integral) against ∫ f_s(ω_i, ω) ⟨ω, n⟩ dω by
    // quadrature, and the relative L1 error of the lobe. Measured errors are printed (`--nocapture`);
    // the bounds here are loose caps on them.
    for alpha in [0.1f32, 0.3, 0.6] {
        for theta in [0.0f32, 45.0, 70.0] {
            let (s, c) = theta.to_radians().sin_cos();
            let mut t = plane_texel(Vec3::ZERO, 1.0);
            t.omega_i = Vec3::new(s, 0.0, c);
            t.brdf.kd = Vec3::ZERO;
            t.brdf.alpha = alpha;
            let l = TexelLobes::new(&t).unwrap();
            let exact =
                |w: Vec3| f64::from(t.brdf.specular(t.normal, t.omega_i, w).x * w.z.max(0.0));
            let sg = |w: Vec3| f64::from(l.specular_reflectance.x * l.specular_lobe.eval(w));
            let mixture: Vec<slc_bounds::SphericalGaussian> =
                ggx_mixture(&l.specular_lobe).collect();
            let mixed = |w: Vec3| {
                let sum: f32 = mixture.iter().map(|g| g.eval(w)).sum();
                f64::from(l.specular_reflectance.x * sum)
            };
            let axis = l.specular_lobe.axis;
            let truth = sphere_integral(axis, exact);
            let approx = sphere_integral(axis, sg);
            let l1 = sphere_integral(axis, |w| (exact(w) - sg(w)).abs()) / truth;
            let l1_mixture = sphere_integral(axis, |w| (exact(w) - mixed(w)).abs()) / truth;
            let err = approx / truth - 1.0;
            println!("specular α {alpha} θi {theta}: truth {truth:.5} R_s {approx:.5} ({:+.1} %), L1 {:.1} %, with the mixture {:.1} %", 100.0 * err, 100.0 * l1, 100.0 * l1_mixture);
            assert!((f64::from(l.specular_reflectance.x) - approx).abs() < 1e-3 * approx);
            // Measured: R_s within 0.8 % of the truth (the warped SG it replaced: up to +83 %),
            // L1 21-66 % (an isotropic SG against GGX's heavy tails and, at grazing
            // incidence, its stretched lobe).
            assert!(err.abs() < 0.015 && l1 < 0.7, "{err} {l1}");
            assert!(l1_mixture <= l1, "{l1_mixture} {l1}");
        }
    }
}

#[test]
fn flux_importance_is_the_mip_weight() {
    // The paper's p(s) ∝ Φ (R_d + R_s) computed from the RSM equals the mip's positional
    // weights, at every level.
    for rsm in default_rsms(6) {
        let mip = MipRsm::build(&rsm, MeanMap::Toksvig).unwrap();
        let from_rsm = ImportanceMap::flux(&rsm).unwrap();
        assert_eq!(from_rsm, ImportanceMap::from_mip(&mip));
        for face in 0..mip.faces() {
            for level in 0..mip.levels() {
                let size = mip.size(level);
                for y in 0..size {
                    for x in 0..size {
                        let w = mip.sums(face, level, x, y).weight();
                        let m = from_rsm.mass(face, level, x, y);
                        assert!((w - m).abs() <= 1e-12 * w.max(1.0), "{w} {m}");
                    }
                }
            }
        }
    }
}

#[test]
fn texel_patches_add_their_variance() {
    // A texel of cross-section 1.2 met at cos 0.5 stands for a 1.095 × 2.191 rectangle:
    // variance 1.2 (1 + 4)/12 = 0.5. Two such texels 3 apart with weights 1 and 3 have
    // σ² = 27/16 (their centres) + 0.5 (their patches), the law of total variance.
    let mut a = plane_texel(Vec3::new(1.0, 1.0, 0.0), 1.0);
    a.cross_section = 1.2;
    a.omega_i = Vec3::new(0.75f32.sqrt(), 0.0, 0.5);
    assert!((footprint_variance(&a) - 0.5).abs() < 1e-6);
    let mut b = a;
    b.position = Vec3::new(4.0, 1.0, 0.0);
    b.flux = Vec3::splat(3.0);
    let mut texels = vec![None; 4];
    texels[0] = Some(a);
    texels[3] = Some(b);
    let rsm = Rsm {
        resolution: 2,
        faces: 1,
        texels,
    };
    let mip = MipRsm::build(&rsm, MeanMap::Toksvig).unwrap();
    assert!(close(
        mip.vsgl(0, 0, 0, 0, 0.0).unwrap().sigma2,
        0.5,
        1e-5,
        0.0
    ));
    let top = mip.vsgl(0, 1, 0, 0, 0.0).unwrap();
    assert!(close(top.sigma2, 27.0 / 16.0 + 0.5, 1e-5, 0.0), "{top:?}");
    // At grazing incidence the stretch is capped at 100.
    a.omega_i = Vec3::X;
    assert!((footprint_variance(&a) - 1.2 * (1.0 + 1e4) / 12.0).abs() < 1e-3);
}

#[test]
fn the_normal_concentration_matches_the_mean_normal() {
    // Coplanar texels: κ at its cap. Two equal texels with normals 90° apart: the mean normal
    // has length cos 45°, and κ is the vMF sharpness with that mean length.
    let flat = Rsm {
        resolution: 2,
        faces: 1,
        texels: vec![Some(plane_texel(Vec3::ZERO, 1.0)); 4],
    };
    let v = MipRsm::build(&flat, MeanMap::Toksvig)
        .unwrap()
        .vsgl(0, 1, 0, 0, FLOOR)
        .unwrap();
    assert!(v.normal_concentration > 1e6, "{v:?}");
    for map in [MeanMap::Toksvig, MeanMap::Exact] {
        let mut a = plane_texel(Vec3::ZERO, 1.0);
        a.omega_i = Vec3::new(1.0, 0.0, 1.0).normalize();
        let mut b = a;
        a.normal = Vec3::Z;
        b.normal = Vec3::X;
        let rsm = Rsm {
            resolution: 2,
            faces: 1,
            texels: vec![Some(a), Some(b), None, None],
        };
        let v = MipRsm::build(&rsm, map)
            .unwrap()
            .vsgl(0, 1, 0, 0, FLOOR)
            .unwrap();
        let mean = slc_bounds::sg::exact_mean_length(v.normal_concentration);
        assert!((mean - 0.5f32.sqrt()).abs() < 1e-4, "{map:?}: {v:?} {mean}");
        assert!(close3(
            v.xi_diffuse,
            Vec3::new(1.0, 0.0, 1.0).normalize(),
            0.0,
            1e-5
        ));
    }
}

#[test]
fn the_stretch_follows_the_true_lobe() {
    // (e) One glossy texel's VSGL: the L1 error of its specular intensity (the mixture of
    // GGX's profile) against the true lobe, with the stretch of the plane of incidence and
    // without (an unknown normal). Measured (`--nocapture`), isotropic → stretched:
    // α 0.08 at 45° 23.9 → 6.9 %, at 70° 63.0 → 22.5 %; α 0.4 at 70° 54.8 → 47.7 %.
    for alpha in [0.08f32, 0.2, 0.3, 0.4] {
        let mut line = format!("α {alpha}:");
        for theta in [0.0f32, 22.5, 45.0, 60.0, 70.0, 80.0] {
            let (s, c) = theta.to_radians().sin_cos();
            let mut t = plane_texel(Vec3::ZERO, 1.0);
            t.omega_i = Vec3::new(s, 0.0, c);
            t.brdf.kd = Vec3::ZERO;
            t.brdf.alpha = alpha;
            let sums = super::sums::ClusterSums::from_texel(&t, MeanMap::Toksvig).unwrap();
            let v = Vsgl::from_sums(&sums, FLOOR).unwrap();
            let isotropic = Vsgl {
                specular_normal: Vec3::ZERO,
                ..v
            };
            assert_eq!(v.specular_normal, Vec3::Z);
            let exact =
                |w: Vec3| f64::from(t.brdf.specular(t.normal, t.omega_i, w).x * w.z.max(0.0));
            let truth = sphere_integral(v.xi_specular, exact);
            let l1 = |v: &Vsgl| {
                sphere_integral(v.xi_specular, |w| {
                    (exact(w) - f64::from(v.specular_intensity(w).x)).abs()
                }) / truth
            };
            let (before, after) = (l1(&isotropic), l1(&v));
            line += &format!(" {theta}° {:.1} → {:.1} %", 100.0 * before, 100.0 * after);
            assert!(
                after <= before + 0.002,
                "α {alpha} θ {theta}: {before} {after}"
            );
            if theta == 0.0 {
                assert_eq!(before, after);
            }
            if alpha < 0.1 && (22.0..50.0).contains(&theta) {
                assert!(after < 0.08, "α {alpha} θ {theta}: {after}");
            }
        }
        println!("{line}");
    }
}

/// The top VSGL (level 2) of one 4 x 4 face of `texels`, σ² floored at `sigma2_floor`.
pub(super) fn top_vsgl(texels: Vec<Option<RsmTexel>>, sigma2_floor: f32) -> Vsgl {
    let rsm = Rsm {
        resolution: 4,
        faces: 1,
        texels,
    };
    MipRsm::build(&rsm, MeanMap::Toksvig)
        .unwrap()
        .vsgl(0, 2, 0, 0, sigma2_floor)
        .unwrap()
}
