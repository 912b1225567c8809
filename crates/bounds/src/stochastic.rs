//! Stochastic light culling by Russian roulette with one random number per light: the
//! acceptance probability (eq. 2), the estimator (eq. 3) and the random range (eq. 5).
use crate::error::BoundsError;
use glam::Vec3;

/// The scalar intensity of an RGB quantity: its largest channel.
///
/// This is the convention the whole project uses wherever an RGB radiant intensity, flux or
/// flux-times-reflectance enters the probability p of eq. (2), the range of eq. (5) or the
/// radii of eq. (12) and section 6. Since the bounds scale every channel by the same
/// non-negative factor, the maximum channel is the one that bounds them all.
#[inline]
pub fn scalar_intensity(rgb: Vec3) -> f32 {
    rgb.max_element()
}

/// The user parameter δ of eq. (2) and the per-light random number ξ of eq. (3), validated:
/// δ is a finite positive normal `f32` and ξ a normal `f32` in the open interval (0, 1) (the
/// project's RNG never returns exactly 0 or 1). Validated once, so the per-pixel methods need
/// no checks and can never produce NaN or infinity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StochasticParams {
    delta: f32,
    xi: f32,
}

impl StochasticParams {
    /// Validates δ ∈ (0, ∞) (eq. 2) and ξ ∈ (0, 1) (eq. 3).
    pub fn new(delta: f32, xi: f32) -> Result<Self, BoundsError> {
        if !(delta.is_normal() && delta > 0.0) {
            return Err(BoundsError::InvalidDelta(delta));
        }
        if !(xi.is_normal() && xi > 0.0 && xi < 1.0) {
            return Err(BoundsError::InvalidXi(xi));
        }
        Ok(Self { delta, xi })
    }

    /// δ, the variance control of eq. (2).
    #[inline]
    pub fn delta(&self) -> f32 {
        self.delta
    }

    /// ξ, the light's uniform random number of eq. (3).
    #[inline]
    pub fn xi(&self) -> f32 {
        self.xi
    }

    /// The acceptance probability of eq. (2): `p = min(I / (δ l²), 1)` for a scalar radiant
    /// intensity `I` (see [`scalar_intensity`]) and squared distance `l²`.
    ///
    /// `I <= 0` (or NaN) gives 0; `l² = 0` gives 1 for `I > 0`. A negative or NaN `l²` is
    /// treated like 0. The result always lies in [0, 1].
    #[inline]
    pub fn probability(&self, intensity: f32, distance_sq: f32) -> f32 {
        if intensity > 0.0 {
            let p = intensity / (self.delta * distance_sq);
            if (0.0..1.0).contains(&p) {
                p
            } else {
                1.0
            }
        } else {
            0.0
        }
    }

    /// The random range of eq. (5): `l_max = p⁻¹(ξ) = sqrt(I / (δ ξ))`, the distance beyond
    /// which the light is rejected. `I <= 0` (or NaN) gives 0; values beyond `f32::MAX`
    /// saturate to `f32::MAX`.
    #[inline]
    pub fn range(&self, intensity: f32) -> f32 {
        if intensity > 0.0 {
            (intensity / self.delta / self.xi).sqrt().min(f32::MAX)
        } else {
            0.0
        }
    }

