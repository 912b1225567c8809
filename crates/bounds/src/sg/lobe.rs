//! The spherical Gaussian lobe of VSGL section 2.2, with its amplitude.
use crate::check;
use crate::error::BoundsError;
use crate::sg::integral::sg_integral;
use glam::Vec3;

/// `c G(ω; ξ, λ) = c exp(λ(ω·ξ − 1))`: the spherical Gaussian of VSGL section 2.2 (axis ξ,
/// sharpness λ ≥ 0) scaled by an amplitude c ≥ 0.
///
/// The fields are public for reading; [`SphericalGaussian::new`] and the operations of this
/// module keep them valid (unit axis, finite non-negative sharpness and amplitude).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphericalGaussian {
    /// The lobe axis ξ (unit length).
    pub axis: Vec3,
    /// The sharpness λ (the inverse variance of VSGL section 2.2); 0 is a constant lobe.
    pub sharpness: f32,
    /// The amplitude c, the value at the axis.
    pub amplitude: f32,
}

impl SphericalGaussian {
    /// A lobe from its axis (unit within 1e-3, renormalised), sharpness and amplitude (both
    /// finite and non-negative).
    pub fn new(axis: Vec3, sharpness: f32, amplitude: f32) -> Result<Self, BoundsError> {
        let axis = check::unit(axis, "SG axis")?;
        let sharpness = non_negative(sharpness, "SG sharpness")?;
        let amplitude = non_negative(amplitude, "SG amplitude")?;
        Ok(Self {
            axis,
            sharpness,
            amplitude,
        })
    }

    /// The normalized lobe `G(ω; ξ, λ) / A(λ)` of VSGL section 2.2 (unit integral).
    pub fn normalized(axis: Vec3, sharpness: f32) -> Result<Self, BoundsError> {
        Self::new(axis, sharpness, 1.0).map(|sg| sg.to_normalized())
    }

    /// The value `c exp(λ(ω·ξ − 1))` at the unit direction `omega`, evaluated as
    /// `c exp(−λ |ω − ξ|² / 2)` (equal for unit vectors; the paper's `g(‖ω − ξ‖, 1/λ)` form),
    /// which keeps full precision near the axis of a sharp lobe.
    #[inline]
    pub fn eval(&self, omega: Vec3) -> f32 {
        self.amplitude * (-0.5 * self.sharpness * (omega - self.axis).length_squared()).exp()
    }

    /// The integral over the sphere, `c A(λ)` (VSGL section 2.2).
    #[inline]
    pub fn integral(&self) -> f32 {
        self.amplitude * sg_integral(self.sharpness)
    }

    /// The same lobe with unit integral: amplitude `1 / A(λ)` (VSGL section 2.2).
    #[inline]
    pub fn to_normalized(self) -> Self {
        Self {
            amplitude: 1.0 / sg_integral(self.sharpness),
            ..self
        }
    }

    /// The lobe with its amplitude multiplied by `factor` (finite and non-negative).
    pub fn scaled(self, factor: f32) -> Result<Self, BoundsError> {
        let factor = non_negative(factor, "SG scale factor")?;
        let amplitude = self.amplitude * factor;
        if amplitude.is_finite() {
            Ok(Self { amplitude, ..self })
        } else {
            Err(BoundsError::Overflow("SG amplitude"))
        }
    }
}

/// `x` if it is finite and >= 0.
fn non_negative(x: f32, what: &'static str) -> Result<f32, BoundsError> {
    check::non_negative(Vec3::splat(x), what).map(|_| x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;

    #[test]
    fn eval_matches_the_dot_product_form() {
        let mut rng = Rng::new(31);
        for _ in 0..1000 {
            let sg = SphericalGaussian::new(rng.unit(), rng.range(0.0, 50.0), rng.f32()).unwrap();
            let w = rng.unit();
            let want = sg.amplitude * (sg.sharpness * (w.dot(sg.axis) - 1.0)).exp();
            assert!(
                (sg.eval(w) - want).abs() <= 1e-5 * sg.amplitude,
                "{sg:?} {w}"
            );
        }
        // Sharp lobes: exact on the axis, e^{-1/2} one standard deviation away.
        let sg = SphericalGaussian::new(Vec3::Z, 1e8, 2.0).unwrap();
        assert_eq!(sg.eval(Vec3::Z), 2.0);
        let w = Vec3::new(1e-4f32.sin(), 0.0, 1e-4f32.cos());
        assert!((sg.eval(w) / 2.0 - (-0.5f32).exp()).abs() < 1e-3);
    }

    #[test]
    fn validation_and_scaling() {
        assert!(SphericalGaussian::new(Vec3::ZERO, 1.0, 1.0).is_err());
        for bad in [-1.0, f32::NAN, f32::INFINITY] {
            assert!(SphericalGaussian::new(Vec3::Z, bad, 1.0).is_err(), "{bad}");
            assert!(SphericalGaussian::new(Vec3::Z, 1.0, bad).is_err(), "{bad}");
        }
        let sg = SphericalGaussian::new(Vec3::X, 3.0, 2.0).unwrap();
        assert_eq!(sg.scaled(0.5).unwrap().amplitude, 1.0);
        assert!(sg.scaled(-1.0).is_err());
        assert_eq!(
            sg.scaled(f32::MAX),
            Err(BoundsError::Overflow("SG amplitude"))
        );
        let n = SphericalGaussian::normalized(Vec3::Y, 3.0).unwrap();
        assert!((n.integral() - 1.0).abs() < 1e-6);
        assert_eq!(sg.to_normalized(), SphericalGaussian { axis: Vec3::X, ..n });
    }
}
