//! Watertight ray-triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1), 2013): rays through a shared edge or vertex hit at least one of
//! the triangles, so closed meshes do not leak light (obvhs's Möller-Trumbore test does).
use glam::{DVec3, Vec3, Vec3A};
use obvhs::triangle::Triangle;

/// A ray transformed once into the shear space of the algorithm.
#[derive(Clone, Copy, Debug)]
pub struct ShearedRay {
    origin: Vec3A,
    /// Permuted axes: kz is the dominant direction axis.
    k: [usize; 3],
    /// Shear constants (Sx, Sy, Sz).
    s: Vec3,
}

impl ShearedRay {
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        let [kx, ky, kz] = Self::axes_of(dir);
        let s = Vec3::new(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
        Self {
            origin: origin.into(),
            k: [kx, ky, kz],
            s,
        }
    }

    /// The permuted axes (kx, ky, kz) of a ray along `dir`: kz its dominant axis, kx and ky
    /// swapped where that component is negative (which keeps the triangles' winding).
    #[inline]
    pub fn axes_of(dir: Vec3) -> [usize; 3] {
        let a = dir.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if dir[kz] < 0.0 {
            [ky, kx, kz]
        } else {
            [kx, ky, kz]
        }
    }

    /// The permuted axes (kx, ky, kz): kz is the direction's dominant axis.
    pub fn axes(&self) -> [usize; 3] {
        self.k
    }

    /// The shear constants (Sx, Sy, Sz).
    pub fn shear(&self) -> Vec3 {
        self.s
    }

    /// Distance t to the triangle in units of the ray's direction, if hit with tmin < t <= tmax.
    #[inline]
    pub fn intersect(&self, tri: &Triangle, tmin: f32, tmax: f32) -> f32 {
        self.hit(tri, tmin, tmax).map_or(f32::INFINITY, |(t, _)| t)
    }

    /// The hit with tmin < t <= tmax: t and the barycentric weights of (v0, v1, v2) at it
    /// (U, V, W over their sum, the algorithm's own).
    #[inline]
    pub fn hit(&self, tri: &Triangle, tmin: f32, tmax: f32) -> Option<(f32, [f32; 3])> {
        let [kx, ky, kz] = self.k;
        let (a, b, c) = (
            tri.v0 - self.origin,
            tri.v1 - self.origin,
            tri.v2 - self.origin,
        );
        let (ax, ay) = (a[kx] - self.s.x * a[kz], a[ky] - self.s.y * a[kz]);
        let (bx, by) = (b[kx] - self.s.x * b[kz], b[ky] - self.s.y * b[kz]);
        let (cx, cy) = (c[kx] - self.s.x * c[kz], c[ky] - self.s.y * c[kz]);
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // Exactly on an edge in single precision: decide in double precision.
            let d =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            u = d(cx, by, cy, bx);
            v = d(ax, cy, ay, cx);
            w = d(bx, ay, by, ax);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let (az, bz, cz) = (self.s.z * a[kz], self.s.z * b[kz], self.s.z * c[kz]);
        let t = (u * az + v * bz + w * cz) / det;
        (t > tmin && t <= tmax).then(|| (t, [u / det, v / det, w / det]))
    }
}

/// Barycentric weights (w0, w1, w2) of point `p` in triangle (a, b, c), in double precision.
pub fn barycentric(a: Vec3, b: Vec3, c: Vec3, p: Vec3) -> (f32, f32, f32) {
    let (a, b, c, p) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3(), p.as_dvec3());
    let n: DVec3 = (b - a).cross(c - a);
    let area2 = n.length_squared();
    let w1 = (p - a).cross(c - a).dot(n) / area2;
    let w2 = (b - a).cross(p - a).dot(n) / area2;
    ((1.0 - w1 - w2) as f32, w1 as f32, w2 as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: Vec3, b: Vec3, c: Vec3) -> Triangle {
        Triangle {
            v0: a.into(),
            v1: b.into(),
            v2: c.into(),
        }
    }

    #[test]
    fn hits_inside_and_misses_outside_for_both_windings() {
        let t = tri(Vec3::ZERO, Vec3::X, Vec3::Y);
        let r = ShearedRay::new(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z);
        assert!((r.intersect(&t, 0.0, f32::INFINITY) - 1.0).abs() < 1e-6);
        let back = tri(Vec3::ZERO, Vec3::Y, Vec3::X);
        assert!((r.intersect(&back, 0.0, f32::INFINITY) - 1.0).abs() < 1e-6);
        let miss = ShearedRay::new(Vec3::new(0.8, 0.8, 1.0), Vec3::NEG_Z);
        assert_eq!(miss.intersect(&t, 0.0, f32::INFINITY), f32::INFINITY);
        assert_eq!(r.intersect(&t, 0.0, 0.5), f32::INFINITY);
    }

    /// The hit's own weights locate the hit point, for either winding and a slanted ray.
    #[test]
    fn hit_weights_reconstruct_the_hit_point() {
        let (a, b, c) = (
            Vec3::new(0.1, -0.2, 0.3),
            Vec3::new(1.4, 0.1, -0.2),
            Vec3::Y,
        );
        let origin = Vec3::new(0.3, 0.2, 2.0);
        let dir = Vec3::new(0.1, 0.05, -1.0).normalize();
        let r = ShearedRay::new(origin, dir);
        for t in [tri(a, b, c), tri(a, c, b)] {
            let (d, [w0, w1, w2]) = r.hit(&t, 0.0, f32::INFINITY).unwrap();
            let p = Vec3::from(t.v0) * w0 + Vec3::from(t.v1) * w1 + Vec3::from(t.v2) * w2;
            assert!((w0 + w1 + w2 - 1.0).abs() < 1e-6);
            assert!((p - (origin + dir * d)).length() < 1e-5, "{p}");
        }
    }

    /// Rays through the shared diagonal of a quad hit one of its two triangles, always.
    #[test]
    fn shared_edges_do_not_leak() {
        let (p0, p1, p2, p3) = (
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        );
        let (t0, t1) = (tri(p0, p1, p2), tri(p0, p2, p3));
        let origin = Vec3::new(0.123, -0.456, 3.0);
        for k in 0..10_000 {
            let s = k as f32 / 10_000.0 * 1.8 - 0.9;
            let target = Vec3::new(s, s, 0.0);
            let r = ShearedRay::new(origin, (target - origin).normalize());
            let hit =
                r.intersect(&t0, 0.0, f32::INFINITY)
                    .min(r.intersect(&t1, 0.0, f32::INFINITY));
            assert!(hit.is_finite(), "leak at {target}");
        }
    }

    #[test]
    fn barycentrics_reconstruct_the_point() {
        let (a, b, c) = (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
        );
        let p = 0.2 * a + 0.5 * b + 0.3 * c;
        let (w0, w1, w2) = barycentric(a, b, c, p);
        assert!((w0 - 0.2).abs() < 1e-6 && (w1 - 0.5).abs() < 1e-6 && (w2 - 0.3).abs() < 1e-6);
    }
}
