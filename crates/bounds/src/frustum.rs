//! The frustum of a screen tile between two depths, the region tested by tiled culling
//! (Modified HalfZ, section 5.1).
use crate::aabb::Aabb;
use crate::error::BoundsError;
use glam::{Vec2, Vec3};

/// The view-space frustum `{ z (u, v, 1) : (u, v) in [rect_min, rect_max], z in [z_min,
/// z_max] }` of a screen tile: its rectangle at unit depth (the tile corners unprojected to
/// z = 1) swept between two depths. Renderer-agnostic: with a camera looking down −z, pass
/// negative depths and the rectangle at z = 1 of the same rays, i.e. (x/z, y/z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileFrustum {
    rect_min: Vec2,
    rect_max: Vec2,
    z_min: f32,
    z_max: f32,
}

impl TileFrustum {
    /// Validates a tile frustum of section 5.1: finite bounds, `rect_min <= rect_max`,
    /// `z_min <= z_max`.
    pub fn new(
        rect_min: Vec2,
        rect_max: Vec2,
        z_min: f32,
        z_max: f32,
    ) -> Result<Self, BoundsError> {
        let finite =
            rect_min.is_finite() && rect_max.is_finite() && z_min.is_finite() && z_max.is_finite();
        if finite && rect_min.cmple(rect_max).all() && z_min <= z_max {
            Ok(Self {
                rect_min,
                rect_max,
                z_min,
                z_max,
            })
        } else {
            Err(BoundsError::InvalidFrustum)
        }
    }

    /// The lower corner of the tile rectangle at unit depth (section 5.1).
    #[inline]
    pub fn rect_min(&self) -> Vec2 {
        self.rect_min
    }

    /// The upper corner of the tile rectangle at unit depth (section 5.1).
    #[inline]
    pub fn rect_max(&self) -> Vec2 {
        self.rect_max
    }

    /// The near end of the depth range (section 5.1).
    #[inline]
    pub fn z_min(&self) -> f32 {
        self.z_min
    }

    /// The far end of the depth range (section 5.1).
    #[inline]
    pub fn z_max(&self) -> f32 {
        self.z_max
    }

    /// The view-space box around the frustum, the rough culling volume of Modified HalfZ
    /// (section 5.1; supplemental listing 2 with the rectangle at z = 1).
    #[inline]
    pub fn aabb(&self) -> Aabb {
        Aabb::frustum(self.rect_min, self.rect_max, 1.0, self.z_min, self.z_max)
    }

    /// Whether the view-space `point` lies in the closed frustum (section 5.1), without
    /// division: x lies between u_min z and u_max z, and likewise y.
    #[inline]
    pub fn contains(&self, point: Vec3) -> bool {
        let z = point.z;
        let (a, b) = (self.rect_min * z, self.rect_max * z);
        let xy = Vec2::new(point.x, point.y);
        z >= self.z_min && z <= self.z_max && xy.cmpge(a.min(b)).all() && xy.cmple(a.max(b)).all()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contains_matches_definition() {
        let f = TileFrustum::new(Vec2::new(-0.1, 0.2), Vec2::new(0.3, 0.4), 2.0, 5.0).unwrap();
        assert!(f.contains(Vec3::new(0.0, 0.3, 1.0) * 3.0));
        assert!(f.contains(Vec3::new(-0.1, 0.4, 1.0) * 5.0), "corner");
        assert!(!f.contains(Vec3::new(0.0, 0.3, 1.0) * 5.5), "too deep");
        assert!(
            !f.contains(Vec3::new(0.31, 0.3, 1.0) * 3.0),
            "outside the rectangle"
        );
        let bx = f.aabb();
        assert!(
            bx.contains(Vec3::new(-0.1, 0.2, 1.0) * 5.0)
                && bx.contains(Vec3::new(0.3, 0.4, 1.0) * 2.0)
        );
        // A −z camera: negative depths mirror x and y through the apex.
        let rh = TileFrustum::new(Vec2::new(-0.1, 0.2), Vec2::new(0.3, 0.4), -5.0, -2.0).unwrap();
        assert!(rh.contains(Vec3::new(0.0, 0.3, 1.0) * -3.0));
        assert!(rh.aabb().contains(Vec3::new(0.0, 0.3, 1.0) * -3.0));
    }

    #[test]
    fn invalid_frustum_is_an_error() {
        let (a, b) = (Vec2::ZERO, Vec2::ONE);
        assert!(TileFrustum::new(b, a, 1.0, 2.0).is_err());
        assert!(TileFrustum::new(a, b, 2.0, 1.0).is_err());
        assert!(TileFrustum::new(a, Vec2::new(f32::NAN, 1.0), 1.0, 2.0).is_err());
        assert!(TileFrustum::new(a, b, 1.0, f32::INFINITY).is_err());
        assert!(TileFrustum::new(a, b, 1.0, 1.0).is_ok());
    }
}
