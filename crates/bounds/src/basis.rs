//! Orthonormal frames around a unit vector, for directions where the spheroid's ω_w of
//! eq. (14) is undefined (normal incidence, ω_u = n).
use crate::check;
use crate::error::BoundsError;
use glam::Vec3;

/// A right-handed orthonormal basis (x, y, z), x × y = z, around a given unit vector z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Basis {
    pub x: Vec3,
    pub y: Vec3,
    pub z: Vec3,
}

impl Basis {
    /// The frame around `z` of Duff et al. 2017, "Building an Orthonormal Basis, Revisited"
    /// (JCGT 6(1)): branch-free, accurate for every direction including z = −e_z, and
    /// continuous except where z.z changes sign. `z` must be finite and of unit length (within 1e-3; it is renormalised).
    pub fn new(z: Vec3) -> Result<Self, BoundsError> {
        Ok(Self::from_unit(check::unit(z, "frame axis")?))
    }

    /// [`Basis::new`] for an already validated unit vector.
    #[inline]
    pub(crate) fn from_unit(z: Vec3) -> Self {
        let sign = 1.0f32.copysign(z.z);
        let a = -1.0 / (sign + z.z);
        let b = z.x * z.y * a;
        Self {
            x: Vec3::new(1.0 + sign * z.x * z.x * a, sign * b, -sign * z.x),
            y: Vec3::new(b, sign + z.y * z.y * a, -z.y),
            z,
        }
    }

    /// Local coordinates (along x, y, z) to world space (Duff et al. 2017 basis).
    #[inline]
    pub fn to_world(&self, local: Vec3) -> Vec3 {
        self.x * local.x + self.y * local.y + self.z * local.z
    }

    /// World space to local coordinates (along x, y, z) (Duff et al. 2017 basis).
    #[inline]
    pub fn to_local(&self, world: Vec3) -> Vec3 {
        Vec3::new(self.x.dot(world), self.y.dot(world), self.z.dot(world))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;

    fn assert_orthonormal(f: &Basis) {
        for (a, b) in [(f.x, f.y), (f.y, f.z), (f.z, f.x)] {
            assert!(a.dot(b).abs() < 1e-6, "{f:?}");
        }
        for v in [f.x, f.y, f.z] {
            assert!((v.length() - 1.0).abs() < 1e-6, "{f:?}");
        }
        assert!(
            (f.x.cross(f.y) - f.z).length() < 1e-6,
            "right-handed: {f:?}"
        );
    }

    #[test]
    fn orthonormal_everywhere_including_poles() {
        let mut rng = Rng::new(3);
        let mut axes: Vec<Vec3> = (0..2000).map(|_| rng.unit()).collect();
        axes.extend([Vec3::Z, -Vec3::Z, Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y]);
        axes.push(Vec3::new(1e-4, 0.0, -1.0).normalize());
        axes.push(Vec3::new(0.0, 1e-7, -1.0).normalize());
        axes.push(Vec3::new(3e-4, -2e-4, 1.0).normalize());
        for z in axes {
            let f = Basis::new(z).unwrap();
            assert_orthonormal(&f);
            let v = Vec3::new(0.3, -0.5, 0.8);
            assert!((f.to_local(f.to_world(v)) - v).length() < 1e-6);
        }
        assert_orthonormal(&Basis::new(Vec3::new(1.0, 0.0, -0.0)).unwrap());
    }

    #[test]
    fn invalid_axis_is_an_error() {
        assert_eq!(
            Basis::new(Vec3::ZERO),
            Err(BoundsError::NotUnit("frame axis"))
        );
        assert_eq!(
            Basis::new(Vec3::NAN),
            Err(BoundsError::NotFinite("frame axis"))
        );
    }
}
