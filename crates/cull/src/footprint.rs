//! The screen pixels a VPL's bound may cover, for the `binned` strategy, written once for one
//! `f32` and for eight lanes ([`slc_bounds::lanes`]). The bound (the section-6 sphere or the
//! GGX spheroid of eq. 12-15, grown by `BOUND_SLACK`) is an ellipsoid `{c + M w : |w| <= 1}`
//! symmetric about a unit axis a: semi-axis `along` on a, `across` perpendicular to it, so
//! M Mᵀ = across² I + s a aᵀ with s = along² − across².
//!
//! A point x of depth z > 0 projects to u = x/z, i.e. lies on the plane through the eye with
//! normal (1, 0, −u). That plane meets the ellipsoid iff |n·c| <= |Mᵀn|: with the entries
//! xx, xz, zz of M Mᵀ called A, B, D, iff qa u² − 2 qb u + qc <= 0 with qa = c_z² − D,
//! qb = c_x c_z − B, qc = c_x² − A. When the whole ellipsoid lies in front of the eye
//! (qa > 0, c_z > 0) those u form the interval between the roots (qb ± √disc)/qa, and the
//! discriminant qb² − qa qc is, multiplied out,
//!
//!   disc = across² (c_x² + c_z²) + s (a_x c_z − a_z c_x)² − across² (across² + s (a_x² + a_z²)),
//!
//! whose terms cancel only when the bound nearly reaches the eye: for a small, far bound the
//! f32 discriminant keeps its digits. The same holds for v = y/z.
//!
//! **Rounding.** Everything is f32. The bound's centre and axis carry the rounding of their
//! own formation and of the view rotation, a few ε of the bound's `size` (|q − eye| +
//! |c − q| + along); both semi-axes grow by 8 ε size, which puts every point within that
//! distance of the bound inside the grown one. The discriminant grows by 1e-6 of its terms'
//! magnitude before its root, and each end of the span by 1e-5 of the magnitudes it is
//! formed from, plus 1e-4 of its own: with qa at least 1e-2 c_z² (nearer to the eye, the
//! bound counts as reaching it), that is over 40 times the f32 error of each. The screen
//! position grows by 1e-6 of its value and 1e-3 pixel. The tests check the spans against an
//! f64 reference.
use slc_bounds::lanes::{dot, max, Real};

/// A VPL's bound in lanes: its centre c relative to the eye (world axes), unit axis a, the
/// semi-axes along a and across it (along >= across), and `size`, the magnitude its rounding
/// scales with: |q − eye| + |c − q| + along.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bound<R> {
    pub center: [R; 3],
    pub axis: [R; 3],
    pub along: R,
    pub across: R,
    pub size: R,
}

/// The view and image as the footprint reads them, in lanes: the world-to-view rotation's
/// rows, the map from the image plane at unit depth to screen pixels (X = u scale + offset,
/// per axis) and the smallest depth of any sample.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ScreenMap<R> {
    pub rows: [[R; 3]; 3],
    pub scale: [R; 2],
    pub offset: [R; 2],
    pub near: R,
}

/// Where a bound's points in front of the eye project: the screen rectangle `[lo, hi]` (in
/// pixels, continuous: pixel (i, j) covers `[i, i + 1) x [j, j + 1)`), unless it lies nearer
/// than every sample (`nowhere`) or reaches the eye's plane (`everywhere`, the rectangle
/// unset).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Footprint<R: Real> {
    pub lo: [R; 2],
    pub hi: [R; 2],
    pub nowhere: R::Mask,
    pub everywhere: R::Mask,
}

/// `|x|`.
#[inline(always)]
fn abs<R: Real>(x: R) -> R {
    max(x, -x)
}

