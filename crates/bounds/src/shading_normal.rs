//! VPLs on surfaces whose shading normal n differs from the geometric normal n_g (normal maps).
//!
//! A VPL is a photon that light tracing left at a surface point, so its re-emission follows
//! the *adjoint* BSDF. With shading normals that is not the BSDF itself (Veach 1997, thesis
//! section 5.3, eq. 5.17): the photon's flux Φ arrived through the geometric cross-section
//! (ωi·n_g), the BSDF's cosine is taken at n (ωi·n), and the emitted intensity projects the
//! patch's geometric area (ωo·n_g). Eq. (4) becomes
//!
//! `I(ωo) = Φ f(ωi, ωo) (ωi·n)(ωo·n_g)/(ωi·n_g)`,
//!
//! zero unless ωi and ωo lie above both planes (f is one-sided in n, eq. 6). Where n = n_g it
//! is eq. (4) exactly; a path tracer (and Mitsuba 3) evaluates the same transport.
//!
//! Bounds (what every bound of a tilted VPL uses, proven in `docs/materials.md`):
//! - diffuse: `I = Φ' (kd/π) (ωo·n_g)` with `Φ' = Φ (ωi·n)/(ωi·n_g)` where ωo·n > 0, so the
//!   section-6 sphere of a diffuse lobe around n_g with flux Φ' contains every pair;
//! - glossy: `I = Φ' F D G1(ωi)/(4 ωi·n) · G1(ωo)(ωo·n_g)/(ωo·n)`; eq. (9)-(12) bound the
//!   last factor, G1(ωo), by 1; here it is at most `cos θt + (2/α) sin θt` with θt the angle
//!   between n and n_g ([`g1_tilt_max`]), so the spheroid of eq. (12)-(15) around n with flux
//!   `Φ' (cos θt + (2/α) sin θt)` contains every pair.
use crate::ggx;
use glam::Vec3;

/// The smallest ωi·n_g at which a tilted VPL reflects: the factor 1/(ωi·n_g) stays below 1e6,
/// so its flux stays finite (a photon grazing the geometric surface closer than that is
/// dropped; it carries a vanishing share of any map's flux).
pub const MIN_COS_GEOMETRIC: f32 = 1e-6;

/// The cosine factor of `I(ωo) = Φ f(ωi, ωo) cos_e` (module documentation): `max(ωo·n, 0)`
/// where `n == n_g` (eq. 4), else `(ωi·n)(ωo·n_g)/(ωi·n_g)` where ωi (by at least
/// [`MIN_COS_GEOMETRIC`]) and ωo lie above the geometric plane, else 0. All vectors are
/// unit; f is one-sided in n.
#[inline]
pub fn emitted_cosine(n: Vec3, n_g: Vec3, omega_i: Vec3, omega_o: Vec3) -> f32 {
    if n == n_g {
        return n.dot(omega_o).max(0.0);
    }
    let (gi, go) = (n_g.dot(omega_i), n_g.dot(omega_o));
    if gi < MIN_COS_GEOMETRIC || go <= 0.0 || n.dot(omega_o) <= 0.0 {
        return 0.0;
    }
    n.dot(omega_i).max(0.0) * go / gi
}

/// `(ωi·n)/(ωi·n_g)`: the flux Φ' that multiplies f (ωo·n_g); 1 where `n == n_g`, 0 where
/// ωi lies below n's plane or within [`MIN_COS_GEOMETRIC`] of n_g's (the VPL reflects
/// nothing).
#[inline]
pub fn flux_scale(n: Vec3, n_g: Vec3, omega_i: Vec3) -> f32 {
    if n == n_g {
        return 1.0;
    }
    let (ci, gi) = (n.dot(omega_i), n_g.dot(omega_i));
    if ci <= 0.0 || gi < MIN_COS_GEOMETRIC {
        return 0.0;
    }
    ci / gi
}

