//! Axis-aligned boxes: point distance, sphere overlap and the box around a sheared tile
//! frustum, the rough test of Modified HalfZ tiled culling (section 5.1, supplemental
//! listing 2).
use glam::{Vec2, Vec3};

/// A closed axis-aligned box `min <= p <= max` (componentwise).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    /// The squared distance from `point` to the box, 0 inside (the sphere-vs-box distance of
    /// section 5.1, supplemental listing 2). May overflow to infinity for coordinates beyond
    /// about 1e19; [`Aabb::intersects_sphere`] never does.
    #[inline]
    pub fn distance_sq(&self, point: Vec3) -> f32 {
        self.gap(point).length_squared()
    }

    /// Whether the closed ball of `radius` around `center` meets the box (the rough
    /// sphere-frustum test of section 5.1). False for `radius <= 0` or NaN (an empty bound).
    /// Divides before squaring, so it is exact where [`Aabb::distance_sq`] would overflow.
    #[inline]
    pub fn intersects_sphere(&self, center: Vec3, radius: f32) -> bool {
        if radius.is_nan() || radius <= 0.0 {
            return false;
        }
        let d = self.gap(center) / radius;
        d.max_element() <= 1.0 && d.length_squared() <= 1.0
    }

    /// The box around the frustum `{ z (u, v, rect_z) : (u, v) in [rect_min, rect_max],
    /// z in [z_min, z_max] }` (supplemental listing 2, `CalculateFrustumAABB`), for any signs
    /// of the inputs: every coordinate is bilinear in (u or v, z), so its extremes lie at the
    /// corners. `rect_z = 1` gives a view-space tile frustum with its rectangle at unit depth;
    /// in the test space of eq. (17) `rect_z` is the (3, 3) entry of BS.
    #[inline]
    pub fn frustum(rect_min: Vec2, rect_max: Vec2, rect_z: f32, z_min: f32, z_max: f32) -> Self {
        let lo = rect_min.extend(rect_z);
        let hi = rect_max.extend(rect_z);
        let corners = [lo * z_min, lo * z_max, hi * z_min, hi * z_max];
        Self {
            min: corners[0].min(corners[1]).min(corners[2]).min(corners[3]),
            max: corners[0].max(corners[1]).max(corners[2]).max(corners[3]),
        }
    }

    /// Whether `point` lies in the closed box (the brute-force counterpart of the tests of
    /// section 5.1).
    #[inline]
    pub fn contains(&self, point: Vec3) -> bool {
        point.cmpge(self.min).all() && point.cmple(self.max).all()
    }

    /// Per-axis distance from `point` to the box (0 inside).
    #[inline]
    fn gap(&self, point: Vec3) -> Vec3 {
        (self.min - point).max(point - self.max).max(Vec3::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;

    fn random_box(rng: &mut Rng) -> Aabb {
        let a = Vec3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        );
        let b = Vec3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        );
        Aabb {
            min: a.min(b),
            max: a.max(b),
        }
    }

    #[test]
    fn distance_matches_brute_force() {
        let mut rng = Rng::new(31);
        for _ in 0..200 {
            let b = random_box(&mut rng);
            let p = Vec3::new(
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
            );
            // Closest point by dense sampling of the box.
            let n = 24;
            let mut best = f32::INFINITY;
            for i in 0..=n {
                for j in 0..=n {
                    for k in 0..=n {
                        let t = Vec3::new(i as f32, j as f32, k as f32) / n as f32;
                        best = best.min((b.min + (b.max - b.min) * t - p).length_squared());
                    }
                }
            }
            let d = b.distance_sq(p);
            assert!(d <= best + 1e-5, "{d} > sampled {best}");
            let cell = ((b.max - b.min) / n as f32).length();
            assert!(d.sqrt() >= best.sqrt() - cell, "{d} vs {best}");
            assert_eq!(d == 0.0, b.contains(p));
        }
    }

    #[test]
    fn sphere_overlap_matches_brute_force() {
        let mut rng = Rng::new(32);
        let (mut hits, mut misses) = (0, 0);
        for _ in 0..400 {
            let b = random_box(&mut rng);
            let c = Vec3::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            );
            let radius = rng.range(0.05, 2.5);
            let n = 16;
            let mut sampled_hit = false;
            let mut near_hit = false;
            let cell = ((b.max - b.min) / n as f32).length();
            for i in 0..=n {
                for j in 0..=n {
                    for k in 0..=n {
                        let t = Vec3::new(i as f32, j as f32, k as f32) / n as f32;
                        let dist = (b.min + (b.max - b.min) * t - c).length();
                        sampled_hit |= dist <= radius;
                        near_hit |= dist <= radius + cell;
                    }
                }
            }
            let hit = b.intersects_sphere(c, radius);
            assert!(
                !sampled_hit || hit,
                "a box point is in the ball, test says no"
            );
            assert!(
                !hit || near_hit,
                "test says yes, but no box point is near the ball"
            );
            if hit {
                hits += 1
            } else {
                misses += 1
            }
        }
        assert!(hits > 50 && misses > 50, "{hits} hits, {misses} misses");
    }

    #[test]
    fn empty_or_extreme_spheres() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        assert!(!b.intersects_sphere(Vec3::splat(0.5), 0.0));
        assert!(!b.intersects_sphere(Vec3::splat(0.5), f32::NAN));
        assert!(!b.intersects_sphere(Vec3::splat(0.5), -1.0));
        assert!(b.intersects_sphere(Vec3::splat(0.5), 1e-30));
        assert!(b.intersects_sphere(Vec3::splat(1e30), 2e30));
        assert!(!b.intersects_sphere(Vec3::splat(1e30), 1e30));
        assert!(!b.intersects_sphere(Vec3::splat(f32::MAX), 1.0));
    }

    #[test]
    fn frustum_box_contains_the_frustum() {
        let mut rng = Rng::new(33);
        for _ in 0..200 {
            let (a, b) = (
                Vec2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
                Vec2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
            );
            let (z0, z1) = (rng.range(-3.0, 5.0), rng.range(-3.0, 5.0));
            let (z_min, z_max) = (z0.min(z1), z0.max(z1));
            let rect_z = rng.range(-2.0, 2.0);
            let bx = Aabb::frustum(a.min(b), a.max(b), rect_z, z_min, z_max);
            let mut touched = [false; 6];
            for _ in 0..400 {
                let uv = a.min(b) + (a.max(b) - a.min(b)) * Vec2::new(rng.f32(), rng.f32());
                let z = z_min + (z_max - z_min) * rng.f32();
                let p = uv.extend(rect_z) * z;
                let slack = Vec3::splat(1e-5);
                assert!(p.cmpge(bx.min - slack).all() && p.cmple(bx.max + slack).all());
            }
            // Tight: every face is reached by a corner of the frustum.
            for uv in [
                a.min(b),
                a.max(b),
                Vec2::new(a.min(b).x, a.max(b).y),
                Vec2::new(a.max(b).x, a.min(b).y),
            ] {
                for z in [z_min, z_max] {
                    let p = uv.extend(rect_z) * z;
                    for axis in 0..3 {
                        touched[axis] |= (p[axis] - bx.min[axis]).abs() < 1e-5;
                        touched[axis + 3] |= (p[axis] - bx.max[axis]).abs() < 1e-5;
                    }
                }
            }
            assert!(touched.iter().all(|&t| t));
        }
    }
}
