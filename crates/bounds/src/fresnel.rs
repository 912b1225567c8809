//! Fresnel factors and their maxima over half vectors (supplemental, section 1).
use crate::lanes::{clamp01, Real};
use glam::Vec3;

/// A Fresnel model: Schlick's approximation with an RGB reflectance at normal incidence, or
/// the exact unpolarized dielectric Fresnel factor with a relative index of refraction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fresnel {
    /// Schlick with F0 per channel, supplemental eq. (1).
    Schlick(Vec3),
    /// Unpolarized dielectric with relative index eta > 0, supplemental eq. (3)-(5).
    Dielectric(f32),
}

impl Fresnel {
    /// F(cos θh) of eq. (6) for the cosine between the incoming direction and the half vector:
    /// supplemental eq. (1) (Schlick) or eq. (3)-(5) (dielectric).
    #[inline]
    pub fn eval(&self, cos_h: f32) -> Vec3 {
        match *self {
            Fresnel::Schlick(f0) => schlick(f0, cos_h),
            Fresnel::Dielectric(eta) => Vec3::splat(dielectric(eta, cos_h)),
        }
    }

    /// F_max(ωi): the largest Fresnel factor over all half vectors reachable from an incoming
    /// direction with cosine `cos_i` and sine `sin_i` to the normal; supplemental eq. (2) for
    /// Schlick and eq. (6) for dielectrics: [`Self::max_from`] the cosine of θh_max(ωi)
    /// ([`cos_theta_h_max`]).
    #[inline]
    pub fn max_over_half_vectors(&self, cos_i: f32, sin_i: f32) -> Vec3 {
        self.max_from(cos_theta_h_max(cos_i, sin_i))
    }

    /// The largest Fresnel factor per channel over half vectors with ωi·ωh in `[cos_h, 1]`:
    /// Schlick's at `cos_h` (it grows with the angle, supplemental eq. 2), a dielectric's at an
    /// end of the range (quasiconvex, supplemental eq. 6). A dielectric's far end is taken
    /// [`DIELECTRIC_ULPS`] f32 ulps further: for η < 1 its slope is unbounded near total
    /// internal reflection, where an f32 cosine of a reachable half vector rounded a few ulps
    /// past `cos_h` would otherwise exceed the bound (Schlick's slope is at most 5, so an ulp
    /// changes it by 6e-7 at most).
    #[inline]
    pub fn max_from(&self, cos_h: f32) -> Vec3 {
        match *self {
            Fresnel::Schlick(f0) => schlick(f0, cos_h),
            Fresnel::Dielectric(eta) => {
                let past = cos_h * (1.0 - DIELECTRIC_ULPS * f32::EPSILON);
                Vec3::splat(dielectric(eta, 1.0).max(dielectric(eta, past)))
            }
        }
    }
}

/// How far past θh_max a dielectric's F_max is evaluated, in f32 ulps of the cosine (keep
/// in sync with `fresnel_max_from` in crates/gpu-wgpu/shaders/fresnel_ggx.wgsl).
pub const DIELECTRIC_ULPS: f32 = 4.0;

/// Schlick's approximation, supplemental eq. (1): `F0 + (1 - F0)(1 - cos θh)^5`, where
/// `cos θh = ωi·ωh` (the supplemental text writes `ωi·n`, a typo: the Fresnel factor of eq. (6)
/// is evaluated at `ωi·ωh`).
#[inline]
pub fn schlick(f0: Vec3, cos_h: f32) -> Vec3 {
    let m = (1.0 - cos_h.clamp(0.0, 1.0)).powi(5);
    f0 + (Vec3::ONE - f0) * m
}

/// Unpolarized Fresnel factor of a dielectric with relative index `eta`, supplemental
/// eq. (3)-(5): the mean of the perpendicular and parallel reflectances. Total internal
/// reflection (η² < sin² θh) gives 1.
#[inline]
pub fn dielectric(eta: f32, cos_h: f32) -> f32 {
    dielectric_lanes(eta, cos_h)
}

