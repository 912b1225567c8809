//! The irradiance of a spherical Gaussian light, `∫ c G(ω; ξ, λ) max(ω·n, 0) dω`: the diffuse
//! term of VSGL eq. (2) for the incoming radiance of eq. (5), with the clamp at the horizon.
use crate::sg::integral::integral_f64;
use crate::sg::lobe::SphericalGaussian;
use crate::sg::toksvig::langevin;
use glam::Vec3;

/// `c0` of S. Hill's fit of the clamped-cosine convolution of an SG (published in M.
/// Pettineo, "SG Series Part 3: Diffuse Lighting From an SG Light Source", 2016,
/// `SGIrradianceFitted`): the half-width of the horizon transition is `1/(4 c0²)` times
/// `sqrt(1 − L(λ))`.
const HILL_C0: f64 = 0.36;

/// The irradiance of a normalized lobe, `E(λ, μ) = ∫ G(ω; ξ, λ)/A(λ) max(ω·n, 0) dω` with
/// `μ = ξ·n`, in the form of Hill's fit, `E = L(λ) y(μ) + b(λ)`:
///
/// - `L(λ) = coth λ − 1/λ` is the lobe's exact mean-vector length: with `y(μ) − y(−μ) = μ`,
///   `E(μ) − E(−μ) = L μ` holds exactly (it is `∫ G/A (ω·n) dω`, the unclamped cosine);
/// - `b(λ) = e^{−λ}(1 − e^{−λ}(1 + λ)) / (λ (1 − e^{−2λ}))` is exactly `E(λ, −1)`, the part of
///   the lobe that still reaches a surface facing away from it;
/// - `y(μ)` is Hill's: `max(μ, 0)` away from the horizon and `(c0 μ + x/(4c0))²/x`,
///   `x = sqrt(1 − L)`, across it, while that transition `|μ| ≤ x/(4c0²)` fits in `[−1, 1]`.
///   Broader lobes (λ below about 3.6) use the quadratic through `y(−1) = 0` and `y(1) = 1`,
///   `a + μ/2 + (½ − a) μ²`, with `a` going linearly in `x` from Hill's ¼ at the switch to ½
///   at λ = 0, where `E = ¼ + λμ/6 + O(λ²)` is then exact to first order.
///
/// Hill uses the large-λ forms `1 + 2e^{−2λ} − 1/λ` and `(e^{−λ} − e^{−2λ})/λ − e^{−2λ}` of
/// `L` and `b`, which diverge as λ → 0. This form is exact at λ = 0 (`E = ¼` for a constant
/// lobe), at μ = −1 and for λ → ∞ (the clamped cosine), stays in `[0, 1]`, and is within 1.8 %
/// of `E(λ, 1)` everywhere (measured by the tests). Negative or NaN sharpness is treated as 0,
/// `μ` is clamped to `[−1, 1]`.
pub fn normalized_sg_irradiance(sharpness: f32, mu: f32) -> f32 {
    let l = f64::from(sharpness.max(0.0));
    let mu = f64::from(mu.clamp(-1.0, 1.0));
    let mean = langevin(l);
    let x = (1.0 - mean).max(0.0).sqrt();
    (mean * hill_y(x, mu) + away_facing(l)).clamp(0.0, 1.0) as f32
}

/// `y(μ)` of [`normalized_sg_irradiance`] for `x = sqrt(1 − L(λ))` (also the `f32` shading's,
/// `sg/single.rs`, which forms `x` in `f32`).
pub(crate) fn hill_y(x: f64, mu: f64) -> f64 {
    // The half-width of Hill's horizon transition.
    let switch = 4.0 * HILL_C0 * HILL_C0;
    if x >= switch {
        let a = 0.25 + 0.25 * (x - switch) / (1.0 - switch);
        a + 0.5 * mu + (0.5 - a) * mu * mu
    } else {
        let (x0, x1) = (HILL_C0 * mu, x / (4.0 * HILL_C0));
        if x > 0.0 && x0.abs() <= x1 {
            (x0 + x1).powi(2) / x
        } else {
            mu.max(0.0)
        }
    }
}

/// `b(λ) = E(λ, −1)`, with its series `1/4 − λ/6` below λ = 1e-3 where the numerator cancels.
fn away_facing(l: f64) -> f64 {
    if l < 1e-3 {
        return 0.25 - l / 6.0;
    }
    let e = (-l).exp();
    if l >= 1.0 {
        return e * (1.0 - e * (1.0 + l)) / (l * (1.0 - e * e));
    }
    // 1 − e^{−λ}(1 + λ) and 1 − e^{−2λ} from expm1, to keep their digits for small λ.
    let numerator = -(-l).exp_m1() - l * e;
    e * numerator / (l * -(-2.0 * l).exp_m1())
}