/// The footprint of `b` (see the module). No closures: in the AVX2 kernels a closure is a
/// function of its own, compiled without their target features.
#[inline(always)]
pub(crate) fn footprint<R: Real>(b: &Bound<R>, map: &ScreenMap<R>) -> Footprint<R> {
    let grow = R::splat(8.0 * f32::EPSILON) * b.size;
    let (along, across) = (b.along + grow, b.across + grow);
    let [x, y, z] = map.rows;
    let c = [dot(x, b.center), dot(y, b.center), dot(z, b.center)];
    let a = [dot(x, b.axis), dot(y, b.axis), dot(z, b.axis)];
    let across_sq = across * across;
    let s = along * along - across_sq;
    let d = across_sq + s * a[2] * a[2];
    let half_z = d.sqrt();
    let far = c[2] + half_z + R::splat(1e-5) * (abs(c[2]) + half_z);
    // Nearer than every sample (false for NaN: such a bound covers everything).
    let nowhere = map.near.gt(far);
    let qa = c[2] * c[2] - d;
    let everywhere = !(qa.gt(R::splat(1e-2) * c[2] * c[2]) & c[2].gt(R::splat(0.0)));
    let conic = Conic {
        c,
        a,
        across_sq,
        s,
        qa,
    };
    let (x0, x1) = conic.span(0, map);
    let (y0, y1) = conic.span(1, map);
    Footprint {
        lo: [x0, y0],
        hi: [x1, y1],
        nowhere,
        everywhere,
    }
}

/// A bound in view space as the spans read it: its centre c, axis a, across², s =
/// along² − across² and qa = c_z² − (M Mᵀ)_zz.
struct Conic<R> {
    c: [R; 3],
    a: [R; 3],
    across_sq: R,
    s: R,
    qa: R,
}

