//! The caster points of the imperfect shadow maps ([`crate::vsgl::ism`]): discs on the scene's
//! triangles, uniformly by area (Ritschel et al. 2008) or, given an eye
//! ([`IsmSettings::view`]), view-adaptive (Ritschel et al. 2011, "Making Imperfect Shadow Maps
//! View-Adaptive"): denser where the eye is near, since a shadow there covers more pixels,
//! with the density `p(x) ∝ w(x) = 1/max(|x − eye|, near)²` over the area (`near` is
//! [`NEAR_FRACTION`] of the scene's bounding-box diagonal). Each disc's radius follows the
//! density at its point, `footprint · sqrt(1 / (π M p(x)))`, so that the discs tile the
//! surfaces as the uniform ones do.
//!
//! Sampling by rejection: a triangle with probability `∝ area · w̄` (`w̄ ≥ w` over the
//! triangle, from its bounding sphere), a uniform point `x` on it, kept with probability
//! `w(x)/w̄`. The kept points have the density `w(x) / W`, `W = ∫ w dA`, which the acceptance
//! rate times `Σ area · w̄` estimates without bias. Without an eye `w = w̄ = 1`: nothing is
//! rejected and the points are the uniform ones.
use crate::vsgl::ism::{GpuCaster, IsmSettings};
use glam::Vec3;
use slc_core::rng::{stream, uniform as rng_uniform};
use slc_core::{Material, Scene};

/// Below this distance from the eye, as a fraction of the scene's bounding-box diagonal, the
/// view-adaptive density stops growing.
pub const NEAR_FRACTION: f32 = 0.05;

/// Candidates drawn per requested point at most (a bound on the rejection loop).
const MAX_CANDIDATES_PER_POINT: u32 = 64;

/// A triangle to sample: its corners, unit normal, material and texture coordinates, and the
/// bound `w̄` of the density weight over it.
struct Triangle<'a> {
    corners: [Vec3; 3],
    normal: Vec3,
    material: Option<&'a Material>,
    uvs: Option<[glam::Vec2; 3]>,
    bound: f64,
}

/// The density weight `w(x)` of [`IsmSettings::view`] (1 without an eye).
#[derive(Clone, Copy)]
struct Weight {
    eye: Option<Vec3>,
    near: f32,
}

impl Weight {
    fn at(&self, x: Vec3) -> f64 {
        self.eye.map_or(1.0, |eye| {
            f64::from((x - eye).length().max(self.near)).powi(-2)
        })
    }

    /// A bound of [`Weight::at`] over the triangle: at the distance of its bounding sphere
    /// (about the centroid) from the eye.
    fn bound(&self, corners: &[Vec3; 3]) -> f64 {
        self.eye.map_or(1.0, |eye| {
            let centre = (corners[0] + corners[1] + corners[2]) / 3.0;
            let reach = corners
                .iter()
                .map(|c| (*c - centre).length())
                .fold(0.0, f32::max);
            let d = ((centre - eye).length() - reach).max(self.near);
            f64::from(d).powi(-2)
        })
    }
}