impl SphericalGaussian {
    /// The irradiance `∫ c G(ω; ξ, λ) max(ω·n, 0) dω` on a surface of unit normal `n`:
    /// `c A(λ) E(λ, ξ·n)` ([`normalized_sg_irradiance`]). A value beyond the `f32` range (only
    /// for amplitudes near it) saturates at `f32::MAX`.
    pub fn irradiance(&self, n: Vec3) -> f32 {
        let e = normalized_sg_irradiance(self.sharpness, self.axis.dot(n));
        let value =
            f64::from(self.amplitude) * integral_f64(f64::from(self.sharpness)) * f64::from(e);
        value.min(f64::from(f32::MAX)) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sg::quadrature::{eval64, sphere_integral, width};
    use crate::test_util::log_angles;

    fn direction(mu: f64) -> Vec3 {
        Vec3::new((1.0 - mu * mu).max(0.0).sqrt() as f32, 0.0, mu as f32)
    }

    #[test]
    fn irradiance_matches_quadrature() {
        // Over λ from 1e-4 to 1e4 and 41 angles between the lobe and the normal: the error
        // relative to the irradiance facing the lobe, E(λ, 1), and where E is at least a tenth
        // of that, relative to E itself.
        let (mut worst_peak, mut worst_rel) = (0.0f64, 0.0f64);
        for l in log_angles(1e-4, 1e4, 17) {
            let lobe = |mu: f64| SphericalGaussian::new(direction(mu), l as f32, 1.0).unwrap();
            let truth = |mu: f64| {
                let sg = lobe(mu);
                sphere_integral(sg.axis.as_dvec3(), width(l), |w| {
                    eval64(&sg, w) * w.z.max(0.0)
                })
            };
            let peak = truth(1.0);
            for k in 0..=40 {
                let mu = -1.0 + 0.05 * f64::from(k);
                let (want, got) = (truth(mu), f64::from(lobe(mu).irradiance(Vec3::Z)));
                worst_peak = worst_peak.max((got - want).abs() / peak);
                if want > 0.1 * peak {
                    worst_rel = worst_rel.max((got - want).abs() / want);
                }
            }
        }
        // Measured: 0.0178 of the peak and 0.156 relative, both at λ ≈ 10 and μ ≈ 0 (Hill's
        // quadratic across the horizon); below λ = 3 under 0.005 and 0.02. The SG inner
        // product with the cosine fit `1.17 G(·; n, 2.133)` it replaces is off by 0.17 of the
        // light's integral.
        println!("irradiance: worst error {worst_peak:.4} of the peak, {worst_rel:.4} relative");
        assert!(
            worst_peak < 0.02 && worst_rel < 0.17,
            "{worst_peak} {worst_rel}"
        );
    }

    #[test]
    fn exact_limits_and_extremes() {
        // A constant lobe: E = 1/4 of its integral whatever the normal. A very sharp lobe: the
        // clamped cosine. Facing away, exactly b(λ); the odd part exactly L(λ) μ.
        for mu in [-1.0f32, -0.3, 0.0, 0.7, 1.0] {
            assert!((normalized_sg_irradiance(0.0, mu) - 0.25).abs() < 1e-7);
            let sharp = normalized_sg_irradiance(1e9, mu);
            assert!((sharp - mu.max(0.0)).abs() < 1e-4, "{mu}: {sharp}");
        }
        assert!((normalized_sg_irradiance(1e-6, -1.0) - 0.25).abs() < 1e-6);
        for l in [1e-3f32, 0.5, 3.0, 50.0] {
            let facing_away = 2.0
                * core::f64::consts::PI
                * (-f64::from(l)).exp()
                * (1.0 - (-f64::from(l)).exp() * (1.0 + f64::from(l)))
                / f64::from(l).powi(2)
                / integral_f64(f64::from(l));
            let got = f64::from(normalized_sg_irradiance(l, -1.0));
            assert!(
                (got - facing_away).abs() < 1e-6,
                "{l}: {got} vs {facing_away}"
            );
            for mu in [0.1f32, 0.5, 0.9] {
                let odd = normalized_sg_irradiance(l, mu) - normalized_sg_irradiance(l, -mu);
                let want = langevin(f64::from(l)) * f64::from(mu);
                assert!(
                    (f64::from(odd) - want).abs() < 1e-6,
                    "{l} {mu}: {odd} vs {want}"
                );
            }
        }
        for (l, mu) in [(f32::NAN, 0.5), (-1.0, 0.5), (f32::MAX, 0.0), (1.0, 2.0)] {
            let e = normalized_sg_irradiance(l, mu);
            assert!((0.0..=1.0).contains(&e), "{l} {mu}: {e}");
        }
        let huge = SphericalGaussian::new(Vec3::Z, 0.0, f32::MAX).unwrap();
        assert_eq!(huge.irradiance(Vec3::Z), f32::MAX);
    }
}