/// [`dielectric`] written once for one `f32` and for lanes ([`crate::lanes`]): the same IEEE
/// operations in every lane.
#[inline(always)]
pub fn dielectric_lanes<R: Real>(eta: R, cos_h: R) -> R {
    let one = R::splat(1.0);
    let c = clamp01(cos_h);
    // η² − sin² θh as (η² − 1) + cos² θh: exact for index-matched media (η = 1) near grazing.
    let g2 = (eta * eta - one) + c * c;
    let g = g2.sqrt();
    let e2c = eta * eta * c;
    let perp = (c - g) / (c + g);
    let par = (g - e2c) / (g + e2c);
    R::select(
        g2.le(R::splat(0.0)),
        one,
        R::splat(0.5) * (perp * perp + par * par),
    )
}

/// Cosine of the largest angle θh_max(ωi) = ½ arccos(ωi·n) + π/4 between ωi and a half vector
/// whose reflected direction lies above the surface (supplemental, after eq. (2)):
/// `sqrt((1 - sqrt(1 - (ωi·n)²)) / 2)`, evaluated as `cos θi / sqrt(2 (1 + sin θi))`. The
/// reflected direction makes the angle 2θh with ωi, and the largest angle between ωi and a
/// direction of the upper hemisphere is θi + π/2.
///
/// The sine is an argument, not `sqrt(1 − cos²)`: near normal incidence that root loses half
/// the digits (one f32 ulp below 1 is already a sine of 3.5e-4, so two renderers whose
/// cosines differ by an ulp differ by 2e-4 in F_max). The bounds pass `|n × ωi|`
/// ([`crate::GlossyLobe::sin_i`]), exact there; [`sin_from_cos`] serves callers with only a
/// cosine or no need for those digits (the path tracer's lobe choice).
#[inline]
pub fn cos_theta_h_max(cos_i: f32, sin_i: f32) -> f32 {
    cos_theta_h_max_lanes(cos_i, sin_i)
}

/// [`cos_theta_h_max`] written once for one `f32` and for lanes ([`crate::lanes`]): the same
/// IEEE operations in every lane.
#[inline(always)]
pub fn cos_theta_h_max_lanes<R: Real>(cos_i: R, sin_i: R) -> R {
    let one = R::splat(1.0);
    // 1 - sin θi = cos² θi / (1 + sin θi): no cancellation near grazing incidence, where
    // 1 - sin θi would round to 0 for cos θi below about 3e-4.
    clamp01(cos_i) / (R::splat(2.0) * (one + clamp01(sin_i))).sqrt()
}

