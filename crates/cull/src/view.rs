//! The culling view space and the image plane at unit depth (paper section 5.1).
//!
//! View space here has x along the camera's `right`, y along its `down` (so y grows with pixel
//! rows) and z along `forward` (depth, positive in front): a proper rotation (det +1) of the
//! camera-relative world. This is the space [`slc_bounds::TestSpace`] and
//! [`slc_bounds::TileFrustum`] expect: a tile is the set `z (u, v, 1)` of its image-plane
//! rectangle `[u0, u1] x [v0, v1]` swept over a depth range.
//!
//! Points are mapped as `R (p - eye)` in f64: subtracting the eye first keeps the precision
//! relative to the distance from the camera rather than from the world origin, and both the
//! G-buffer samples and the VPL bounds go through the same matrix, so culling and the
//! brute-force truth see the same geometry up to f64 rounding.
use glam::{Affine3A, DMat3, DVec2, DVec3, Mat3, Vec3};
use slc_bounds::test_space::orthonormality_error;
use slc_core::{Camera, CullError};

/// Largest accepted deviation of the camera basis from orthonormal; within it the basis is
/// re-orthonormalised, so the view rotation is orthonormal to f32 rounding.
const BASIS_TOLERANCE: f32 = 1e-3;

/// The culling view of one camera and image size.
#[derive(Clone, Debug, PartialEq)]
pub struct CullView {
    eye: DVec3,
    /// World-to-view rotation: rows right, down, forward.
    rotation: Mat3,
    /// The same rotation in f64 (identical values).
    rotation64: DMat3,
    /// Image-plane half extents at unit depth: (aspect tan(yfov/2), tan(yfov/2)).
    half_extent: DVec2,
    /// Image size in pixels (W, H).
    size: DVec2,
}

impl CullView {
    /// The view of `camera` rendering a `width` x `height` image. Errors when the image is
    /// empty, the field of view is outside (0, π) or the camera basis is not orthonormal.
    pub fn new(camera: &Camera, width: u32, height: u32) -> Result<Self, CullError> {
        if width == 0 || height == 0 {
            return Err(CullError::Input(format!("empty image {width}x{height}")));
        }
        if !(camera.yfov > 0.0 && camera.yfov < std::f32::consts::PI) {
            return Err(CullError::Input(format!(
                "vertical field of view {} is outside (0, pi)",
                camera.yfov
            )));
        }
        let rotation = orthonormal_basis(camera).ok_or_else(|| {
            CullError::Input(
                "camera position or basis (right, up, forward) is not finite and orthonormal"
                    .into(),
            )
        })?;
        let tan_half = (0.5 * f64::from(camera.yfov)).tan();
        let aspect = f64::from(width) / f64::from(height);
        Ok(Self {
            eye: camera.position.as_dvec3(),
            rotation,
            rotation64: rotation.as_dmat3(),
            half_extent: DVec2::new(aspect * tan_half, tan_half),
            size: DVec2::new(f64::from(width), f64::from(height)),
        })
    }

    /// The world-to-view rotation R (rows right, down, forward; det +1).
    #[inline]
    pub fn rotation(&self) -> Mat3 {
        self.rotation
    }

    /// The whole world-to-view map `p ↦ R (p − eye)` as one affine transform, for code that
    /// wants a matrix (a GPU backend). Culling itself uses [`Self::to_view`].
    pub fn affine(&self) -> Affine3A {
        let eye = self.eye.as_vec3();
        Affine3A::from_mat3_translation(self.rotation, -(self.rotation * eye))
    }

    /// A world point in view space, `R (p − eye)`, in f64.
    #[inline]
    pub fn to_view(&self, world: Vec3) -> DVec3 {
        self.rotate(self.relative(world))
    }

    /// A world point relative to the eye, `p − eye`, in f64 (exact unless the two differ in
    /// magnitude by more than 2^29).
    #[inline]
    pub fn relative(&self, world: Vec3) -> DVec3 {
        world.as_dvec3() - self.eye
    }

    /// A camera-relative vector (see [`Self::relative`]) rotated into view space.
    #[inline]
    pub fn rotate(&self, relative: DVec3) -> DVec3 {
        self.rotation64 * relative
    }

