//! The stretched and rotated test space of a bounding ellipsoid (eq. 16-17): the linear map
//! BS that turns the view-space ellipsoid into a unit sphere and keeps depth planes
//! perpendicular to the z-axis, so tiled culling can test a sphere against a box.
use crate::aabb::Aabb;
use crate::error::BoundsError;
use crate::frustum::TileFrustum;
use crate::spheroid::Spheroid;
use glam::{Affine3A, Mat3, Vec2, Vec3};

/// Largest accepted |RᵀR − I| entry for a rotation passed in.
const ROTATION_TOLERANCE: f32 = 1e-4;

/// The transformed centre of an empty test space. With BS = 0 every point and every tile box
/// maps to the origin, at distance 2 from this centre, outside the unit sphere.
const EMPTY_CENTER: Vec3 = Vec3::new(2.0, 0.0, 0.0);

/// What a culler stores per light (section 5.2): the matrix BS and the point BS·c, with S the
/// stretch of eq. (16) and B the rotation of eq. (17), both for the ellipsoid in view space.
/// In this space the ellipsoid is the unit sphere around BS·c, and a view-space plane z = k is
/// the plane z' = (BS)₃₃ k.
///
/// An empty bound (r = 0) is stored as BS = 0 and BS·c = (2, 0, 0): every point and every
/// tile box then maps to the origin, at distance 2 > 1 from the centre, so every test fails
/// through the ordinary code path, with no flag, NaN or infinity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TestSpace {
    matrix: Mat3,
    center: Vec3,
}

impl TestSpace {
    /// The test space of eq. (16)-(17) for the ellipsoid with view-space rotation `rotation`
    /// (columns = axes; R already multiplied by the view rotation V, section 5.1), semi-axes
    /// `semi_axes` along those columns, and view-space centre `center`.
    ///
    /// Semi-axes all zero give the empty test space. Errors: non-finite input, a `rotation`
    /// that is not orthonormal with det +1 (tolerance 1e-4), semi-axes that are negative,
    /// mixed zero and positive, or infinite, and [`BoundsError::Overflow`] if BS or BS·c
    /// does not fit in an `f32` (semi-axes below about 1e-38 relative to the centre).
    pub fn new(rotation: Mat3, semi_axes: Vec3, center: Vec3) -> Result<Self, BoundsError> {
        if !rotation.is_finite() {
            return Err(BoundsError::NotFinite("rotation"));
        }
        if !center.is_finite() {
            return Err(BoundsError::NotFinite("ellipsoid centre"));
        }
        if !is_rotation(rotation) {
            return Err(BoundsError::NotRotation);
        }
        if semi_axes == Vec3::ZERO {
            return Ok(Self {
                matrix: Mat3::ZERO,
                center: EMPTY_CENTER,
            });
        }
        if !(semi_axes.is_finite() && semi_axes.cmpgt(Vec3::ZERO).all()) {
            return Err(BoundsError::InvalidSemiAxes(semi_axes));
        }
        let s = stretch(rotation, semi_axes);
        let matrix = test_rotation(s) * s;
        let transformed = matrix * center;
        if matrix.is_finite() && transformed.is_finite() {
            Ok(Self {
                matrix,
                center: transformed,
            })
        } else {
            Err(BoundsError::Overflow("test space BS"))
        }
    }

    /// The test space of a world-space [`Spheroid`] seen through the rigid world-to-view
    /// transform `view` (section 5.1: R ← V R, c ← V c + o), then eq. (16)-(17).
    pub fn from_spheroid(spheroid: &Spheroid, view: Affine3A) -> Result<Self, BoundsError> {
        let rotation = Mat3::from(view.matrix3) * spheroid.rotation();
        let center = view.transform_point3(spheroid.center());
        Self::new(rotation, spheroid.semi_axes(), center)
    }

    /// The matrix BS of section 5.2 (eq. 16-17); zero for an empty bound.
    #[inline]
    pub fn matrix(&self) -> Mat3 {
        self.matrix
    }

    /// The transformed centre BS·c of section 5.2; (2, 0, 0) for an empty bound.
    #[inline]
    pub fn center(&self) -> Vec3 {
        self.center
    }