/// `settings.points` caster discs on `scene`'s triangles (see the module docs), less those an
/// alpha mask cuts away (the others keep their density); none for a scene without area.
/// Deterministic in `settings.seed` (and the eye). View-adaptive sampling draws at most
/// `MAX_CANDIDATES_PER_POINT` candidates per point: where the triangles' bounds are loose
/// (large triangles near the eye) the set may come out short, its discs still sized for the
/// density they were drawn with.
pub fn caster_points(scene: &Scene, settings: &IsmSettings) -> Vec<GpuCaster> {
    let near = scene
        .bounds()
        .map_or(0.0, |(lo, hi)| NEAR_FRACTION * (hi - lo).length())
        .max(f32::MIN_POSITIVE);
    let weight = Weight {
        eye: settings.view,
        near,
    };
    let mut tris = Vec::new();
    let mut cdf = Vec::new();
    let mut total = 0.0f64;
    for mesh in &scene.meshes {
        let material = scene.materials.get(mesh.material);
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions.get(i as usize).copied());
            let (Some(a), Some(b), Some(c)) = (a, b, c) else {
                continue;
            };
            let cross = (b - a).cross(c - a);
            let area = 0.5 * f64::from(cross.length());
            if !(area > 0.0 && area.is_finite()) {
                continue;
            }
            let corners = [a, b, c];
            let bound = weight.bound(&corners);
            total += area * bound;
            let uvs = mesh
                .uvs
                .as_ref()
                .map(|uv| t.map(|i| uv.get(i as usize).copied()))
                .and_then(|[a, b, c]| Some([a?, b?, c?]));
            tris.push(Triangle {
                corners,
                normal: cross.normalize(),
                material,
                uvs,
                bound,
            });
            cdf.push(total);
        }
    }
    if tris.is_empty() || settings.points == 0 || !total.is_finite() {
        return Vec::new();
    }
    // The kept points with their weights; cut ones count towards `points` but are not kept.
    let mut kept: Vec<(Vec3, Vec3, f64)> = Vec::with_capacity(settings.points as usize);
    let (mut accepted, mut candidates) = (0u32, 0u32);
    let most = settings.points.saturating_mul(MAX_CANDIDATES_PER_POINT);
    while accepted < settings.points && candidates < most {
        let index = candidates;
        let u = |k| rng_uniform(settings.seed, index, stream::ISM_CASTERS, k);
        candidates += 1;
        let target = f64::from(u(0)) * total;
        let t = &tris[cdf.partition_point(|&c| c < target).min(tris.len() - 1)];
        let s = u(1).sqrt();
        let r = u(2);
        let b = [1.0 - s, s * (1.0 - r), s * r];
        let p = t.corners[0] * b[0] + t.corners[1] * b[1] + t.corners[2] * b[2];
        let w = weight.at(p);
        if w < t.bound && f64::from(u(3)) * t.bound >= w {
            continue;
        }
        accepted += 1;
        let uv = t.uvs.map(|[ua, ub, uc]| ua * b[0] + ub * b[1] + uc * b[2]);
        if t.material.is_some_and(|m| m.cuts(uv, &scene.textures)) {
            continue;
        }
        kept.push((p, t.normal, w));
    }
    // Each map draws `points_per_map` of the points: their discs tile the area at the density
    // w / W, W = total · accepted / candidates.
    let per_map = f64::from(settings.points_per_map.clamp(1, settings.points));
    let integral = total * (f64::from(accepted) / f64::from(candidates));
    kept.into_iter()
        .map(|(p, n, w)| {
            let radius = settings.footprint
                * (integral / (per_map * std::f64::consts::PI * w)).sqrt() as f32;
            GpuCaster {
                position_radius: [p.x, p.y, p.z, radius],
                normal: [n.x, n.y, n.z, 0.0],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points lie on the triangles, spread by area, deterministically.
    #[test]
    fn caster_points_cover_the_scene_by_area() {
        let scene = slc_core::builtin("default").unwrap();
        let settings = IsmSettings::paper(1e-4);
        let a = caster_points(&scene, &settings);
        assert_eq!(a.len(), 8192);
        assert_eq!(a, caster_points(&scene, &settings));
        let (lo, hi) = scene.bounds().unwrap();
        let radius = a[0].position_radius[3];
        for c in &a {
            let p = Vec3::from_slice(&c.position_radius[..3]);
            assert!(p.cmpge(lo - 1e-4).all() && p.cmple(hi + 1e-4).all(), "{p}");
            assert!((Vec3::from_slice(&c.normal[..3]).length() - 1.0).abs() < 1e-4);
            assert!(c.position_radius[3] > 0.0 && c.position_radius[3] == radius);
        }
    }

    /// With an eye, the density falls as `1/d²` and the discs grow as `d`: among the points
    /// of the built-in room, those within a near shell of the eye are about
    /// `(d_far / d_near)²` times as dense as those in a far one, and every disc's radius is
    /// `footprint · sqrt(W / (π M w))` with the same `W`.
    #[test]
    fn view_adaptive_points_follow_the_distance() {
        let scene = slc_core::builtin("default").unwrap();
        let eye = scene.camera_or_default().position;
        let uniform = IsmSettings::paper(1e-4);
        let settings = IsmSettings {
            points: 65536,
            points_per_map: 65536,
            view: Some(eye),
            ..uniform
        };
        let adaptive = caster_points(&scene, &settings);
        let flat = caster_points(
            &scene,
            &IsmSettings {
                view: None,
                ..settings
            },
        );
        assert_eq!(adaptive.len(), 65536);
        assert_eq!(adaptive, caster_points(&scene, &settings));
        // Counts in two shells of distance, against the uniform points' counts there (the
        // same area): the ratio of densities is the ratio of 1/d² at the shells' middles.
        let count = |points: &[GpuCaster], lo: f32, hi: f32| {
            points
                .iter()
                .filter(|c| {
                    let d = (Vec3::from_slice(&c.position_radius[..3]) - eye).length();
                    (lo..hi).contains(&d)
                })
                .count() as f64
        };
        let (near, far) = ((2.5, 2.8), (4.2, 4.5));
        let gain = |(lo, hi): (f32, f32)| count(&adaptive, lo, hi) / count(&flat, lo, hi);
        let ratio = gain(near) / gain(far);
        let expected = (4.35f64 / 2.65).powi(2);
        assert!((ratio / expected - 1.0).abs() < 0.1, "{ratio} {expected}");
        // r² w is the same for every disc, r² the uniform disc's at the mean weight.
        let key = |c: &GpuCaster| {
            let d = (Vec3::from_slice(&c.position_radius[..3]) - eye).length();
            f64::from(c.position_radius[3]).powi(2) / f64::from(d).powi(2)
        };
        let k0 = key(&adaptive[0]);
        assert!(adaptive.iter().all(|c| (key(c) / k0 - 1.0).abs() < 1e-4));
        assert!(adaptive.iter().all(|c| c.position_radius[3].is_finite()));
    }
}
