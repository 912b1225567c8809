//! The GGX (Trowbridge-Reitz) microfacet distribution and its Smith masking function, for a
//! roughness α in (0, 1] (section 4.1).
use crate::lanes::Real;
use core::f32::consts::PI;

/// GGX normal distribution function, paper eq. (7):
/// `D(cos θm) = α² χ⁺(cos θm) / (π (α² cos² θm + sin² θm)²)`.
///
/// `sin² θm` is formed as `(1 - cos)(1 + cos)`, exact for the given `f32` cosine. Near the peak
/// of a very smooth lobe (α below about 1e-3) an `f32` cosine itself cannot resolve the angle;
/// callers that know `sin² θm` directly should use [`d_with_sin2`].
#[inline]
pub fn d(alpha: f32, cos_m: f32) -> f32 {
    d_with_sin2(alpha, cos_m, (1.0 - cos_m) * (1.0 + cos_m))
}

/// GGX normal distribution function, paper eq. (7), from both `cos θm` and `sin² θm` (e.g.
/// `|n × m|²`), which keeps full relative precision near θm = 0 for any α in (0, 1].
#[inline]
pub fn d_with_sin2(alpha: f32, cos_m: f32, sin2_m: f32) -> f32 {
    if cos_m <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let denom = a2 * cos_m * cos_m + sin2_m.max(0.0);
    a2 / (PI * denom * denom)
}

/// `G1_dist(ω) / |ω·n|` of paper eq. (8): `2 / (|cos| + sqrt((1-α²) cos² + α²))`.
/// Finite at grazing incidence (cos -> 0), where G1 itself goes to 0; equals 2/α there.
#[inline]
pub fn g1_over_cos(alpha: f32, cos_v: f32) -> f32 {
    g1_over_cos_lanes(alpha * alpha, cos_v.abs())
}

/// [`g1_over_cos`] written once for one `f32` and for lanes ([`crate::lanes`]), from α² and a
/// cosine c >= 0 (the scalar passes |c|): `2 / (c + sqrt((1 − α²) c² + α²))`, the same IEEE
/// operations in every lane.
#[inline(always)]
pub fn g1_over_cos_lanes<R: Real>(alpha_sq: R, cos: R) -> R {
    let one = R::splat(1.0);
    R::splat(2.0) / (cos + ((one - alpha_sq) * cos * cos + alpha_sq).sqrt())
}

/// Smith masking function for GGX, paper eq. (8):
/// `G1_dist(ω) = 2|ω·n| / (|ω·n| + sqrt((1-α²)(ω·n)² + α²))`.
#[inline]
pub fn g1(alpha: f32, cos_v: f32) -> f32 {
    cos_v.abs() * g1_over_cos(alpha, cos_v)
}

/// [`d_with_sin2`] (paper eq. 7) in `f64` for `a2 = α²`, `cos θm > 0` and `sin² θm`: the
/// quadratures that fit and test the SG lobes (`crate::sg`).
pub(crate) fn d_f64(a2: f64, cos_m: f64, sin2_m: f64) -> f64 {
    a2 / (core::f64::consts::PI * (a2 * cos_m * cos_m + sin2_m).powi(2))
}

/// [`g1`] (paper eq. 8) in `f64` for `a2 = α²` and `cos ≥ 0`.
pub(crate) fn g1_f64(a2: f64, cos_v: f64) -> f64 {
    2.0 * cos_v / (cos_v + ((1.0 - a2) * cos_v * cos_v + a2).sqrt())
}

/// The separable Smith masking-shadowing function `G2 = G1(ωi) G1(ωo)` (section 4.1, the form
/// used with eq. (6); any Smith form satisfies `G2 <= G1(ωi)`, the step to eq. (9)).
#[inline]
pub fn g2_separable(alpha: f32, cos_i: f32, cos_o: f32) -> f32 {
    g1(alpha, cos_i) * g1(alpha, cos_o)
}

/// Anisotropic GGX normal distribution function (Heitz 2014, "Understanding the
/// masking-shadowing function", eq. 85; glTF `KHR_materials_anisotropy`):
/// `D(m) = χ⁺(m·n) / (π α_t α_b ((m·t/α_t)² + (m·b/α_b)² + (m·n)²)²)` for a unit micro-normal
/// m with components `m_t`, `m_b`, `m_n` in the orthonormal frame (t, b, n). Equal to eq. (7)
/// where α_t = α_b.
#[inline]
pub fn d_anisotropic(alpha_t: f32, alpha_b: f32, m_t: f32, m_b: f32, m_n: f32) -> f32 {
    if m_n <= 0.0 {
        return 0.0;
    }
    let (x, y) = (m_t / alpha_t, m_b / alpha_b);
    let denom = x * x + y * y + m_n * m_n;
    1.0 / (PI * alpha_t * alpha_b * denom * denom)
}

