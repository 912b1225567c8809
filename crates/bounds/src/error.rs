//! The crate's error type: every out-of-domain input is reported as a value, never a panic,
//! NaN or infinity.
use core::fmt;
use glam::Vec3;

/// Why an input was rejected or a derived quantity could not be represented.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BoundsError {
    /// δ of eq. (2) must be a finite positive normal `f32`.
    InvalidDelta(f32),
    /// ξ of eq. (3) must be a normal `f32` in the open interval (0, 1).
    InvalidXi(f32),
    /// The GGX roughness α of eq. (7) must lie in (0, 1].
    InvalidAlpha(f32),
    /// Schlick's F0 (supplemental eq. (1)) must lie in [0, 1] in every channel.
    InvalidF0(Vec3),
    /// The relative index η of a dielectric (supplemental eq. (3)-(5)) must be finite and > 0.
    InvalidEta(f32),
    /// The named input has a NaN or infinite component.
    NotFinite(&'static str),
    /// The named input has a negative component.
    Negative(&'static str),
    /// The named direction is not of unit length (tolerance 1e-3 on the length).
    NotUnit(&'static str),
    /// The named direction is not perpendicular to the normal (tolerance 1e-4 on the cosine,
    /// less for a sharp anisotropic lobe: `GlossyLobe::with_anisotropy`).
    NotPerpendicular(&'static str),
    /// A matrix that must be a rotation is not orthonormal with determinant +1 (tolerance 1e-4).
    NotRotation,
    /// Ellipsoid semi-axes must be all positive, or all zero for an empty bound.
    InvalidSemiAxes(Vec3),
    /// A tile frustum needs finite bounds with min <= max for the rectangle and the depths.
    InvalidFrustum,
    /// The named derived quantity does not fit in an `f32` (the inputs are extreme).
    Overflow(&'static str),
}

impl fmt::Display for BoundsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidDelta(d) => write!(f, "delta must be a finite positive float, got {d}"),
            Self::InvalidXi(x) => write!(f, "xi must lie in the open interval (0, 1), got {x}"),
            Self::InvalidAlpha(a) => write!(f, "GGX roughness alpha must lie in (0, 1], got {a}"),
            Self::InvalidF0(f0) => write!(f, "Schlick F0 must lie in [0, 1] per channel, got {f0}"),
            Self::InvalidEta(e) => write!(f, "relative index eta must be finite and > 0, got {e}"),
            Self::NotFinite(what) => write!(f, "{what} has a NaN or infinite component"),
            Self::Negative(what) => write!(f, "{what} has a negative component"),
            Self::NotUnit(what) => write!(f, "{what} is not a unit vector"),
            Self::NotPerpendicular(what) => write!(f, "{what} is not perpendicular to the normal"),
            Self::NotRotation => write!(f, "matrix is not a rotation (orthonormal, det +1)"),
            Self::InvalidSemiAxes(a) => {
                write!(f, "semi-axes must be all positive or all zero, got {a}")
            }
            Self::InvalidFrustum => {
                write!(f, "tile frustum needs finite bounds with min <= max")
            }
            Self::Overflow(what) => write!(f, "{what} overflows f32 for these inputs"),
        }
    }
}

impl std::error::Error for BoundsError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_problem() {
        assert!(BoundsError::InvalidXi(1.0).to_string().contains("xi"));
        assert!(BoundsError::NotUnit("normal")
            .to_string()
            .contains("normal"));
        let boxed: Box<dyn std::error::Error> = Box::new(BoundsError::Overflow("r"));
        assert!(boxed.to_string().contains('r'));
    }
}
