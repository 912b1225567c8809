//! Test helpers: probe a glossy lobe's random range l_max(ωo) (eq. 5) in many directions and
//! measure it against the spheroid (eq. 12-15) and the baseline spheres (section 7).
use super::*;
use crate::fresnel::Fresnel;
use crate::sphere::Sphere;
use crate::test_util::{around, fibonacci, log_angles, Rng};
use glam::DVec3;

/// |diag(1/r_u, 1/r_v, 1/r_w) Rᵀ (p − c)| in f64 from the spheroid's own data: 1 on its surface.
pub(super) fn normalized_radius(s: &Spheroid, p: DVec3) -> f64 {
    let d = p - s.center().as_dvec3();
    let r = s.rotation();
    let local = DVec3::new(
        r.x_axis.as_dvec3().dot(d),
        r.y_axis.as_dvec3().dot(d),
        r.z_axis.as_dvec3().dot(d),
    );
    (local / s.semi_axes().as_dvec3()).length()
}

/// Allowed excess of the normalised radius for f32 rounding. Sharper lobes are longer
/// (r_u / r = (1+α²)/(2α)), so the same relative rounding moves a point further across the
/// thin axes.
fn tolerance(alpha: f32) -> f64 {
    2e-4 * (1e-3 / f64::from(alpha)).max(1.0)
}

/// Directions that probe a lobe: a Fibonacci sphere (both hemispheres; l_max = 0 below),
/// random ones, dense rings around the mirror direction ω_u from 1e-3 α to 3 rad, and the
/// great circle through ωi and n, where eq. (10) is an equality.
pub(super) fn directions(lobe: &GlossyLobe, rng: &mut Rng, sphere_count: usize) -> Vec<Vec3> {
    let mut dirs: Vec<Vec3> = (0..sphere_count)
        .map(|k| fibonacci(k, sphere_count))
        .collect();
    dirs.extend((0..sphere_count / 5).map(|_| rng.unit()));
    let omega_u = lobe.reflection();
    let angles = log_angles(1e-3 * f64::from(lobe.alpha()), 3.0, 40);
    dirs.extend(around(omega_u, &angles, 12));
    dirs.push(omega_u);
    let towards_n = lobe.normal() - lobe.normal().dot(omega_u) * omega_u;
    if towards_n.length_squared() > 1e-8 {
        let (u, t) = (omega_u.as_dvec3(), towards_n.normalize().as_dvec3());
        for &a in &angles {
            for sign in [-1.0, 1.0] {
                dirs.push((u * a.cos() + t * (sign * a.sin())).normalize().as_vec3());
            }
        }
    }
    dirs
}

/// The largest normalised radius (spheroid) and distance/radius (spheres) over the points
/// q + l_max(ωo) ωo, l_max from eq. (5) with I(ωo) of eq. (4) and the true BRDF of eq. (6).
pub(super) struct Worst {
    pub(super) spheroid: f64,
    pub(super) around_vpl: f64,
    pub(super) enclosing: f64,
}

fn worst_case(lobe: &GlossyLobe, params: &StochasticParams, dirs: &[Vec3]) -> Worst {
    let s = Spheroid::new(lobe, params).unwrap();
    let around_vpl = Sphere::around_vpl(lobe, params).unwrap();
    let enclosing = Sphere::enclosing(&s);
    let q = lobe.position().as_dvec3();
    let mut worst = Worst {
        spheroid: 0.0,
        around_vpl: 0.0,
        enclosing: 0.0,
    };
    for &dir in dirs {
        let l = params.range(lobe.intensity(dir));
        assert!(l.is_finite(), "{lobe:?} {dir}");
        let p = q + f64::from(l) * dir.as_dvec3();
        let rho = normalized_radius(&s, p);
        worst.spheroid = worst.spheroid.max(rho);
        worst.around_vpl = worst
            .around_vpl
            .max((p - q).length() / f64::from(around_vpl.radius));
        let to_c = (p - enclosing.center.as_dvec3()).length();
        worst.enclosing = worst.enclosing.max(to_c / f64::from(enclosing.radius));
        if rho < 0.999 {
            assert!(s.contains(p.as_vec3()), "contains() disagrees at ρ = {rho}");
        }
    }
    worst
}

pub(super) fn assert_conservative(
    lobe: &GlossyLobe,
    params: &StochasticParams,
    dirs: &[Vec3],
) -> Worst {
    let w = worst_case(lobe, params, dirs);
    let tol = 1.0 + tolerance(lobe.alpha());
    assert!(
        w.spheroid <= tol,
        "spheroid misses ρ = {} for {lobe:?} {params:?}",
        w.spheroid
    );
    assert!(
        w.around_vpl <= tol,
        "r/α sphere misses {} for {lobe:?}",
        w.around_vpl
    );
    assert!(
        w.enclosing <= tol,
        "r_u sphere misses {} for {lobe:?}",
        w.enclosing
    );
    w
}

/// A lobe with ωi at `theta_i` from a random normal, at a random position and flux.
pub(super) fn random_lobe(rng: &mut Rng, alpha: f32, theta_i: f32, fresnel: Fresnel) -> GlossyLobe {
    let n = rng.unit();
    let phi = rng.range(0.0, core::f32::consts::TAU);
    let local = Vec3::new(
        theta_i.sin() * phi.cos(),
        theta_i.sin() * phi.sin(),
        theta_i.cos(),
    );
    let omega_i = Basis::from_unit(n).to_world(local);
    let q = Vec3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    );
    let flux = Vec3::new(
        rng.range(0.01, 50.0),
        rng.range(0.01, 50.0),
        rng.range(0.01, 50.0),
    );
    GlossyLobe::new(q, n, omega_i, alpha, flux, fresnel).unwrap()
}

pub(super) fn random_params(rng: &mut Rng) -> StochasticParams {
    StochasticParams::new(10f32.powf(rng.range(-5.0, 0.0)), rng.range(1e-6, 1.0)).unwrap()
}
