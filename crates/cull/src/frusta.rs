//! A tile's frusta in view space and the rough bound-vs-frustum tests of Modified HalfZ
//! (paper sections 5.1-5.2, supplemental Listing 2), in f64.
//!
//! A tile frustum is `{ z (u, v, 1) : (u, v) in the tile's image-plane rectangle, z in a
//! depth range }`. A sphere is tested against the frustum's view-space box; an ellipsoid
//! against the box of the frustum's image in its test space BS (eq. 16-17): the rectangle's
//! corners mapped by BS, bounded, and swept over the depth range. Every row of BS is used, so
//! the box stays conservative even though the rounded B of eq. (17) leaves tiny non-zero
//! entries where Listing 2 assumes zeros.
use crate::vpl_bounds::{ViewEllipsoid, ViewSphere};
use glam::{DVec2, DVec3};

/// Relative growth of a tile's frusta: the image-plane rectangle grows on each side by
/// 1e-6 (1 + its largest |u| or |v|), the depth ranges by the factors 1 ∓ 1e-6. The rectangle
/// and ranges are built from the very samples they must contain, so this only has to cover
/// the f64 rounding of the projection to the image plane, of the box corners and of the
/// test-space mapping (about 1e-16 relative, amplified at most by the eccentricity
/// 1/(2α) = 500 of the sharpest spheroid): a millionth of a tile's width costs nothing.
pub const FRUSTUM_SLACK: f64 = 1e-6;

/// A closed axis-aligned box.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Box3 {
    min: DVec3,
    max: DVec3,
}

impl Box3 {
    /// The box around `{ z w : w in [lo, hi], z in [z0, z1] }` for 0 < z0 <= z1
    /// (`CalculateFrustumAABB` of Listing 2 with the rectangle's depth row included): each
    /// coordinate is bilinear in (w, z), so its extremes lie at the corners.
    #[inline]
    fn swept(lo: DVec3, hi: DVec3, [z0, z1]: [f64; 2]) -> Self {
        Self {
            min: (lo * z0).min(lo * z1),
            max: (hi * z0).max(hi * z1),
        }
    }

    /// The box around the image of the box `center ± half` under the ellipsoid's test space
    /// BS (eq. 16-17): BS·center ± |BS| half, since BS is linear.
    #[inline]
    pub(crate) fn in_test_space(e: &ViewEllipsoid, center: DVec3, half: DVec3) -> Self {
        let [a, b, c] = e.columns;
        let mapped = a * center.x + b * center.y + c * center.z;
        let extent = a.abs() * half.x + b.abs() * half.y + c.abs() * half.z;
        Self {
            min: mapped - extent,
            max: mapped + extent,
        }
    }

    /// Whether the closed ball of squared radius `radius_sq` around `center` meets the box
    /// (`ComputeSquaredDistanceToBox` of Listing 2).
    #[inline]
    pub(crate) fn meets_ball(&self, center: DVec3, radius_sq: f64) -> bool {
        let gap = (self.min - center).max(center - self.max).max(DVec3::ZERO);
        gap.length_squared() <= radius_sq
    }
}

/// The frusta of one tile: its image-plane rectangle and the depth ranges of its clusters
/// (see `depth`), grown by [`FRUSTUM_SLACK`], with the view-space boxes the sphere test uses.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct TileFrusta {
    rect: [DVec2; 2],
    /// Depth range of the whole tile, then of each cluster.
    whole: [f64; 2],
    ranges: Vec<[f64; 2]>,
    whole_box: Box3,
    boxes: Vec<Box3>,
}

