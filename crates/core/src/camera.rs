//! The perspective pinhole camera and its ray convention.
use glam::{Mat4, Vec3, Vec4};

/// A pinhole camera. `forward`, `right` and `up` are orthonormal (right-handed: right = forward x up).
///
/// Ray convention (the one the reference renders in `shared/reference` use): pixel (i, j), i the
/// column from the left, j the row from the top, (s, t) in [0, 1)^2 the position inside the pixel:
/// `x = (2(i+s)/W - 1) * aspect * tan(yfov/2)`, `y = (1 - 2(j+t)/H) * tan(yfov/2)`,
/// `dir = normalize(forward + x right + y up)`, aspect = W / H of the rendered image.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
    /// Full vertical field of view in radians.
    pub yfov: f32,
    pub znear: f32,
    pub zfar: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target`; `up` need not be orthogonal to the view direction.
    /// Returns `None` when the view direction is zero or parallel to `up`.
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3, yfov: f32) -> Option<Self> {
        let forward = (target - eye).try_normalize()?;
        Self::from_basis(eye, forward, up, yfov)
    }

    /// A camera from a position, a view direction and an up hint.
    pub fn from_basis(eye: Vec3, forward: Vec3, up: Vec3, yfov: f32) -> Option<Self> {
        let forward = forward.try_normalize()?;
        let right = forward.cross(up).try_normalize()?;
        let up = right.cross(forward);
        (yfov > 0.0 && yfov < std::f32::consts::PI).then_some(Self {
            position: eye,
            forward,
            right,
            up,
            yfov,
            znear: 0.01,
            zfar: 1000.0,
        })
    }

    /// The unit direction of the primary ray through pixel (i, j) at sub-pixel offset (s, t).
    pub fn ray_direction(&self, i: u32, j: u32, s: f32, t: f32, width: u32, height: u32) -> Vec3 {
        let tan_half = (0.5 * self.yfov).tan();
        let aspect = width as f32 / height as f32;
        let x = (2.0 * (i as f32 + s) / width as f32 - 1.0) * aspect * tan_half;
        let y = (1.0 - 2.0 * (j as f32 + t) / height as f32) * tan_half;
        (self.forward + x * self.right + y * self.up).normalize()
    }

    /// World-to-view matrix: view space has x = right, y = up and looks along -z
    /// (right-handed, as glTF and most GPU code).
    pub fn view_matrix(&self) -> Mat4 {
        let (r, u, b) = (self.right, self.up, -self.forward);
        Mat4::from_cols(
            Vec4::new(r.x, u.x, b.x, 0.0),
            Vec4::new(r.y, u.y, b.y, 0.0),
            Vec4::new(r.z, u.z, b.z, 0.0),
            Vec4::new(
                -r.dot(self.position),
                -u.dot(self.position),
                -b.dot(self.position),
                1.0,
            ),
        )
    }

    /// Linear view depth of a world point: its distance along `forward` (positive in front).
    pub fn view_depth(&self, p: Vec3) -> f32 {
        (p - self.position).dot(self.forward)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_is_forward_and_corners_span_the_fov() {
        let cam = Camera::look_at(
            Vec3::new(0.0, 1.0, 3.4),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::Y,
            40f32.to_radians(),
        )
        .unwrap();
        let d = cam.ray_direction(128, 128, 0.0, 0.0, 256, 256);
        assert!((d - Vec3::NEG_Z).length() < 1e-6);
        // Top edge of the image: angle to forward is yfov/2.
        let top = cam.ray_direction(128, 0, 0.0, 0.0, 256, 256);
        assert!((top.dot(cam.forward).acos() - 20f32.to_radians()).abs() < 1e-5);
        assert!(top.y > 0.0);
        let left = cam.ray_direction(0, 128, 0.0, 0.0, 256, 256);
        assert!(left.x < 0.0);
    }

    #[test]
    fn degenerate_cameras_are_refused() {
        assert!(Camera::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y, 1.0).is_none());
        assert!(Camera::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, 1.0).is_none());
        assert!(Camera::look_at(Vec3::ZERO, Vec3::X, Vec3::Y, 0.0).is_none());
    }

    #[test]
    fn view_matrix_agrees_with_depth() {
        let cam = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 1.0).unwrap();
        let p = Vec3::new(0.3, -0.2, 0.1);
        let v = cam.view_matrix().transform_point3(p);
        assert!((-v.z - cam.view_depth(p)).abs() < 1e-5);
    }
}