/// `G1(ω) / |ω·n|` of the anisotropic Smith masking function (Heitz 2014, eq. 86):
/// `2 / (|ω_n| + sqrt(ω_n² + α_t² ω_t² + α_b² ω_b²))`, eq. (8) with α² sin²θ replaced by the
/// projected roughness `α_t² ω_t² + α_b² ω_b²` (ω's components in the frame (t, b, n)).
#[inline]
pub fn g1_over_cos_anisotropic(alpha_t: f32, alpha_b: f32, w_t: f32, w_b: f32, w_n: f32) -> f32 {
    let (x, y) = (alpha_t * w_t, alpha_b * w_b);
    let c = w_n.abs();
    2.0 / (c + (c * c + x * x + y * y).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI as PI64;

    const ALPHAS: [f32; 5] = [0.001, 0.01, 0.1, 0.5, 1.0];

    /// Polar angle of a GGX lobe parametrised by x in (0, 1): tan² θ = t = α² x / (1 - x).
    /// Returns (cos θ, sin² θ, dt/dx). The substitution puts the peak of width α² at x ~ 1/2.
    fn polar(alpha: f64, x: f64) -> (f64, f64, f64) {
        let a2 = alpha * alpha;
        let t = a2 * x / (1.0 - x);
        (
            1.0 / (1.0 + t).sqrt(),
            t / (1.0 + t),
            a2 / ((1.0 - x) * (1.0 - x)),
        )
    }

    /// ∫ D(cos θ) cos θ dω over the hemisphere, midpoint rule in x. With sin θ dθ =
    /// cos³θ dt / 2: the integrand is 2π · D cos⁴θ / 2 · dt/dx.
    fn projected_area(alpha: f32, eval: impl Fn(f64, f64) -> f32) -> f64 {
        let n = 4000;
        (0..n)
            .map(|k| {
                let (c, s2, jac) = polar(f64::from(alpha), (k as f64 + 0.5) / n as f64);
                PI64 * f64::from(eval(c, s2)) * c.powi(4) * jac / n as f64
            })
            .sum()
    }

    #[test]
    fn d_integrates_to_one_against_projected_area() {
        for alpha in ALPHAS {
            let i = projected_area(alpha, |c, s2| d_with_sin2(alpha, c as f32, s2 as f32));
            assert!((i - 1.0).abs() < 1e-5, "alpha {alpha}: {i}");
        }
        // The cosine-only form loses the peak for tiny α (f32 cosines near 1 are 6e-8 apart).
        for alpha in &ALPHAS[1..] {
            let i = projected_area(*alpha, |c, _| d(*alpha, c as f32));
            assert!((i - 1.0).abs() < 2e-3, "alpha {alpha}: {i}");
        }
    }

    #[test]
    fn d_matches_eq_7_pointwise() {
        for alpha in ALPHAS {
            assert!((d(alpha, 1.0) - 1.0 / (PI * alpha * alpha)).abs() <= 1e-6 * d(alpha, 1.0));
            assert!((d(alpha, 0.0)).abs() == 0.0 && d(alpha, -0.3) == 0.0);
            // Monotonically decreasing in θ for α <= 1 (used for eq. (11)).
            let mut prev = f32::INFINITY;
            for k in 0..=100 {
                let v = d(alpha, 1.0 - k as f32 / 100.0 * 0.999);
                assert!(v <= prev * (1.0 + 1e-6), "alpha {alpha}");
                prev = v;
            }
        }
        assert!((d(1.0, 0.3) - 1.0 / PI).abs() < 1e-6, "α = 1 is uniform");
    }

    /// G1 by eq. (8): |ωi·n| / ∫ D(m·n) max(ωi·m, 0) dm, over the hemisphere of microfacet
    /// normals (D vanishes below), φ in [0, π] doubled by symmetry. The polar angle is
    /// parametrised by y in (0, 1) through tan θ = α sqrt(1 − w²) / w, w = 1 − y, which spreads
    /// both the peak (width α) and the heavy tail of D over the interval with a bounded
    /// integrand: dm = sin θ cos² θ dτ dφ, dτ/dy = α / (w² sqrt(1 − w²)).
    fn g1_numeric(alpha: f32, cos_i: f64) -> f64 {
        let sin_i = (1.0 - cos_i * cos_i).sqrt();
        let a = f64::from(alpha);
        let (ny, nphi) = (800, 256);
        let mut sum = 0.0;
        for k in 0..ny {
            let w = 1.0 - (k as f64 + 0.5) / ny as f64;
            let root = (1.0 - w * w).sqrt();
            let tau = a * root / w;
            let c = 1.0 / (1.0 + tau * tau).sqrt();
            let (s, s2) = (tau * c, tau * tau / (1.0 + tau * tau));
            let jac = s * c * c * a / (w * w * root);
            let weight = f64::from(d_with_sin2(alpha, c as f32, s2 as f32)) * jac;
            for j in 0..nphi {
                let phi = (j as f64 + 0.5) / nphi as f64 * PI64;
                let proj = (sin_i * s * phi.cos() + cos_i * c).max(0.0);
                sum += 2.0 * weight * proj * PI64 / (ny as f64 * nphi as f64);
            }
        }
        cos_i / sum
    }

    #[test]
    fn g1_closed_form_matches_eq_8_integral() {
        for alpha in ALPHAS {
            for cos_i in [1.0, 0.8, 0.4, 0.1, 0.02] {
                let numeric = g1_numeric(alpha, cos_i);
                let closed = f64::from(g1(alpha, cos_i as f32));
                assert!(
                    (numeric - closed).abs() < 1e-3 * closed,
                    "alpha {alpha} cos {cos_i}: {numeric} vs {closed}"
                );
            }
        }
    }

    #[test]
    fn g1_limits_and_over_cos_consistency() {
        for alpha in ALPHAS {
            assert!((g1(alpha, 1.0) - 1.0).abs() < 1e-6);
            assert!((g1_over_cos(alpha, 0.0) - 2.0 / alpha).abs() < 1e-5 * 2.0 / alpha);
            for c in [1e-6f32, 0.3, 0.9] {
                assert!((g1(alpha, c) - c * g1_over_cos(alpha, c)).abs() < 1e-6);
                assert!(g1(alpha, c) <= 1.0 + 1e-6 && g1(alpha, c) > 0.0);
                assert_eq!(g1(alpha, -c), g1(alpha, c));
                assert_eq!(g2_separable(alpha, c, 0.5), g1(alpha, c) * g1(alpha, 0.5));
            }
        }
    }
}
