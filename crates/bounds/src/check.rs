//! Input validation shared by the constructors (private to the crate).
use crate::error::BoundsError;
use crate::fresnel::Fresnel;
use glam::Vec3;

/// Largest accepted deviation of a direction's length from 1.
pub(crate) const UNIT_TOLERANCE: f32 = 1e-3;

/// `v` if all components are finite.
pub(crate) fn finite(v: Vec3, what: &'static str) -> Result<Vec3, BoundsError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(BoundsError::NotFinite(what))
    }
}

/// `v` renormalised, if it is finite and of unit length within [`UNIT_TOLERANCE`].
pub(crate) fn unit(v: Vec3, what: &'static str) -> Result<Vec3, BoundsError> {
    let len = finite(v, what)?.length();
    if (len - 1.0).abs() <= UNIT_TOLERANCE {
        Ok(v / len)
    } else {
        Err(BoundsError::NotUnit(what))
    }
}

/// `v` if all components are finite and >= 0.
pub(crate) fn non_negative(v: Vec3, what: &'static str) -> Result<Vec3, BoundsError> {
    if finite(v, what)?.min_element() >= 0.0 {
        Ok(v)
    } else {
        Err(BoundsError::Negative(what))
    }
}

/// `alpha` if it lies in (0, 1] (NaN is rejected).
pub(crate) fn alpha(alpha: f32) -> Result<f32, BoundsError> {
    if alpha > 0.0 && alpha <= 1.0 {
        Ok(alpha)
    } else {
        Err(BoundsError::InvalidAlpha(alpha))
    }
}

/// `fresnel` if F0 lies in [0, 1] per channel (Schlick) or η is finite and positive (dielectric).
pub(crate) fn fresnel(fresnel: Fresnel) -> Result<Fresnel, BoundsError> {
    match fresnel {
        Fresnel::Schlick(f0) if f0.cmpge(Vec3::ZERO).all() && f0.cmple(Vec3::ONE).all() => {
            Ok(fresnel)
        }
        Fresnel::Schlick(f0) => Err(BoundsError::InvalidF0(f0)),
        Fresnel::Dielectric(eta) if eta > 0.0 && eta.is_finite() => Ok(fresnel),
        Fresnel::Dielectric(eta) => Err(BoundsError::InvalidEta(eta)),
    }
}

/// `x` as an `f32` if it is representable (finite) there.
pub(crate) fn fits(x: f64, what: &'static str) -> Result<f32, BoundsError> {
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(BoundsError::Overflow(what))
    }
}

/// `v` if all components are finite; a derived quantity, so failure is an overflow.
pub(crate) fn fits_vec(v: Vec3, what: &'static str) -> Result<Vec3, BoundsError> {
    finite(v, what).map_err(|_| BoundsError::Overflow(what))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_out_of_domain_values() {
        assert!(unit(Vec3::new(0.0, 0.0, 1.0005), "n").is_ok());
        assert_eq!(unit(Vec3::ZERO, "n"), Err(BoundsError::NotUnit("n")));
        assert_eq!(unit(Vec3::NAN, "n"), Err(BoundsError::NotFinite("n")));
        assert_eq!(
            unit(Vec3::splat(f32::INFINITY), "n"),
            Err(BoundsError::NotFinite("n"))
        );
        assert_eq!(
            non_negative(Vec3::new(1.0, -0.1, 0.0), "flux"),
            Err(BoundsError::Negative("flux"))
        );
        for a in [0.0, -0.5, 1.0001, f32::NAN, f32::INFINITY] {
            assert_eq!(alpha(a).map_err(|_| ()), Err(()), "alpha {a}");
        }
        assert!(alpha(1.0).is_ok() && alpha(1e-4).is_ok());
        assert!(fresnel(Fresnel::Schlick(Vec3::new(0.0, 1.0, 0.5))).is_ok());
        assert!(fresnel(Fresnel::Schlick(Vec3::new(0.0, 1.01, 0.5))).is_err());
        assert!(fresnel(Fresnel::Schlick(Vec3::new(f32::NAN, 0.5, 0.5))).is_err());
        for eta in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(fresnel(Fresnel::Dielectric(eta)).is_err(), "eta {eta}");
        }
        assert_eq!(fits(1e39, "r"), Err(BoundsError::Overflow("r")));
        assert_eq!(fits(2.5, "r"), Ok(2.5));
    }
}
