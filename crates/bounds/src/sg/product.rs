//! The product of two spherical Gaussians, itself a spherical Gaussian (VSGL eq. 5).
use crate::check;
use crate::error::BoundsError;
use crate::sg::lobe::SphericalGaussian;
use glam::DVec3;

/// The combined parameters of two lobes: `λ1 ξ1 + λ2 ξ2`, its length `d` (the product's
/// sharpness) and the log of the amplitude factor `d − λ1 − λ2 ≤ 0`, all in `f64`.
pub(crate) struct Merged {
    pub(crate) axis_sum: DVec3,
    pub(crate) sharpness: f64,
    pub(crate) log_scale: f64,
}

impl Merged {
    /// With `|λ1ξ1 + λ2ξ2|² = (λ1 + λ2)² − λ1 λ2 |ξ1 − ξ2|²`, the exponent is formed as
    /// `d − λ1 − λ2 = −λ1 λ2 |ξ1 − ξ2|² / (d + λ1 + λ2)`: no cancellation for nearby sharp
    /// lobes, exactly 0 for equal axes. The axes are renormalised in `f64` first.
    pub(crate) fn of(a: &SphericalGaussian, b: &SphericalGaussian) -> Self {
        let (la, lb) = (f64::from(a.sharpness), f64::from(b.sharpness));
        let (xa, xb) = (a.axis.as_dvec3().normalize(), b.axis.as_dvec3().normalize());
        let axis_sum = xa * la + xb * lb;
        let sharpness = axis_sum.length();
        let total = sharpness + la + lb;
        let log_scale = if total > 0.0 {
            -la * lb * (xa - xb).length_squared() / total
        } else {
            0.0
        };
        Self {
            axis_sum,
            sharpness,
            log_scale,
        }
    }
}

impl SphericalGaussian {
    /// The product `c1 G(ω; ξ1, λ1) c2 G(ω; ξ2, λ2) = c G(ω; ξ, λ)` (the form of VSGL eq. 5):
    /// `ξ = (λ1ξ1 + λ2ξ2)/|λ1ξ1 + λ2ξ2|`, `λ = |λ1ξ1 + λ2ξ2|`, `c = c1 c2 e^{λ − λ1 − λ2}`.
    /// When `λ1ξ1 + λ2ξ2` vanishes (opposite axes of equal sharpness, or two constant lobes)
    /// the product is the constant `c` and the axis is `ξ1`. Fails with
    /// [`BoundsError::Overflow`] if the sharpness or amplitude exceeds the `f32` range.
    pub fn product(&self, other: &Self) -> Result<Self, BoundsError> {
        let m = Merged::of(self, other);
        let sharpness = check::fits(m.sharpness, "SG product sharpness")?;
        let amplitude = check::fits(
            f64::from(self.amplitude) * f64::from(other.amplitude) * m.log_scale.exp(),
            "SG product amplitude",
        )?;
        let axis = if m.sharpness > 0.0 {
            (m.axis_sum / m.sharpness).as_vec3().normalize()
        } else {
            self.axis
        };
        Ok(Self {
            axis: if axis.is_finite() { axis } else { self.axis },
            sharpness: if m.sharpness > 0.0 { sharpness } else { 0.0 },
            amplitude,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;
    use glam::Vec3;

    #[test]
    fn product_equals_pointwise_product() {
        let mut rng = Rng::new(51);
        for _ in 0..500 {
            let a = SphericalGaussian::new(rng.unit(), 10f32.powf(rng.range(-3.0, 3.0)), rng.f32())
                .unwrap();
            let b = SphericalGaussian::new(rng.unit(), 10f32.powf(rng.range(-3.0, 3.0)), rng.f32())
                .unwrap();
            let p = a.product(&b).unwrap();
            assert!((p.axis.length() - 1.0).abs() < 1e-6);
            for _ in 0..20 {
                let w = rng.unit();
                let want = a.eval(w) * b.eval(w);
                let got = p.eval(w);
                assert!(
                    (got - want).abs() <= 1e-3 * want + 1e-30,
                    "{a:?} {b:?} {w}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn product_degenerate_and_overflowing_cases() {
        let z = SphericalGaussian::new(Vec3::Z, 2.0, 3.0).unwrap();
        let p = z
            .product(&SphericalGaussian {
                axis: -Vec3::Z,
                ..z
            })
            .unwrap();
        assert_eq!((p.axis, p.sharpness), (Vec3::Z, 0.0));
        assert!((p.amplitude - 9.0 * (-4f32).exp()).abs() < 1e-6);
        let sharp = SphericalGaussian::new(Vec3::Z, f32::MAX, 1.0).unwrap();
        assert_eq!(
            sharp.product(&sharp),
            Err(BoundsError::Overflow("SG product sharpness"))
        );
        let bright = SphericalGaussian::new(Vec3::Z, 1.0, f32::MAX).unwrap();
        assert_eq!(
            bright.product(&bright),
            Err(BoundsError::Overflow("SG product amplitude"))
        );
        let far = SphericalGaussian::new(Vec3::X, 1e30, 1.0).unwrap();
        let q = far
            .product(&SphericalGaussian {
                axis: Vec3::Y,
                ..far
            })
            .unwrap();
        assert_eq!(q.amplitude, 0.0);
        assert!(q.axis.is_finite() && q.sharpness.is_finite());
    }
}
