//! Reflective shadow maps traced from the light: the surface points the light's photons reach
//! first, with the flux each texel carries.
//!
//! A point light gets six cube faces, a spot light one perspective face whose half-angle is the
//! outer cone angle (six faces when that angle exceeds [`SPOT_SINGLE_FACE_MAX_ANGLE`]), a
//! directional light one orthographic map covering the scene's bounding sphere.
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::Brdf;
use slc_core::rng::{stream, Sequence};
use slc_core::{Light, Scene};

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

/// Where inside each texel the light's ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexelSample {
    /// Through the texel centre, with the texel's exact solid angle (as a rasterizer would).
    Centre,
    /// At a uniformly random point of the texel (pass `pass` of `seed`), with the flux divided
    /// by that point's density: an unbiased estimate of the light's one-bounce transport.
    Jittered { seed: u32, pass: u32 },
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

/// One face of a map: rays leave `origin` (perspective) or the plane through `origin`
/// (orthographic) through the points `forward + x right + y up`, x and y in [-extent, extent].
#[derive(Clone, Copy, Debug)]
struct Face {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    extent: f32,
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

fn cube_faces() -> Vec<Face> {
    CUBE_FACES
        .iter()
        .map(|&(forward, right, up)| Face {
            forward,
            right,
            up,
            extent: 1.0,
        })
        .collect()
}

/// Solid angle of the rectangle [x0, x1] x [y0, y1] on the plane at unit distance:
/// `F(x1,y1) - F(x0,y1) - F(x1,y0) + F(x0,y0)` with `F(x, y) = atan2(xy, sqrt(x² + y² + 1))`.
pub fn rectangle_solid_angle(x0: f32, x1: f32, y0: f32, y1: f32) -> f32 {
    let f = |x: f64, y: f64| (x * y).atan2((x * x + y * y + 1.0).sqrt());
    let (x0, x1, y0, y1) = (x0 as f64, x1 as f64, y0 as f64, y1 as f64);
    (f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0)).abs() as f32
}

/// Traces the reflective shadow map of `light`.
pub fn trace_rsm(
    scene: &Scene,
    tracer: &Tracer,
    light: &Light,
    resolution: u32,
    sample: TexelSample,
) -> Rsm {
    let n = resolution;
    let (faces, origin, orthographic) = match *light {
        Light::Point { position, .. } => (cube_faces(), position, false),
        Light::Spot {
            position,
            direction,
            outer_cone_angle,
            ..
        } => {
            if outer_cone_angle > SPOT_SINGLE_FACE_MAX_ANGLE {
                (cube_faces(), position, false)
            } else {
                let (right, up) = direction.any_orthonormal_pair();
                (
                    vec![Face {
                        forward: direction,
                        right,
                        up,
                        extent: outer_cone_angle.tan(),
                    }],
                    position,
                    false,
                )
            }
        }
        Light::Directional { direction, .. } => {
            let (lo, hi) = scene.bounds().unwrap_or((Vec3::splat(-1.0), Vec3::ONE));
            let centre = 0.5 * (lo + hi);
            let radius = (0.5 * (hi - lo).length()).max(1e-3) * 1.01;
            let (right, up) = direction.any_orthonormal_pair();
            (
                vec![Face {
                    forward: direction,
                    right,
                    up,
                    extent: radius,
                }],
                centre - direction * (2.0 * radius),
                true,
            )
        }
    };
    let texel_size = 2.0 / n as f32;
    let texels = (0..faces.len() as u32 * n * n)
        .into_par_iter()
        .map(|index| {
            let face = faces[(index / (n * n)) as usize];
            let (i, j) = (index % n, (index / n) % n);
            let (s, t) = match sample {
                TexelSample::Centre => (0.5, 0.5),
                TexelSample::Jittered { seed, pass } => {
                    Sequence::new(seed, index, stream::RSM_JITTER, 2 * pass).next_2d()
                }
            };
            let e = face.extent;
            let x = (-1.0 + (i as f32 + s) * texel_size) * e;
            let y = (1.0 - (j as f32 + t) * texel_size) * e;
            // The beam's cross-section is `beam` (orthographic) or `beam` times the squared
            // distance (perspective, `beam` a solid angle).
            let (ray_origin, dir, flux, beam) = if orthographic {
                let area = (texel_size * e) * (texel_size * e);
                let irradiance = match *light {
                    Light::Directional { irradiance, .. } => irradiance,
                    _ => unreachable!("only directional lights are orthographic"),
                };
                (
                    origin + x * face.right + y * face.up,
                    face.forward,
                    irradiance * area,
                    area,
                )
            } else {
                let dir = (face.forward + x * face.right + y * face.up).normalize();
                let solid_angle = match sample {
                    TexelSample::Centre => {
                        let (x0, y1) = (
                            (-1.0 + i as f32 * texel_size) * e,
                            (1.0 - j as f32 * texel_size) * e,
                        );
                        rectangle_solid_angle(x0, x0 + texel_size * e, y1 - texel_size * e, y1)
                    }
                    // Density of a uniform point on the texel, in solid angle:
                    // dω = dA / (1 + x² + y²)^{3/2} on the plane at unit distance.
                    TexelSample::Jittered { .. } => {
                        (texel_size * e).powi(2) / (1.0 + x * x + y * y).powf(1.5)
                    }
                };
                let intensity = match *light {
                    Light::Point { intensity, .. } => intensity,
                    Light::Spot { intensity, .. } => intensity * light.spot_falloff(dir),
                    Light::Directional { .. } => {
                        unreachable!("directional lights are orthographic")
                    }
                };
                (origin, dir, intensity * solid_angle, solid_angle)
            };
            if flux.max_element() <= 0.0 {
                return None;
            }
            let hit = tracer.intersect(scene, ray_origin, dir, f32::INFINITY)?;
            let cross_section = if orthographic {
                beam
            } else {
                beam * hit.distance * hit.distance
            };
            hit.front.then_some(RsmTexel {
                position: hit.position,
                normal: hit.shading_normal,
                geometric_normal: hit.geometric_normal,
                normal_mapped: hit.normal_mapped,
                omega_i: -dir,
                flux,
                cross_section,
                brdf: hit.brdf,
            })
        })
        .collect();
    Rsm {
        resolution: n,
        faces: faces.len() as u32,
        texels,
    }
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