    /// The image-plane rectangle at unit depth `[u0, u1] x [v0, v1]` covered by the pixels
    /// `[x0, x1) x [y0, y1)` (pixel (i, j) covers `[i, i + 1) x [j, j + 1)`, where the camera's
    /// jittered samples lie): `u = (2x/W − 1) aspect tan(yfov/2)`, `v = (2y/H − 1) tan(yfov/2)`
    /// (the camera's ray convention with y pointing down).
    pub fn image_rect(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> (DVec2, DVec2) {
        let map = |x: u32, y: u32| {
            (2.0 * DVec2::new(f64::from(x), f64::from(y)) / self.size - 1.0) * self.half_extent
        };
        (map(x0, y0), map(x1, y1))
    }

    /// The eye, the origin of the view (rounded to f32: the camera's own position).
    #[inline]
    pub(crate) fn eye(&self) -> Vec3 {
        self.eye.as_vec3()
    }

    /// The map from the image plane at unit depth to screen pixels of
    /// [`Self::to_screen`], `X = u scale + offset` per axis: (scale, offset).
    pub(crate) fn screen_map(&self) -> ([f64; 2], [f64; 2]) {
        let half = self.size * 0.5;
        ((half / self.half_extent).to_array(), half.to_array())
    }

    /// The screen position (in pixels, pixel (i, j) covering `[i, i + 1) x [j, j + 1)`) of the
    /// image-plane point `uv` at unit depth: the inverse of [`Self::image_rect`]'s map.
    #[inline]
    pub(crate) fn to_screen(&self, uv: DVec2) -> DVec2 {
        (uv / self.half_extent + 1.0) * self.size * 0.5
    }
}

/// The world-to-view rotation (rows right, down, forward) of a camera whose basis is
/// orthonormal and right-handed (right = forward × up) within [`BASIS_TOLERANCE`],
/// re-orthonormalised (Gram-Schmidt from forward, then right); `None` otherwise.
fn orthonormal_basis(camera: &Camera) -> Option<Mat3> {
    let given = Mat3::from_cols(camera.right, -camera.up, camera.forward);
    let worst = orthonormality_error(given);
    if !(camera.position.is_finite() && worst <= BASIS_TOLERANCE && given.determinant() > 0.0) {
        return None;
    }
    let forward = camera.forward.normalize();
    let right = camera.right.reject_from_normalized(forward).normalize();
    Some(Mat3::from_cols(right, forward.cross(right), forward).transpose())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::look_at(
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(-0.5, 0.3, -2.0),
            Vec3::Y,
            50f32.to_radians(),
        )
        .unwrap()
    }

    #[test]
    fn view_space_is_right_down_forward_with_det_one() {
        let cam = camera();
        let view = CullView::new(&cam, 64, 48).unwrap();
        assert!((view.rotation().determinant() - 1.0).abs() < 1e-6);
        let p = cam.position + 2.0 * cam.right + 3.0 * cam.up + 5.0 * cam.forward;
        let v = view.to_view(p);
        assert!((v - DVec3::new(2.0, -3.0, 5.0)).length() < 1e-5, "{v}");
        assert!((v.z - f64::from(cam.view_depth(p))).abs() < 1e-5);
        let a = view.affine().transform_point3(p).as_dvec3();
        assert!((a - v).length() < 1e-5);
    }

    #[test]
    fn camera_rays_project_into_their_pixel_rectangles() {
        let cam = camera();
        let (w, h) = (37, 23);
        let view = CullView::new(&cam, w, h).unwrap();
        for j in 0..h {
            for i in 0..w {
                let (lo, hi) = view.image_rect(i, j, i + 1, j + 1);
                assert!(lo.cmplt(hi).all());
                for (s, t) in [(0.0, 0.0), (0.5, 0.5), (0.999, 0.001), (0.001, 0.999)] {
                    let d = view.rotate(cam.ray_direction(i, j, s, t, w, h).as_dvec3());
                    let uv = DVec2::new(d.x / d.z, d.y / d.z);
                    let slack = 1e-6;
                    assert!(uv.cmpge(lo - slack).all() && uv.cmple(hi + slack).all());
                }
                // Rows grow downwards: the row below has larger v.
                let below = view.image_rect(i, j + 1, i + 1, j + 2);
                assert!(below.0.y >= hi.y - 1e-12);
            }
        }
    }

    #[test]
    fn invalid_views_are_errors() {
        let cam = camera();
        assert!(CullView::new(&cam, 0, 4).is_err());
        let wide = Camera {
            yfov: std::f32::consts::PI,
            ..cam.clone()
        };
        assert!(CullView::new(&wide, 4, 4).is_err());
        let skew = Camera {
            up: Vec3::new(0.3, 1.0, 0.0),
            ..cam.clone()
        };
        assert!(CullView::new(&skew, 4, 4).is_err());
        let far = Camera {
            position: Vec3::NAN,
            ..cam
        };
        assert!(CullView::new(&far, 4, 4).is_err());
    }
}