impl<R: Real> Conic<R> {
    /// The screen span `[X0, X1]` along image axis `k` (0: x, 1: y), grown as the module
    /// says.
    #[inline(always)]
    fn span(&self, k: usize, map: &ScreenMap<R>) -> (R, R) {
        let (c, a, across_sq, s) = (&self.c, &self.a, self.across_sq, self.s);
        let e = a[k] * c[2] - a[2] * c[k];
        let q = across_sq * (c[k] * c[k] + c[2] * c[2]) + s * e * e;
        let det = across_sq * (across_sq + s * (a[k] * a[k] + a[2] * a[2]));
        let disc = max(q - det, R::splat(0.0)) + R::splat(1e-6) * (q + det);
        let root = disc.sqrt();
        let (cross, tilt) = (c[k] * c[2], s * a[k] * a[2]);
        let qb = cross - tilt;
        let (u0, u1) = ((qb - root) / self.qa, (qb + root) / self.qa);
        let pad = R::splat(1e-5) * (abs(cross) + abs(tilt) + root) / self.qa
            + R::splat(1e-4) * (abs(u0) + abs(u1));
        let x0 = (u0 - pad) * map.scale[k] + map.offset[k];
        let x1 = (u1 + pad) * map.scale[k] + map.offset[k];
        (
            x0 - (R::splat(1e-6) * abs(x0) + R::splat(1e-3)),
            x1 + (R::splat(1e-6) * abs(x1) + R::splat(1e-3)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use crate::view::CullView;
    use glam::{DVec2, Mat3, Quat, Vec3};
    use slc_core::Camera;

    /// A 640x360 view from `eye` along −z.
    fn view(eye: Vec3) -> CullView {
        let cam = Camera::look_at(eye, eye - Vec3::Z, Vec3::Y, 1.0).unwrap();
        CullView::new(&cam, 640, 360).unwrap()
    }

    fn screen_map(view: &CullView, near: f32) -> ScreenMap<f32> {
        let (scale, offset) = view.screen_map();
        let r = view.rotation();
        ScreenMap {
            rows: [0, 1, 2].map(|i| r.row(i).to_array()),
            scale: scale.map(|v| v as f32),
            offset: offset.map(|v| v as f32),
            near,
        }
    }

    /// A random spheroid (α from 1e-3 to 1) or sphere around q: its rotation and semi-axes.
    fn random_bound(rng: &mut Rng) -> (Mat3, Vec3) {
        let axis = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let rotation = Mat3::from_quat(Quat::from_axis_angle(
            axis.try_normalize().unwrap_or(Vec3::X),
            rng.range(0.0, 6.3),
        ));
        let r = 10f32.powf(rng.range(-5.0, 1.5));
        let alpha = 10f32.powf(rng.range(-3.0, 0.0));
        let along = if rng.f32() < 0.2 {
            r
        } else {
            (1.0 + alpha * alpha) / (2.0 * alpha) * r
        };
        (rotation, Vec3::new(along, r, r))
    }

    /// Every point of random bounds that lies in front of the nearest depth projects into
    /// the f32 footprint (or the footprint covers everything): against the f64 projection of
    /// points on (and just inside) the bound's surface, anywhere in scenes far from the origin,
    /// from far away to around the eye. And the rectangles are tight where nothing is near
    /// the eye.
    #[test]
    fn points_in_front_project_into_the_footprint() {
        let mut rng = Rng(0x5eed_1234_dead_beef);
        let (mut tight, mut bounded) = (0, 0);
        for case in 0..6000 {
            let eye =
                Vec3::new(rng.range(-1e3, 1e3), rng.range(-1e3, 1e3), 0.0) * (case % 3) as f32;
            let v = view(eye);
            let near = 10f32.powf(rng.range(-3.0, 0.0));
            let map = screen_map(&v, near);
            let (rotation, semi) = random_bound(&mut rng);
            let distance = 10f32.powf(rng.range(-2.0, 3.0));
            let q = eye
                + Vec3::new(rng.range(-1.0, 1.0), rng.range(-0.6, 0.6), -1.0) * distance
                + Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                ) * semi.x;
            let relative = q - eye;
            let bound = Bound {
                center: relative.to_array(),
                axis: rotation.x_axis.to_array(),
                along: semi.x,
                across: semi.y,
                size: relative.length() + semi.x,
            };
            let f = footprint(&bound, &map);
            let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
            for _ in 0..300 {
                let w = Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                );
                let Some(w) = w.try_normalize() else { continue };
                let local = rotation.as_dmat3()
                    * (semi.as_dvec3() * w.as_dvec3() * rng.range64(0.999, 1.0));
                let x = v.rotate(v.relative(q) + local);
                if x.z < f64::from(near) {
                    continue;
                }
                assert!(
                    !f.nowhere,
                    "case {case}: a point at depth {} >= {near}",
                    x.z
                );
                if f.everywhere {
                    continue;
                }
                let at = v.to_screen(DVec2::new(x.x, x.y) / x.z);
                let (flo, fhi) = (
                    DVec2::new(f.lo[0].into(), f.lo[1].into()),
                    DVec2::new(f.hi[0].into(), f.hi[1].into()),
                );
                assert!(
                    at.cmpge(flo).all() && at.cmple(fhi).all(),
                    "case {case}: {at} outside {flo}..{fhi}"
                );
                (lo, hi) = (lo.min(at), hi.max(at));
            }
            if !f.everywhere && !f.nowhere && lo.x.is_finite() {
                bounded += 1;
                let size = (hi - lo).max_element().max(1.0);
                let slack = (DVec2::new(f.lo[0].into(), f.lo[1].into()) - lo)
                    .abs()
                    .max((DVec2::new(f.hi[0].into(), f.hi[1].into()) - hi).abs())
                    .max_element();
                if slack < 0.1 * size {
                    tight += 1;
                }
            }
        }
        assert!(
            bounded > 2000 && tight > bounded * 9 / 10,
            "{tight} of {bounded} tight"
        );
    }

    /// Bounds behind the eye cover nothing, around it everything, and non-finite or
    /// overflowing bounds everything.
    #[test]
    fn bounds_behind_around_or_beyond_f32() {
        let v = view(Vec3::ZERO);
        let map = screen_map(&v, 0.1);
        let sphere = |at: Vec3, r: f32| Bound {
            center: at.to_array(),
            axis: [1.0, 0.0, 0.0],
            along: r,
            across: r,
            size: at.length() + r,
        };
        assert!(footprint(&sphere(Vec3::new(0.0, 0.0, 5.0), 1.0), &map).nowhere);
        let around = footprint(&sphere(Vec3::new(0.0, 0.3, 0.2), 1.0), &map);
        assert!(!around.nowhere && around.everywhere);
        for r in [1e19, f32::MAX, f32::INFINITY, f32::NAN] {
            let f = footprint(&sphere(Vec3::new(0.0, 0.0, -50.0), r), &map);
            let covers = f.everywhere
                || !(f.lo[0] > 0.0 || f.lo[1] > 0.0 || f.hi[0] < 640.0 || f.hi[1] < 360.0);
            assert!(!f.nowhere && covers, "radius {r}: {f:?}");
        }
    }
}
