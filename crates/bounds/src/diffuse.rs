//! A diffuse VPL: the Lambertian lobe of its radiant intensity (eq. 4 with f = kd/π) and its
//! largest range (eq. 5 along the normal), the scale of its bounding sphere (section 6).
use crate::check;
use crate::error::BoundsError;
use crate::stochastic::StochasticParams;
use core::f32::consts::FRAC_1_PI;
use glam::Vec3;

/// A Lambertian VPL, validated: finite position q, unit normal n, and the scalar reflected
/// flux Φk = scalar(Φ kd) (largest channel, see
/// [`scalar_intensity`](crate::stochastic::scalar_intensity)) from finite
/// non-negative RGB flux Φ and diffuse reflectance kd.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiffuseLobe {
    position: Vec3,
    normal: Vec3,
    reflected_flux: f32,
}

impl DiffuseLobe {
    /// Validates the VPL of eq. (4) with f = kd/π and stores Φk = scalar(Φ kd) (section 6).
    pub fn new(position: Vec3, normal: Vec3, flux: Vec3, kd: Vec3) -> Result<Self, BoundsError> {
        let flux = check::non_negative(flux, "flux")?;
        let kd = check::non_negative(kd, "kd")?;
        Ok(Self {
            position: check::finite(position, "position")?,
            normal: check::unit(normal, "normal")?,
            // scalar_intensity (largest channel) of Φ kd, formed in f64 so it cannot overflow.
            reflected_flux: check::fits(
                (flux.as_dvec3() * kd.as_dvec3()).max_element(),
                "flux * kd",
            )?,
        })
    }

    /// The VPL position q of section 6.
    #[inline]
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// The normal n of eq. (4) and section 6.
    #[inline]
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// Φk = scalar(Φ kd) of section 6.
    #[inline]
    pub fn reflected_flux(&self) -> f32 {
        self.reflected_flux
    }

    /// The scalar radiant intensity of eq. (4) with f = kd/π: `I(ωo) = Φk/π max(ωo·n, 0)`.
    /// `omega_o` is the unit direction from the VPL to the shading point (not validated).
    #[inline]
    pub fn intensity(&self, omega_o: Vec3) -> f32 {
        self.reflected_flux * FRAC_1_PI * self.normal.dot(omega_o).max(0.0)
    }

    /// The range of eq. (5) along the normal, `sqrt(Φk / (π δ ξ))`: the scale of the diffuse
    /// bounding sphere of section 6 (l_max(ωo) = this · sqrt(max(ωo·n, 0))). Computed in f64;
    /// [`BoundsError::Overflow`] if it does not fit in an `f32`.
    pub fn peak_range(&self, params: &StochasticParams) -> Result<f32, BoundsError> {
        let denominator =
            core::f64::consts::PI * f64::from(params.delta()) * f64::from(params.xi());
        check::fits(
            (f64::from(self.reflected_flux) / denominator).sqrt(),
            "diffuse range",
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intensity_and_range_are_eq_4_and_5() {
        let l = DiffuseLobe::new(
            Vec3::ONE,
            Vec3::Y,
            Vec3::new(2.0, 1.0, 1.0),
            Vec3::splat(0.5),
        )
        .unwrap();
        assert_eq!(l.reflected_flux(), 1.0);
        assert!((l.intensity(Vec3::Y) - FRAC_1_PI).abs() < 1e-7);
        assert_eq!(l.intensity(-Vec3::Y), 0.0);
        let params = StochasticParams::new(1e-3, 0.5).unwrap();
        let r = l.peak_range(&params).unwrap();
        assert!((r - params.range(l.intensity(Vec3::Y))).abs() < 1e-5 * r);
    }

    #[test]
    fn invalid_inputs_are_errors() {
        let n = Vec3::Z;
        assert_eq!(
            DiffuseLobe::new(Vec3::ZERO, n, Vec3::ONE, Vec3::new(0.5, -0.1, 0.0)),
            Err(BoundsError::Negative("kd"))
        );
        assert_eq!(
            DiffuseLobe::new(Vec3::ZERO, Vec3::ZERO, Vec3::ONE, Vec3::ONE),
            Err(BoundsError::NotUnit("normal"))
        );
        assert_eq!(
            DiffuseLobe::new(Vec3::ZERO, n, Vec3::splat(f32::NAN), Vec3::ONE),
            Err(BoundsError::NotFinite("flux"))
        );
        assert_eq!(
            DiffuseLobe::new(Vec3::ZERO, n, Vec3::splat(f32::MAX), Vec3::splat(2.0)),
            Err(BoundsError::Overflow("flux * kd"))
        );
    }
}