/// `sqrt(1 − cos²)`, the sine for callers that have only a cosine.
#[inline]
pub fn sin_from_cos(cos: f32) -> f32 {
    (1.0 - cos * cos).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{fibonacci, Rng};
    use glam::DVec3;

    /// Cosines of incident directions from normal to almost grazing incidence.
    fn incidences() -> impl Iterator<Item = f32> {
        [0.0f32, 10.0, 30.0, 45.0, 60.0, 80.0, 89.0, 89.99]
            .into_iter()
            .map(|deg| deg.to_radians().cos())
    }

    /// Cosines ωi·h of half vectors h whose mirror direction 2(ωi·h)h − ωi lies above the
    /// surface (n = +z, ωi in the x-z plane): a dense set on the sphere plus the two extremes
    /// (h = ωi, and ωo grazing on the far side, where θh = θh_max). In f64, so the test's own
    /// rounding cannot step outside the reachable set near grazing incidence.
    fn reachable_cosines(cos_i: f32, count: usize) -> Vec<f32> {
        let c = f64::from(cos_i);
        let omega_i = DVec3::new((1.0 - c * c).sqrt(), 0.0, c);
        let far = (omega_i + DVec3::new(-1.0, 0.0, 0.0)).normalize();
        let mut out = vec![1.0, omega_i.dot(far) as f32];
        for k in 0..count {
            let h = fibonacci(k, count).as_dvec3().normalize();
            let cos_h = omega_i.dot(h);
            if cos_h > 0.0 && (2.0 * cos_h * h - omega_i).z > 0.0 {
                out.push(cos_h as f32);
            }
        }
        out
    }

    fn assert_bounds_and_attains(fresnel: Fresnel, cos_i: f32, cosines: &[f32]) {
        let f_max = fresnel.max_over_half_vectors(cos_i, sin_from_cos(cos_i));
        let mut attained = Vec3::ZERO;
        for &c in cosines {
            let f = fresnel.eval(c);
            assert!(
                f.cmple(f_max + 1e-6).all(),
                "{fresnel:?} {cos_i}: F({c}) = {f} > {f_max}"
            );
            attained = attained.max(f);
        }
        // Attained up to the dielectric's few ulps past θh_max (steep near TIR for η < 1).
        assert!(
            (f_max - attained).abs().max_element() < 1e-4,
            "{fresnel:?} {cos_i}: F_max {f_max} not attained ({attained})"
        );
    }

    #[test]
    fn f_max_bounds_every_reachable_half_vector() {
        let etas = [0.2, 0.25, 0.3, 0.5, 0.8, 1.0, 1.33, 1.5, 2.5, 3.7, 4.0, 5.0];
        let mut rng = Rng::new(7);
        for cos_i in incidences() {
            let cosines = reachable_cosines(cos_i, 6000);
            for eta in etas {
                assert_bounds_and_attains(Fresnel::Dielectric(eta), cos_i, &cosines);
            }
            for _ in 0..12 {
                let f0 = Vec3::new(rng.f32(), rng.f32(), rng.f32());
                assert_bounds_and_attains(Fresnel::Schlick(f0), cos_i, &cosines);
            }
        }
    }

    /// Found by the random test in CI: η < 1 near total internal reflection, where a reachable
    /// half vector's f32 cosine fell an ulp past cos θh_max and F's slope is steep.
    #[test]
    fn f_max_bounds_near_total_internal_reflection() {
        let cos_i = 0.707_115_23;
        let cosines = reachable_cosines(cos_i, 1500);
        assert_bounds_and_attains(Fresnel::Dielectric(0.924_656_03), cos_i, &cosines);
    }

    #[test]
    fn theta_h_max_matches_its_angle_form() {
        for k in 0..=100 {
            let theta_i = k as f32 / 100.0 * core::f32::consts::FRAC_PI_2;
            let expected = (0.5 * theta_i + core::f32::consts::FRAC_PI_4).cos();
            assert!((cos_theta_h_max(theta_i.cos(), theta_i.sin()) - expected).abs() < 1e-3);
        }
        assert_eq!(cos_theta_h_max(0.0, 1.0), 0.0);
        // Near grazing incidence θh_max = π/2 - θ_i'/2 with θ_i' = π/2 - θi: cos ≈ cos θi / 2.
        assert!((cos_theta_h_max(1e-6, 1.0) - 5e-7).abs() < 1e-12);
        assert!((cos_theta_h_max(1.0, 0.0) - core::f32::consts::FRAC_1_SQRT_2).abs() < 1e-6);
    }

    #[test]
    fn dielectric_matches_known_values() {
        // Normal incidence: ((η - 1)/(η + 1))²; grazing incidence and TIR: 1.
        for eta in [0.5f32, 1.5, 4.0] {
            let r0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((dielectric(eta, 1.0) - r0).abs() < 1e-6);
            assert!((dielectric(eta, 0.0) - 1.0).abs() < 1e-6);
        }
        assert_eq!(
            dielectric(0.5, 0.5),
            1.0,
            "sin θ = 0.87 > η: total internal reflection"
        );
        assert_eq!(dielectric(1.0, 0.7), 0.0, "index-matched");
        // Brewster's angle: the parallel part vanishes, F = F_perp / 2.
        let eta = 1.5f32;
        let c = (1.0 / (1.0 + eta * eta)).sqrt();
        let g = (eta * eta - (1.0 - c * c)).sqrt();
        assert!((dielectric(eta, c) - 0.5 * ((c - g) / (c + g)).powi(2)).abs() < 1e-6);
    }

    #[test]
    fn schlick_endpoints() {
        let f0 = Vec3::new(0.04, 0.5, 1.0);
        assert_eq!(schlick(f0, 1.0), f0);
        assert_eq!(schlick(f0, 0.0), Vec3::ONE);
        assert_eq!(Fresnel::Schlick(f0).eval(1.0), f0);
    }

    proptest::proptest! {
        #[test]
        fn f_max_bounds_random_cases(
            cos_i in 1e-6f32..=1.0,
            eta in 0.2f32..5.0,
            f0 in proptest::array::uniform3(0.0f32..=1.0),
        ) {
            let cosines = reachable_cosines(cos_i, 1500);
            assert_bounds_and_attains(Fresnel::Dielectric(eta), cos_i, &cosines);
            assert_bounds_and_attains(Fresnel::Schlick(Vec3::from_array(f0)), cos_i, &cosines);
        }
    }
}
