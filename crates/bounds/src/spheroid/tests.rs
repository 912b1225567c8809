//! Geometry of the GGX bounding spheroid: the peak, the surface of eq. (12), the axes of
//! eq. (13)-(15), empty bounds and overflow.
use super::probe::{normalized_radius, random_lobe, random_params};
use super::*;
use crate::fresnel::Fresnel;
use crate::ggx;
use crate::sphere::Sphere;
use crate::test_space::TestSpace;
use crate::test_util::{fibonacci, Rng};
use glam::Affine3A;

#[test]
fn peak_touches_the_surface_at_normal_incidence() {
    // ωi = n, F ≡ 1: l_max(ω_u) = r/α, the far end of the spheroid (eq. 12 with D(1)).
    let params = StochasticParams::new(1e-3, 0.3).unwrap();
    for alpha in [1e-4, 1e-3, 0.01, 0.1, 0.5, 1.0] {
        let n = Vec3::new(0.36, 0.48, 0.8);
        let lobe = GlossyLobe::new(
            Vec3::ONE,
            n,
            n,
            alpha,
            Vec3::splat(3.0),
            Fresnel::Schlick(Vec3::ONE),
        )
        .unwrap();
        let s = Spheroid::new(&lobe, &params).unwrap();
        let l = params.range(lobe.intensity(n));
        let rho = normalized_radius(&s, (lobe.position() + l * n).as_dvec3());
        assert!((rho - 1.0).abs() < 3e-4, "α {alpha}: ρ = {rho}");
        assert!((s.radius() / alpha - l).abs() < 1e-4 * l);
    }
}

/// A random lobe of `alpha` at `deg` degrees of incidence with Fresnel 1 everywhere.
fn white_lobe(rng: &mut Rng, alpha: f32, deg: f32) -> GlossyLobe {
    random_lobe(rng, alpha, deg.to_radians(), Fresnel::Schlick(Vec3::ONE))
}

#[test]
fn peak_ratio_is_fresnel_times_g1_over_f_max() {
    // At ωo = ω_u the half vector is n, and s(ω_u) = r/α (eq. 12 with D(1) = 1/(πα²)):
    // l²/s² = F(ωi·n) G1(ωo) / F_max(ωi) with G1(ωo) = G1(ωi) (eq. 6, 9).
    let params = StochasticParams::new(1e-2, 0.7).unwrap();
    let mut rng = Rng::new(42);
    for alpha in [0.01f32, 0.2, 1.0] {
        for deg in [0.0f32, 30.0, 60.0, 80.0] {
            let cos_i = f64::from(deg.to_radians().cos());
            let lobe = white_lobe(&mut rng, alpha, deg);
            let s = Spheroid::new(&lobe, &params).unwrap();
            let u = lobe.reflection();
            let ratio = f64::from(params.range(lobe.intensity(u)) / (s.radius() / alpha));
            let a2 = f64::from(alpha).powi(2);
            let g1 = 2.0 * cos_i / (cos_i + ((1.0 - a2) * cos_i * cos_i + a2).sqrt());
            assert!(
                (ratio - g1.sqrt()).abs() < 2e-5,
                "α {alpha} θ {deg}: {ratio} vs {}",
                g1.sqrt()
            );
        }
    }
    // Dielectric η = 1.5 at normal incidence: F(1) = 0.04, F_max = F(45°).
    let n = Vec3::Z;
    let lobe = GlossyLobe::new(Vec3::ZERO, n, n, 0.1, Vec3::ONE, Fresnel::Dielectric(1.5)).unwrap();
    let s = Spheroid::new(&lobe, &params).unwrap();
    let ratio = f64::from(params.range(lobe.intensity(n)) / (s.radius() / 0.1));
    let (c, eta2) = (0.5f64.sqrt(), 2.25f64);
    let g = (eta2 - 0.5).sqrt();
    let f45 = 0.5 * (((c - g) / (c + g)).powi(2) + ((g - eta2 * c) / (g + eta2 * c)).powi(2));
    assert!(
        (ratio - (0.04 / f45).sqrt()).abs() < 2e-5,
        "{ratio} vs {}",
        (0.04 / f45).sqrt()
    );
}

#[test]
fn surface_is_the_radial_function_of_eq_12() {
    // Appendix A: q + s(ωo) ωo with s = r sqrt(π D(cos θ/2)) = r α / (α² cos²(θ/2) +
    // sin²(θ/2)), θ = ∠(ωo, ω_u), lies on the spheroid for every ωo.
    let mut rng = Rng::new(43);
    for _ in 0..60 {
        let alpha = 10f32.powf(rng.range(-2.0, 0.0));
        let theta_i = rng.range(0.0, 1.5);
        let lobe = random_lobe(&mut rng, alpha, theta_i, Fresnel::Dielectric(1.4));
        let s = Spheroid::new(&lobe, &random_params(&mut rng)).unwrap();
        let (r, a) = (f64::from(s.radius()), f64::from(alpha));
        let u = lobe.reflection().as_dvec3();
        for k in 0..200 {
            let dir = fibonacci(k, 200).as_dvec3();
            let cos = dir.dot(u);
            let radial = r * a / (a * a * (1.0 + cos) / 2.0 + (1.0 - cos) / 2.0);
            let rho = normalized_radius(&s, lobe.position().as_dvec3() + radial * dir);
            assert!((rho - 1.0).abs() < 2e-4, "α {alpha}: ρ = {rho}");
        }
    }
}

