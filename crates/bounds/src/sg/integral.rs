//! The integral of a spherical Gaussian over the sphere (VSGL section 2.2) and the inner
//! product of two of them.
use crate::sg::lobe::SphericalGaussian;
use crate::sg::product::Merged;
use core::f64::consts::{PI, TAU};

/// `A(λ) = ∫ G(ω; ξ, λ) dω = 2π/λ (1 − e^{−2λ})` (VSGL section 2.2), evaluated as
/// `−2π expm1(−2λ)/λ`: no cancellation for small λ, the limit 4π (a constant lobe) at λ = 0 and
/// `2π/λ` without overflow for huge λ. Negative or NaN sharpness is treated as 0.
#[inline]
pub fn sg_integral(sharpness: f32) -> f32 {
    integral_f64(f64::from(sharpness)) as f32
}

/// [`sg_integral`] in `f64`, for the combined sharpness of two lobes; above λ = 20,
/// `1 − e^{−2λ}` is 1 to `f64` precision.
pub(crate) fn integral_f64(sharpness: f64) -> f64 {
    let l = sharpness.max(0.0);
    if l == 0.0 {
        4.0 * PI
    } else if l > 20.0 {
        TAU / l
    } else {
        -TAU * (-2.0 * l).exp_m1() / l
    }
}

impl SphericalGaussian {
    /// The inner product `∫ c1 G(ω; ξ1, λ1) c2 G(ω; ξ2, λ2) dω = c1 c2 e^{d − λ1 − λ2} A(d)`,
    /// `d = |λ1 ξ1 + λ2 ξ2|`: the integral of the product lobe (VSGL eq. 5, see
    /// [`SphericalGaussian::product`]). Computed in `f64`; the exponent `d − λ1 − λ2` is formed
    /// without cancellation, so sharp lobes far apart give 0 rather than NaN. A value beyond
    /// the `f32` range (only for amplitudes near it) saturates at `f32::MAX`.
    pub fn inner_product(&self, other: &Self) -> f32 {
        let m = Merged::of(self, other);
        let value = f64::from(self.amplitude)
            * f64::from(other.amplitude)
            * m.log_scale.exp()
            * integral_f64(m.sharpness);
        value.min(f64::from(f32::MAX)) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sg::quadrature::{eval64, sphere_integral, width};
    use crate::test_util::{log_angles, Rng};
    use glam::Vec3;

    #[test]
    fn integral_matches_quadrature_from_1e_minus_4_to_1e4() {
        let mut worst = 0.0f64;
        for l in log_angles(1e-4, 1e4, 33) {
            let axis = glam::DVec3::new(0.3, -0.5, 0.8).normalize();
            let numeric = sphere_integral(axis, width(l), |w| (l * (w.dot(axis) - 1.0)).exp());
            let closed = f64::from(sg_integral(l as f32));
            worst = worst.max((closed / numeric - 1.0).abs());
        }
        // Measured: 7.7e-8 (the f32 rounding of the result).
        assert!(worst < 1e-6, "{worst}");
    }

    #[test]
    fn integral_limits_are_finite() {
        assert_eq!(sg_integral(0.0), 4.0 * core::f32::consts::PI);
        assert!((sg_integral(1e-30) / (4.0 * core::f32::consts::PI) - 1.0).abs() < 1e-6);
        assert!((sg_integral(1e-45) / (4.0 * core::f32::consts::PI) - 1.0).abs() < 1e-6);
        for l in [1e4f32, 1e20, f32::MAX] {
            let want = core::f32::consts::TAU / l;
            assert!((sg_integral(l) / want - 1.0).abs() < 1e-6, "{l}");
        }
        assert_eq!(sg_integral(-1.0), sg_integral(0.0));
        assert_eq!(sg_integral(f32::NAN), sg_integral(0.0));
    }

    #[test]
    fn inner_product_matches_quadrature() {
        let mut rng = Rng::new(41);
        let mut worst = 0.0f64;
        for _ in 0..60 {
            let a = SphericalGaussian::new(rng.unit(), 10f32.powf(rng.range(-2.0, 3.0)), rng.f32())
                .unwrap();
            let b = SphericalGaussian::new(rng.unit(), 10f32.powf(rng.range(-2.0, 3.0)), rng.f32())
                .unwrap();
            let p = a.product(&b).unwrap();
            let numeric = sphere_integral(p.axis.as_dvec3(), width(f64::from(p.sharpness)), |w| {
                eval64(&a, w) * eval64(&b, w)
            });
            let closed = f64::from(a.inner_product(&b));
            let scale = f64::from(a.amplitude * b.amplitude) * 1e-30;
            worst = worst.max((closed - numeric).abs() / (numeric + scale));
        }
        // Measured: 5.6e-8 (the f32 rounding of the result).
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn inner_product_extremes_are_finite() {
        let z = SphericalGaussian::new(Vec3::Z, 1e30, 1.0).unwrap();
        let x = SphericalGaussian::new(Vec3::X, 1e30, 1.0).unwrap();
        assert_eq!(z.inner_product(&x), 0.0);
        let zz = z.inner_product(&z);
        assert!(
            (zz / (core::f32::consts::PI / 1e30) - 1.0).abs() < 1e-6,
            "{zz}"
        );
        let flat = SphericalGaussian::new(Vec3::Z, 0.0, 1.0).unwrap();
        assert_eq!(flat.inner_product(&flat), 4.0 * core::f32::consts::PI);
        let minus = SphericalGaussian::new(-Vec3::Z, 3.0, 1.0).unwrap();
        let opposite = SphericalGaussian {
            sharpness: 3.0,
            ..z
        }
        .inner_product(&minus);
        assert!((opposite / (4.0 * core::f32::consts::PI * (-6f32).exp()) - 1.0).abs() < 1e-5);
        let huge = SphericalGaussian::new(Vec3::Z, 0.0, f32::MAX).unwrap();
        assert_eq!(huge.inner_product(&huge), f32::MAX);
    }
}