impl TileFrusta {
    /// Sets the tile's rectangle `[lo, hi]` at unit depth and its clusters' depth ranges
    /// (positive, at most 32), grown by [`FRUSTUM_SLACK`].
    pub(crate) fn set(&mut self, lo: DVec2, hi: DVec2, clusters: &[[f64; 2]]) {
        debug_assert!(!clusters.is_empty() && clusters.len() <= 32);
        let pad = FRUSTUM_SLACK * (1.0 + lo.abs().max(hi.abs()).max_element());
        self.rect = [lo - pad, hi + pad];
        let grow = |[z0, z1]: [f64; 2]| [z0 * (1.0 - FRUSTUM_SLACK), z1 * (1.0 + FRUSTUM_SLACK)];
        self.ranges.clear();
        self.ranges.extend(clusters.iter().map(|&r| grow(r)));
        self.whole = self
            .ranges
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &[a, b]| {
                [lo.min(a), hi.max(b)]
            });
        let (rect_lo, rect_hi) = (self.rect[0].extend(1.0), self.rect[1].extend(1.0));
        self.whole_box = Box3::swept(rect_lo, rect_hi, self.whole);
        self.boxes.clear();
        self.boxes.extend(
            self.ranges
                .iter()
                .map(|&r| Box3::swept(rect_lo, rect_hi, r)),
        );
    }

    /// The whole tile as the exact tests see it: the grown image-plane rectangle `[lo, hi]`,
    /// the depth range of all its clusters, and the view-space box of that frustum.
    pub(crate) fn whole(&self) -> ([DVec2; 2], [f64; 2], (DVec3, DVec3)) {
        (
            self.rect,
            self.whole,
            (self.whole_box.min, self.whole_box.max),
        )
    }

    /// The clusters a view-space sphere may touch, as a bit mask (bit i: cluster i): the
    /// sphere-vs-frustum-box test of Modified HalfZ, first against the whole tile.
    #[inline]
    pub(crate) fn sphere_hits(&self, sphere: &ViewSphere) -> u32 {
        if !self.whole_box.meets_ball(sphere.center, sphere.radius_sq) {
            return 0;
        }
        if self.boxes.len() == 1 {
            return 1;
        }
        self.boxes
            .iter()
            .enumerate()
            .filter(|(_, b)| b.meets_ball(sphere.center, sphere.radius_sq))
            .fold(0, |mask, (i, _)| mask | 1 << i)
    }

    /// The clusters an ellipsoid may touch, as a bit mask: the unit ball at BS·c against the
    /// box of each cluster frustum's image under BS (section 5.2, Listing 2), first against
    /// the whole tile. The rectangle's image is bounded per coordinate, which equals the
    /// bounding rectangle of its four mapped corners: `BS (u, v, 1)` is affine in u and v.
    #[inline]
    pub(crate) fn ellipsoid_hits(&self, e: &ViewEllipsoid) -> u32 {
        let [cu, cv, cz] = e.columns;
        let [lo, hi] = self.rect;
        let (u0, u1) = (cu * lo.x, cu * hi.x);
        let (v0, v1) = (cv * lo.y, cv * hi.y);
        let image_lo = cz + u0.min(u1) + v0.min(v1);
        let image_hi = cz + u0.max(u1) + v0.max(v1);
        if !Box3::swept(image_lo, image_hi, self.whole).meets_ball(e.center, 1.0) {
            return 0;
        }
        if self.ranges.len() == 1 {
            return 1;
        }
        self.ranges
            .iter()
            .enumerate()
            .filter(|(_, &r)| Box3::swept(image_lo, image_hi, r).meets_ball(e.center, 1.0))
            .fold(0, |mask, (i, _)| mask | 1 << i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use glam::{DMat3, Mat3, Quat, Vec2, Vec3};
    use slc_bounds::{TestSpace, TileFrustum};

    fn ellipsoid(space: &TestSpace, center: Vec3) -> ViewEllipsoid {
        let m = space.matrix().as_dmat3();
        ViewEllipsoid {
            columns: [m.x_axis, m.y_axis, m.z_axis],
            center: m * center.as_dvec3(),
            index: 0,
        }
    }

    fn random_case(rng: &mut Rng) -> (TileFrustum, Mat3, Vec3, Vec3) {
        let (a, b) = (
            Vec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
            Vec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
        );
        let (z0, z1) = (rng.range(0.1, 10.0), rng.range(0.1, 10.0));
        let tile = TileFrustum::new(a.min(b), a.max(b), z0.min(z1), z0.max(z1)).unwrap();
        let axis = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let rotation = Mat3::from_quat(Quat::from_axis_angle(
            axis.try_normalize().unwrap_or(Vec3::Z),
            rng.range(0.0, std::f32::consts::TAU),
        ));
        let alpha = 10f32.powf(rng.range(-3.0, 0.0));
        let r = rng.range(0.05, 2.0);
        let semi = Vec3::new((1.0 + alpha * alpha) / (2.0 * alpha) * r, r, r);
        let center = Vec3::new(
            rng.range(-6.0, 6.0),
            rng.range(-6.0, 6.0),
            rng.range(-2.0, 12.0),
        );
        (tile, rotation, semi, center)
    }

    fn frusta(tile: &TileFrustum) -> TileFrusta {
        let mut f = TileFrusta::default();
        f.set(
            tile.rect_min().as_dvec2(),
            tile.rect_max().as_dvec2(),
            &[[f64::from(tile.z_min()), f64::from(tile.z_max())]],
        );
        f
    }

    /// The f64 tests agree with the f32 reference tests of slc-bounds (`TestSpace::intersects`,
    /// `Aabb::intersects_sphere`): never a miss where those hit, and a hit only within the
    /// slack where they miss.
    #[test]
    fn agrees_with_slc_bounds() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let (mut hits, mut misses) = (0, 0);
        for _ in 0..20_000 {
            let (tile, rotation, semi, center) = random_case(&mut rng);
            let f = frusta(&tile);
            let space = TestSpace::new(rotation, semi, center).unwrap();
            let ours = f.ellipsoid_hits(&ellipsoid(&space, center)) == 1;
            let reference = space.intersects(&tile);
            assert!(
                ours || !reference,
                "missed: {tile:?} {rotation:?} {semi} {center}"
            );
            if ours != reference {
                // Only a near-tangent case may differ: shrink the slack away and it agrees.
                let grown = TestSpace::new(rotation, semi * 1.0001, center).unwrap();
                assert!(grown.intersects(&tile), "hit far from the reference");
            }
            let sphere = ViewSphere {
                center: center.as_dvec3(),
                radius_sq: f64::from(semi.y).powi(2),
                index: 0,
            };
            let ours = f.sphere_hits(&sphere) == 1;
            let reference = tile.aabb().intersects_sphere(center, semi.y);
            assert!(ours || !reference);
            if ours {
                hits += 1;
            } else {
                misses += 1;
            }
        }
        assert!(hits > 2000 && misses > 2000, "{hits} hits, {misses} misses");
    }

    /// Brute force: a point of the ellipsoid inside a cluster's frustum is always reported
    /// for that cluster (and the whole-tile pre-test never rejects it).
    #[test]
    fn points_in_both_are_hits() {
        let mut rng = Rng(77);
        let mut checked = 0;
        for _ in 0..3000 {
            let (tile, rotation, semi, center) = random_case(&mut rng);
            let split = 0.5 * (tile.z_min() + tile.z_max());
            let mut f = TileFrusta::default();
            let ranges = [
                [f64::from(tile.z_min()), f64::from(split)],
                [f64::from(split), f64::from(tile.z_max())],
            ];
            f.set(
                tile.rect_min().as_dvec2(),
                tile.rect_max().as_dvec2(),
                &ranges,
            );
            let space = TestSpace::new(rotation, semi, center).unwrap();
            let e = ellipsoid(&space, center);
            let m = DMat3::from_cols(e.columns[0], e.columns[1], e.columns[2]);
            let mask = f.ellipsoid_hits(&e);
            for _ in 0..50 {
                let d = Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                );
                if d.length_squared() > 1.0 {
                    continue;
                }
                let p = center + rotation * (semi * d);
                if !tile.contains(p) {
                    continue;
                }
                assert!((m * p.as_dvec3() - e.center).length() <= 1.0 + 1e-5);
                let cluster = usize::from(f64::from(p.z) >= f64::from(split));
                assert!(
                    mask & (1 << cluster) != 0,
                    "point {p} of cluster {cluster} missed"
                );
                checked += 1;
            }
        }
        assert!(checked > 500, "{checked}");
    }
}
