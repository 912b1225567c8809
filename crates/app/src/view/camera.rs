//! The fly camera: WASD (and Q/E down/up) moves, the mouse looks around, the wheel sets the
//! speed, R returns to the scene's camera. Input arrives as [`FlyInput`], from the keyboard
//! and mouse or from a script (`--camera-script`), so both drive the same code.
use glam::{Quat, Vec3};
use slc_core::{Camera, Scene};

/// Radians of turn per pixel of mouse motion.
const LOOK_PER_PIXEL: f32 = 0.004;
/// The steepest the view may look up or down (radians from the horizon).
const MAX_PITCH: f32 = 1.5;
/// Speed factor of one wheel notch.
const WHEEL_STEP: f32 = 1.25;

/// What the user does during one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlyInput {
    /// Held movement keys: +1 forward (W) / -1 back (S).
    pub forward: f32,
    /// +1 right (D) / -1 left (A).
    pub right: f32,
    /// +1 up (E) / -1 down (Q).
    pub up: f32,
    /// Mouse motion while looking, in pixels (x right, y down).
    pub look: (f32, f32),
    /// Wheel notches (positive: faster).
    pub wheel: f32,
    /// Back to the scene's camera.
    pub reset: bool,
}

/// A camera flying through the scene, starting at (and reset to) the scene's camera.
#[derive(Clone, Debug)]
pub struct FlyCamera {
    home: Camera,
    camera: Camera,
    home_speed: f32,
    /// Metres per second.
    pub speed: f32,
}

impl FlyCamera {
    /// The scene's camera, at a speed that crosses a quarter of the scene per second.
    pub fn new(scene: &Scene) -> Self {
        let home = scene.camera_or_default();
        let size = scene.bounds().map_or(1.0, |(lo, hi)| (hi - lo).length());
        let speed = (0.25 * size).max(1e-3);
        Self {
            camera: home.clone(),
            home,
            home_speed: speed,
            speed,
        }
    }

    /// The current view.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Applies one frame of input lasting `dt` seconds.
    pub fn apply(&mut self, input: &FlyInput, dt: f32) {
        if input.reset {
            self.camera = self.home.clone();
            self.speed = self.home_speed;
        }
        self.speed *= WHEEL_STEP.powf(input.wheel);
        self.look(input.look.0 * LOOK_PER_PIXEL, input.look.1 * LOOK_PER_PIXEL);
        let c = &mut self.camera;
        let step = input.forward * c.forward + input.right * c.right + input.up * Vec3::Y;
        c.position += step * self.speed * dt;
    }

    /// Turns by `yaw` radians about the world's up axis (positive: to the right) and `pitch`
    /// radians about the camera's right axis (positive: down), keeping away from the poles.
    fn look(&mut self, yaw: f32, pitch: f32) {
        let c = &self.camera;
        let current = c.forward.y.clamp(-1.0, 1.0).asin();
        let pitch = (current - pitch).clamp(-MAX_PITCH, MAX_PITCH) - current;
        let turn = Quat::from_axis_angle(Vec3::Y, -yaw) * Quat::from_axis_angle(c.right, pitch);
        let forward = turn * c.forward;
        if let Some(mut turned) = Camera::from_basis(c.position, forward, Vec3::Y, c.yfov) {
            turned.znear = c.znear;
            turned.zfar = c.zfar;
            self.camera = turned;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        slc_core::builtin("default").expect("built-in scene")
    }

    #[test]
    fn forward_moves_along_the_view_and_reset_returns() {
        let s = scene();
        let mut fly = FlyCamera::new(&s);
        let start = fly.camera().clone();
        let input = FlyInput {
            forward: 1.0,
            ..Default::default()
        };
        fly.apply(&input, 1.0);
        let moved = fly.camera().position - start.position;
        assert!((moved.normalize() - start.forward).length() < 1e-5);
        assert!((moved.length() - fly.speed).abs() < 1e-4);
        fly.apply(
            &FlyInput {
                reset: true,
                ..Default::default()
            },
            1.0,
        );
        assert_eq!(fly.camera(), &start);
    }

    #[test]
    fn looking_turns_and_stays_off_the_poles() {
        let mut fly = FlyCamera::new(&scene());
        let before = fly.camera().forward;
        let look = FlyInput {
            look: (100.0, 0.0),
            ..Default::default()
        };
        fly.apply(&look, 0.1);
        let after = fly.camera().forward;
        assert!(after.dot(before) < 0.99, "{before} -> {after}");
        assert!(after.dot(fly.camera().right).abs() < 1e-5);
        let up = FlyInput {
            look: (0.0, -1e5),
            ..Default::default()
        };
        fly.apply(&up, 0.1);
        assert!(fly.camera().forward.y < MAX_PITCH.sin() + 1e-4);
        assert!(fly.camera().forward.is_finite());
    }

    #[test]
    fn the_wheel_scales_the_speed() {
        let mut fly = FlyCamera::new(&scene());
        let v = fly.speed;
        fly.apply(
            &FlyInput {
                wheel: 2.0,
                ..Default::default()
            },
            0.0,
        );
        assert!((fly.speed - v * WHEEL_STEP * WHEEL_STEP).abs() < 1e-5);
    }
}