#[test]
fn axes_follow_eq_13_to_15() {
    let mut rng = Rng::new(44);
    let params = StochasticParams::new(1e-3, 0.4).unwrap();
    for deg in [0.0f32, 1e-5, 0.05, 10.0, 60.0, 89.0] {
        let alpha = rng.range(0.01, 1.0);
        let lobe = white_lobe(&mut rng, alpha, deg);
        let s = Spheroid::new(&lobe, &params).unwrap();
        let (rot, r) = (s.rotation(), s.radius());
        let cols = [rot.x_axis, rot.y_axis, rot.z_axis];
        for (i, a) in cols.iter().enumerate() {
            assert!((a.length() - 1.0).abs() < 1e-6);
            for b in &cols[i + 1..] {
                assert!(a.dot(*b).abs() < 1e-6);
            }
        }
        assert!((rot.determinant() - 1.0).abs() < 1e-5);
        assert!(
            (rot.x_axis - lobe.reflection()).length() < 1e-6,
            "first axis is ω_u"
        );
        if deg > 1.0 {
            // ω_w = ω_u × n / |ω_u × n| away from normal incidence.
            let w = lobe.reflection().cross(lobe.normal()).normalize();
            assert!((rot.z_axis - w).length() < 1e-5);
        }
        let a = alpha;
        let expect = Vec3::new((1.0 + a * a) / (2.0 * a) * r, r, r);
        assert!((s.semi_axes() - expect).abs().max_element() <= 1e-6 * expect.x);
        let c = lobe.position() + (1.0 - a * a) / (2.0 * a) * r * lobe.reflection();
        assert!((s.center() - c).length() <= 1e-5 * (c.length() + r / a));
        assert!(s.contains(lobe.position() + 0.5 * r * lobe.reflection()));
        assert!(!s.contains(lobe.position() + 1.01 * r / a * lobe.reflection()));
    }
}

#[test]
fn empty_bounds_contain_nothing() {
    let params = StochasticParams::new(1e-3, 0.5).unwrap();
    let f = Fresnel::Schlick(Vec3::splat(0.04));
    let n = Vec3::Z;
    let q = Vec3::new(1.0, 2.0, 3.0);
    let cases = [
        GlossyLobe::new(q, n, n, 0.3, Vec3::ZERO, f).unwrap(),
        GlossyLobe::new(q, n, Vec3::new(0.6, 0.0, -0.8), 0.3, Vec3::ONE, f).unwrap(),
        GlossyLobe::new(q, n, Vec3::X, 0.3, Vec3::ONE, f).unwrap(),
        GlossyLobe::new(q, n, -n, 1e-4, Vec3::ONE, f).unwrap(),
    ];
    for lobe in cases {
        let s = Spheroid::new(&lobe, &params).unwrap();
        assert!(s.is_empty() && s.radius() == 0.0 && s.semi_axes() == Vec3::ZERO);
        assert!(s.center().is_finite() && s.rotation().is_finite());
        for p in [q, s.center(), q + n, Vec3::ZERO] {
            assert!(!s.contains(p));
        }
        assert!(Sphere::around_vpl(&lobe, &params).unwrap().is_empty());
        assert!(Sphere::enclosing(&s).is_empty());
        let space = TestSpace::from_spheroid(&s, Affine3A::IDENTITY).unwrap();
        assert!(space.is_empty() && !space.contains(q));
    }
}

#[test]
fn grazing_and_normal_incidence_are_finite() {
    let params = StochasticParams::new(1e-3, 0.5).unwrap();
    for alpha in [1e-4f32, 0.5, 1.0] {
        for omega_i in [Vec3::Z, Vec3::new(1.0, 0.0, 1e-6).normalize()] {
            let lobe = GlossyLobe::new(
                Vec3::ZERO,
                Vec3::Z,
                omega_i,
                alpha,
                Vec3::ONE,
                Fresnel::Dielectric(1.5),
            )
            .unwrap();
            let s = Spheroid::new(&lobe, &params).unwrap();
            assert!(s.radius() > 0.0 && s.semi_axes().is_finite() && s.center().is_finite());
            assert!(s.rotation().is_finite() && (s.rotation().determinant() - 1.0).abs() < 1e-5);
        }
    }
}

#[test]
fn overflow_is_an_error_not_infinity() {
    let params = StochasticParams::new(f32::MIN_POSITIVE, 1e-7).unwrap();
    let lobe = GlossyLobe::new(
        Vec3::ZERO,
        Vec3::Z,
        Vec3::Z,
        1e-4,
        Vec3::splat(1e30),
        Fresnel::Schlick(Vec3::ONE),
    )
    .unwrap();
    assert!(matches!(
        Spheroid::new(&lobe, &params),
        Err(BoundsError::Overflow(_))
    ));
}

#[test]
fn g1_over_cos_is_what_r_uses() {
    // r² (4π δ ξ) = Φ F_max G1/|cos|: compare with G1 / cos where both are finite.
    let params = StochasticParams::new(1e-3, 0.5).unwrap();
    let wi = Vec3::new(0.8, 0.0, 0.6);
    let lobe = GlossyLobe::new(
        Vec3::ZERO,
        Vec3::Z,
        wi,
        0.25,
        Vec3::ONE,
        Fresnel::Schlick(Vec3::ONE),
    )
    .unwrap();
    let r = Spheroid::new(&lobe, &params).unwrap().radius();
    let want = ggx::g1(0.25, 0.6) / 0.6 / (4.0 * core::f32::consts::PI * 1e-3 * 0.5);
    assert!((r * r - want).abs() < 1e-4 * want);
}