    /// The weight of the estimator of eq. (3): `1/p` if `p > ξ` (the light is accepted), else
    /// 0. Multiplying the light's contribution by it is unbiased: E_ξ(weight) = 1. The result
    /// is finite (at most 1/ξ).
    #[inline]
    pub fn estimator_weight(&self, probability: f32) -> f32 {
        if probability > self.xi {
            1.0 / probability
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(delta: f32, xi: f32) -> StochasticParams {
        StochasticParams::new(delta, xi).unwrap()
    }

    #[test]
    fn scalar_is_max_channel() {
        assert_eq!(scalar_intensity(Vec3::new(0.2, 3.0, 1.0)), 3.0);
        assert_eq!(scalar_intensity(Vec3::ZERO), 0.0);
    }

    #[test]
    fn probability_is_eq_2() {
        let p = params(1e-3, 0.5);
        assert!((p.probability(2e-3, 4.0) - 0.5).abs() < 1e-7);
        assert_eq!(p.probability(1.0, 1.0), 1.0, "clamped to 1");
        assert_eq!(p.probability(1.0, 0.0), 1.0, "l = 0");
        assert_eq!(p.probability(0.0, 0.0), 0.0, "I = 0");
        assert_eq!(p.probability(0.0, 5.0), 0.0);
        assert_eq!(p.probability(-1.0, 5.0), 0.0);
        assert_eq!(p.probability(f32::NAN, 5.0), 0.0);
        assert_eq!(p.probability(1e-3, f32::NAN), 1.0);
        assert_eq!(p.probability(1e-3, -2.0), 1.0);
        assert_eq!(p.probability(f32::INFINITY, f32::INFINITY), 1.0);
        assert_eq!(p.probability(f32::MAX, 0.5), 1.0);
    }

    #[test]
    fn range_inverts_probability() {
        // p(l_max) = ξ: the range is exactly where the roulette stops accepting (eq. 5).
        for (delta, xi) in [(1e-3, 0.25), (1e-9, 3e-8), (1e3, 0.99999994), (0.5, 0.7)] {
            let p = params(delta, xi);
            for intensity in [1e-6f32, 0.3, 12.0, 4e4] {
                let l = p.range(intensity);
                let at = p.probability(intensity, l * l);
                assert!(
                    (at - xi).abs() <= 1e-5 * xi,
                    "δ {delta} ξ {xi} I {intensity}: {at}"
                );
                assert!(p.probability(intensity, (l * 1.001).powi(2)) < xi);
                assert!(p.probability(intensity, (l * 0.999).powi(2)) > xi);
            }
            assert_eq!(p.range(0.0), 0.0);
            assert_eq!(p.range(f32::NAN), 0.0);
        }
        let extreme = params(1e-9, 3e-8);
        assert_eq!(
            extreme.range(f32::MAX),
            f32::MAX,
            "saturates instead of overflowing"
        );
        assert!(extreme.range(1e10).is_finite());
    }

    #[test]
    fn estimator_is_unbiased() {
        // E_ξ[1/p · [p > ξ]] = 1 for any p in (0, 1]: midpoint rule over ξ.
        for prob in [1.0f32, 0.5, 0.1, 0.013] {
            let n = 20_000;
            let mean: f64 = (0..n)
                .map(|k| {
                    let xi = (k as f32 + 0.5) / n as f32;
                    f64::from(params(1.0, xi).estimator_weight(prob))
                })
                .sum::<f64>()
                / f64::from(n);
            assert!((mean - 1.0).abs() < 1e-3, "p {prob}: {mean}");
        }
        let p = params(1.0, 0.3);
        assert_eq!(p.estimator_weight(0.3), 0.0, "p must exceed ξ strictly");
        assert_eq!(p.estimator_weight(0.0), 0.0);
        assert_eq!(p.estimator_weight(f32::NAN), 0.0);
        assert_eq!(p.estimator_weight(0.5), 2.0);
        let tiny = params(1.0, 3e-8);
        assert!(tiny.estimator_weight(3.1e-8).is_finite());
    }

    #[test]
    fn invalid_parameters_are_errors() {
        for delta in [0.0, -1.0, f32::NAN, f32::INFINITY, 1e-40] {
            assert!(matches!(
                StochasticParams::new(delta, 0.5),
                Err(BoundsError::InvalidDelta(_))
            ));
        }
        for xi in [0.0, 1.0, -0.1, 1.5, f32::NAN, 1e-40] {
            assert!(matches!(
                StochasticParams::new(1e-3, xi),
                Err(BoundsError::InvalidXi(_))
            ));
        }
        assert!(StochasticParams::new(1e-9, 3e-8).is_ok());
        assert!(StochasticParams::new(1e3, 1.0 - 6e-8).is_ok());
    }
}