/// An upper bound of `G1(ωo)(ωo·n_g)/(ωo·n)` over every ωo above both planes: 1 where
/// `n == n_g` (G1 <= 1, eq. 8), else `cos θt + (2/α) sin θt` with `cos θt = n·n_g`. Since the
/// angle between ωo and n_g is at least |θo − θt|, `ωo·n_g <= cos θo cos θt + sin θo sin θt`,
/// so the ratio is at most `cos θt + sin θt tan θo`; and `G1 tan θo = 2 tan θo / (1 +
/// sqrt(1 + α² tan² θo)) < 2/α`. The result carries a relative margin of 1e-5 for rounding.
pub fn g1_tilt_max(n: Vec3, n_g: Vec3, alpha: f32) -> f32 {
    if n == n_g {
        return 1.0;
    }
    // In f64, the sine from the cross product: accurate for tiny tilts, where 1 − cos θt
    // is below the f32 rounding of a dot product.
    let (n, n_g) = (n.as_dvec3().normalize(), n_g.as_dvec3().normalize());
    let cos_t = n.dot(n_g).clamp(-1.0, 1.0);
    let sin_t = n.cross(n_g).length().min(1.0);
    let bound = cos_t.max(0.0) + 2.0 * sin_t / f64::from(alpha);
    (bound.max(f64::from(ggx::g1(alpha, 1.0))) * (1.0 + 1e-5)) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;

    #[test]
    fn equal_normals_give_eq_4() {
        let n = Vec3::new(0.3, 0.4, 0.5).normalize();
        let wi = Vec3::new(0.1, 0.9, 0.2).normalize();
        for wo in [Vec3::X, Vec3::Y, -n, n] {
            assert_eq!(emitted_cosine(n, n, wi, wo), n.dot(wo).max(0.0));
        }
        assert_eq!(flux_scale(n, n, wi), 1.0);
        assert_eq!(g1_tilt_max(n, n, 0.01), 1.0);
    }

    #[test]
    fn adjoint_cosine_and_zeros() {
        let n_g = Vec3::Z;
        let n = Vec3::new(0.5, 0.0, 1.0).normalize();
        let wi = Vec3::new(-0.3, 0.2, 0.9).normalize();
        let wo = Vec3::new(0.6, -0.1, 0.7).normalize();
        let expected = n.dot(wi) * n_g.dot(wo) / n_g.dot(wi);
        assert!((emitted_cosine(n, n_g, wi, wo) - expected).abs() < 1e-6);
        assert!((flux_scale(n, n_g, wi) - n.dot(wi) / n_g.dot(wi)).abs() < 1e-6);
        // Below the geometric plane, or below the shading plane: nothing.
        let below_g = Vec3::new(1.0, 0.0, -0.1).normalize();
        assert!(n.dot(below_g) > 0.0);
        assert_eq!(emitted_cosine(n, n_g, wi, below_g), 0.0);
        assert_eq!(flux_scale(n, n_g, below_g), 0.0);
        let below_s = Vec3::new(-1.0, 0.0, 0.3).normalize();
        assert!(n_g.dot(below_s) > 0.0 && n.dot(below_s) < 0.0);
        assert_eq!(emitted_cosine(n, n_g, wi, below_s), 0.0);
    }

    /// `g1_tilt_max` bounds G1(ωo)(ωo·n_g)/(ωo·n) over random directions, tilts and α, and
    /// a grazing direction at small α comes within 2% of it (the bound is not loose).
    #[test]
    fn g1_tilt_max_bounds_the_ratio() {
        let mut rng = Rng::new(7);
        for _ in 0..200_000 {
            let n_g = rng.unit();
            let tilt = rng.range(0.0, 1.2);
            let n = (n_g.any_orthonormal_vector() * tilt.sin() + n_g * tilt.cos()).normalize();
            let alpha = 10f32.powf(rng.range(-3.0, 0.0));
            let wo = rng.unit();
            let (co, go) = (n.dot(wo), n_g.dot(wo));
            if co <= 0.0 || go <= 0.0 {
                continue;
            }
            let ratio = f64::from(ggx::g1(alpha, co)) * f64::from(go) / f64::from(co);
            let bound = f64::from(g1_tilt_max(n, n_g, alpha));
            assert!(
                ratio <= bound,
                "{ratio} > {bound} (alpha {alpha}, tilt {tilt})"
            );
        }
        // Grazing ωo in the plane of n and n_g, on n_g's side: the supremum.
        let n_g = Vec3::Z;
        let tilt: f32 = 0.4;
        let n = Vec3::new(tilt.sin(), 0.0, tilt.cos());
        let alpha = 1e-3;
        let theta_o = std::f32::consts::FRAC_PI_2 - 1e-5;
        let wo = Vec3::new((tilt - theta_o).sin(), 0.0, (tilt - theta_o).cos());
        let co = n.dot(wo);
        let ratio = ggx::g1(alpha, co) * n_g.dot(wo) / co;
        assert!(ratio > 0.98 * g1_tilt_max(n, n_g, alpha), "{ratio}");
    }
}
