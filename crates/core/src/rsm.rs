//! Reflective shadow maps as both backends lay them out: the faces a light's map has
//! ([`RsmLayout`]), what each texel saw ([`RsmTexel`]) and a whole map ([`Rsm`]), which the
//! CPU traces and the GPU rasterizes and reads back.
//!
//! A point light gets six cube faces, a spot light one perspective face whose half-angle is the
//! outer cone angle (six faces when that angle exceeds [`SPOT_SINGLE_FACE_MAX_ANGLE`]), a
//! directional light one orthographic map covering the scene's bounding sphere.
use crate::light::Light;
use crate::vpl::{Vpl, VplLobe};
use glam::Vec3;
use slc_bounds::Brdf;

/// Beyond this outer cone angle a spot light's single face would be too stretched: six faces are used.
pub const SPOT_SINGLE_FACE_MAX_ANGLE: f32 = 80.0 * std::f32::consts::PI / 180.0;

/// What one RSM texel saw: a photon of flux `flux` arriving at a surface point.
#[derive(Clone, Copy, Debug)]
pub struct RsmTexel {
    pub position: Vec3,
    /// Unit shading normal.
    pub normal: Vec3,
    /// Unit geometric normal (on the lit side).
    pub geometric_normal: Vec3,
    /// Whether a normal map perturbed `normal` (`SurfaceHit::normal_mapped`).
    pub normal_mapped: bool,
    /// Unit direction from the surface point towards the light.
    pub omega_i: Vec3,
    /// Radiant flux carried by the texel's photon (W per channel).
    pub flux: Vec3,
    /// Cross-section of the light's beam through the texel where it meets the surface (m²):
    /// the texel's solid angle times the squared distance (perspective maps) or its area
    /// (orthographic maps). The surface patch the texel stands for is this area over the
    /// cosine of incidence.
    pub cross_section: f32,
    pub brdf: Brdf,
}

impl RsmTexel {
    /// The VPL of this texel's `lobe` with the number `id` and the roulette's ξ: the
    /// geometric normal kept beside the shading one where a normal map perturbed it, both the
    /// shading normal elsewhere (eq. 4 as the paper evaluates it).
    pub fn vpl(&self, lobe: VplLobe, id: u32, xi: f32) -> Vpl {
        Vpl {
            position: self.position,
            normal: self.normal,
            geometric_normal: match self.normal_mapped {
                true => self.geometric_normal,
                false => self.normal,
            },
            omega_i: self.omega_i,
            flux: self.flux,
            brdf: self.brdf,
            lobe,
            id,
            xi,
        }
    }
}

/// A reflective shadow map of one light: `faces` square maps of `resolution`² texels,
/// face-major then row-major (row 0 at the top); `None` where the light's ray hit nothing,
/// hit the back of a one-sided surface, or carries no flux.
#[derive(Clone, Debug)]
pub struct Rsm {
    pub resolution: u32,
    pub faces: u32,
    pub texels: Vec<Option<RsmTexel>>,
}

/// (forward, right, up) of the six cube faces, right = forward x up like the camera.
const CUBE_FACES: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::Z, Vec3::Y),
    (Vec3::NEG_X, Vec3::NEG_Z, Vec3::Y),
    (Vec3::Y, Vec3::NEG_X, Vec3::NEG_Z),
    (Vec3::NEG_Y, Vec3::NEG_X, Vec3::Z),
    (Vec3::Z, Vec3::NEG_X, Vec3::Y),
    (Vec3::NEG_Z, Vec3::X, Vec3::Y),
];

/// One face of a map: rays leave `origin` (pinhole) or the plane through it (orthographic)
/// through `forward + x right + y up`, x and y in [−extent, extent].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RsmFace {
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
    pub extent: f32,
}

/// The faces of `light`'s map, their origin and, for a directional light, the orthographic
/// depth range.
#[derive(Clone, Debug, PartialEq)]
pub struct RsmLayout {
    pub faces: Vec<RsmFace>,
    pub origin: Vec3,
    /// `Some(depth range)` for an orthographic map.
    pub orthographic: Option<f32>,
}

impl RsmLayout {
    /// The layout of `light`'s map in a scene with bounds `bounds` (both backends').
    pub fn new(light: &Light, bounds: (Vec3, Vec3)) -> Self {
        let cube = || {
            CUBE_FACES
                .iter()
                .map(|&(forward, right, up)| RsmFace {
                    forward,
                    right,
                    up,
                    extent: 1.0,
                })
                .collect()
        };
        match *light {
            Light::Point { position, .. } => Self {
                faces: cube(),
                origin: position,
                orthographic: None,
            },
            Light::Spot {
                position,
                direction,
                outer_cone_angle,
                ..
            } => {
                let faces = if outer_cone_angle > SPOT_SINGLE_FACE_MAX_ANGLE {
                    cube()
                } else {
                    let (right, up) = direction.any_orthonormal_pair();
                    vec![RsmFace {
                        forward: direction,
                        right,
                        up,
                        extent: outer_cone_angle.tan(),
                    }]
                };
                Self {
                    faces,
                    origin: position,
                    orthographic: None,
                }
            }
            Light::Directional { direction, .. } => {
                let (lo, hi) = bounds;
                let centre = 0.5 * (lo + hi);
                let radius = (0.5 * (hi - lo).length()).max(1e-3) * 1.01;
                let (right, up) = direction.any_orthonormal_pair();
                Self {
                    faces: vec![RsmFace {
                        forward: direction,
                        right,
                        up,
                        extent: radius,
                    }],
                    origin: centre - direction * (2.0 * radius),
                    // The bounding sphere lies within [radius, 3 radius] of the origin plane.
                    orthographic: Some(4.0 * radius),
                }
            }
        }
    }
}

/// Solid angle of the rectangle [x0, x1] x [y0, y1] on the plane at unit distance:
/// `F(x1,y1) - F(x0,y1) - F(x1,y0) + F(x0,y0)` with `F(x, y) = atan2(xy, sqrt(x² + y² + 1))`.
pub fn rectangle_solid_angle(x0: f32, x1: f32, y0: f32, y1: f32) -> f32 {
    let f = |x: f64, y: f64| (x * y).atan2((x * x + y * y + 1.0).sqrt());
    let (x0, x1, y0, y1) = (x0 as f64, x1 as f64, y0 as f64, y1 as f64);
    (f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0)).abs() as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_faces_cover_the_sphere() {
        // The exact texel solid angles of the six faces sum to 4π.
        let n = 16;
        let ts = 2.0 / n as f32;
        let mut total = 0.0f64;
        for _ in 0..6 {
            for j in 0..n {
                for i in 0..n {
                    let x0 = -1.0 + i as f32 * ts;
                    let y0 = -1.0 + j as f32 * ts;
                    total += rectangle_solid_angle(x0, x0 + ts, y0, y0 + ts) as f64;
                }
            }
        }
        assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-4, "{total}");
    }

    #[test]
    fn cube_faces_are_right_handed_and_orthonormal() {
        for (f, r, u) in CUBE_FACES {
            assert!(f.dot(r).abs() < 1e-6 && f.dot(u).abs() < 1e-6 && r.dot(u).abs() < 1e-6);
            // right = forward x up, as for the camera.
            assert!((f.cross(u) - r).length() < 1e-6, "{f:?}");
        }
    }
}