    /// Whether this is the empty test space of an r = 0 bound (eq. 12).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.matrix == Mat3::ZERO
    }

    /// A view-space point mapped into the test space, BS·p (section 5.2).
    #[inline]
    pub fn map(&self, point: Vec3) -> Vec3 {
        self.matrix * point
    }

    /// Whether the view-space `point` lies in the closed ellipsoid, i.e. |BS p − BS c| <= 1
    /// (eq. 16). Always false for an empty bound.
    #[inline]
    pub fn contains(&self, point: Vec3) -> bool {
        let d = self.map(point) - self.center;
        d.abs().max_element() <= 1.0 && d.length_squared() <= 1.0
    }

    /// The test-space box around the image of a view-space tile frustum (section 5.2,
    /// supplemental listing 2): the tile rectangle's corners at unit depth mapped by the
    /// upper 2×3 block of BS, their bounding rectangle swept over the depth range with the
    /// depth plane at z' = (BS)₃₃.
    #[inline]
    pub fn frustum_aabb(&self, frustum: &TileFrustum) -> Aabb {
        let m = self.matrix;
        let project = |u: f32, v: f32| {
            let p = m * Vec3::new(u, v, 1.0);
            Vec2::new(p.x, p.y)
        };
        let (lo, hi) = (frustum.rect_min(), frustum.rect_max());
        let v0 = project(lo.x, lo.y);
        let v1 = project(hi.x, lo.y);
        let v2 = project(hi.x, hi.y);
        let v3 = v2 - v1 + v0;
        Aabb::frustum(
            v0.min(v1).min(v2).min(v3),
            v0.max(v1).max(v2).max(v3),
            m.z_axis.z,
            frustum.z_min(),
            frustum.z_max(),
        )
    }

    /// The rough ellipsoid-frustum test of section 5.1-5.2: the unit sphere at BS·c meets the
    /// box of [`Self::frustum_aabb`]. Conservative (may report a miss as a hit, never the
    /// reverse); always false for an empty bound.
    #[inline]
    pub fn intersects(&self, frustum: &TileFrustum) -> bool {
        self.frustum_aabb(frustum)
            .intersects_sphere(self.center, 1.0)
    }
}

/// Whether `m` is orthonormal with determinant +1, within [`ROTATION_TOLERANCE`].
fn is_rotation(m: Mat3) -> bool {
    orthonormality_error(m) <= ROTATION_TOLERANCE && m.determinant() > 0.0
}

/// How far `m` is from orthonormal: the largest entry of |MᵀM − I|.
pub fn orthonormality_error(m: Mat3) -> f32 {
    let e = m.transpose() * m - Mat3::IDENTITY;
    e.x_axis
        .abs()
        .max(e.y_axis.abs())
        .max(e.z_axis.abs())
        .max_element()
}

/// The stretch of eq. (16): `S = R diag(1/r_u, 1/r_v, 1/r_w) Rᵀ`, which maps the ellipsoid
/// (centred anywhere) onto a unit-radius sphere.
fn stretch(rotation: Mat3, semi_axes: Vec3) -> Mat3 {
    rotation * Mat3::from_diagonal(semi_axes.recip()) * rotation.transpose()
}

/// The rotation B of eq. (17) for a stretch `s` (rows b_x/|b_x|, (b_z × b_x)/|…|,
/// b_z/|b_z| if |b_x| > |b_y|, else (b_y × b_z)/|…|, b_y/|b_y|, b_z/|b_z|), with b_x = S e_x,
/// b_y = S e_y, b_z = b_x × b_y. Then BS e_x and BS e_y have no z-component. S is scaled to
/// a unit largest entry first, which leaves the directions unchanged and avoids overflow.
fn test_rotation(s: Mat3) -> Mat3 {
    let scale = s
        .x_axis
        .abs()
        .max(s.y_axis.abs())
        .max(s.z_axis.abs())
        .max_element();
    let (bx, by) = (s.x_axis / scale, s.y_axis / scale);
    let (len_x, len_y) = (bx.length(), by.length());
    let (ux, uy) = (bx / len_x, by / len_y);
    let z = ux.cross(uy).normalize();
    let (x, y) = if len_x > len_y {
        (ux, z.cross(ux))
    } else {
        (uy.cross(z), uy)
    };
    Mat3::from_cols(x, y, z).transpose()
}

pub mod lanes;

#[cfg(test)]
mod tests;
