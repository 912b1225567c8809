//! [`BoxBound::may_exceed_xi`] in f32, written once for one VPL and for eight at a time
//! ([`crate::lanes`]): the test a CPU shader runs for every VPL of a light list against the
//! box of the receivers it is about to shade, eight VPLs per test.
//!
//! The bound itself is formed in f64 ([`BoxBound`]) and only rounded to f32 here; the test
//! then follows `BoxBound::may_exceed_xi` step for step in f32, like the GPU's
//! `box_bound.wgsl`. Besides the f64 test's slacks ([`CONE_SLACK`] on the cone's half-angle,
//! [`PROBABILITY_SLACK`](super::PROBABILITY_SLACK) on p, each of which covers the shader's rounding tenfold or more)
//! every cosine the test compares is moved by [`COS_SLACK`] towards the side that keeps
//! more: a cosine formed in f32 from unit vectors is off by about 1e-7 (the rounded unit
//! vectors of the bound included). The sine of the angle between a direction and the cone's
//! axis is |u × a|, not sqrt(1 − cos²): near cos = ±1 that root turns the cosine's 1e-7 into
//! an angle off by up to 6e-4, far more than the slacks. The other f32 roundings (some 40
//! of 6e-8 in the value compared with δ ξ l²) stay far below
//! [`PROBABILITY_SLACK`](super::PROBABILITY_SLACK), as long as δ ξ l² is a normal float:
//! below 2⁻¹⁰⁰ the test keeps the VPL.
//!
//! The box is given in the shader's own coordinates, and the test forms its offsets from
//! each VPL as the shader forms d = x − q (f32 subtraction): rounding is monotone, so every
//! offset the shader forms for a receiver in `[lo, hi]` lies in `[lo − q, hi − q]` as
//! rounded here.
use super::{BoxBound, Lobe, CONE_SLACK};
use crate::fresnel::{dielectric, dielectric_lanes, DIELECTRIC_ULPS};
use crate::ggx::g1_over_cos_lanes;
use crate::lanes::{
    clamp01, cross, dot, gather, gather3, gather_flags, load_all, max, min, Lanes8, Real, F8,
};
use crate::Fresnel;
use core::f32::consts::PI;
use glam::Vec3;

/// Added to (or, for a smallest cosine, taken from) every cosine the f32 test compares: the
/// f32 rounding of a cosine formed from unit vectors is about 1e-7 (as in `box_bound.wgsl`).
pub const COS_SLACK: f32 = 1e-6;

/// One VPL's [`BoxBound`] at its position in f32 (`BoxBoundLanes<f32>`), or eight VPLs'
/// (`BoxBoundLanes<F8>`, loaded as any [`Lanes8`]). The largest Fresnel factor over the half
/// vectors with ωi·ωh in [c, 1] is `Fresnel::max_from(c)`: Schlick's F0 + (1 − F0)(1 − c)⁵
/// (a = F0, b = 1 − F0 per channel), or a dielectric's larger value at the two ends of the
/// range (a = F(1), b = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxBoundLanes<R: Real> {
    /// The VPL's position q, which the offsets are formed from.
    position: [R; 3],
    normal: [R; 3],
    /// [`BoxBound`]'s largest intensity in any direction.
    peak: R,
    /// δ ξ / (1 + [`PROBABILITY_SLACK`](super::PROBABILITY_SLACK)).
    delta_xi: R,
    flux: [R; 3],
    fresnel_a: [R; 3],
    fresnel_b: [R; 3],
    /// A dielectric's relative index η (1 for Schlick's).
    eta: R,
    alpha: R,
    omega_i: [R; 3],
    omega_u: [R; 3],
    cos_h_max: R,
    /// G1(ωi)/(4 ωi·n).
    g1_i: R,
    /// The α whose G1 bounds G1(ωo), 0 where G1(ωo) is bounded by 1.
    g1_o_alpha: R,
    glossy: R::Mask,
    dielectric: R::Mask,
    /// Set for a VPL without a bound: every box passes.
    always: R::Mask,
}

impl BoxBound {
    /// This bound in f32 for the VPL at `position` (the f32 position the shader forms its
    /// offsets from), for [`BoxBoundLanes::may_exceed_xi`].
    pub fn to_f32(&self, position: Vec3) -> BoxBoundLanes<f32> {
        let mut out = BoxBoundLanes {
            position: position.to_array(),
            normal: self.normal.as_vec3().to_array(),
            peak: self.peak as f32,
            delta_xi: self.delta_xi_shrunk as f32,
            ..BoxBoundLanes::ALWAYS
        };
        out.always = false;
        if let Lobe::Glossy {
            flux,
            fresnel,
            alpha,
            omega_i,
            omega_u,
            cos_h_max,
            g1_i,
            g1_o_alpha,
        } = self.lobe
        {
            match fresnel {
                Fresnel::Schlick(f0) => {
                    out.fresnel_a = f0.to_array();
                    out.fresnel_b = (Vec3::ONE - f0).to_array();
                }
                Fresnel::Dielectric(eta) => {
                    out.fresnel_a = [dielectric(eta, 1.0); 3];
                    out.eta = eta;
                    out.dielectric = true;
                }
            }
            out.flux = flux.to_array();
            out.alpha = alpha as f32;
            out.omega_i = omega_i.as_vec3().to_array();
            out.omega_u = omega_u.as_vec3().to_array();
            out.cos_h_max = cos_h_max as f32;
            out.g1_i = g1_i as f32;
            out.g1_o_alpha = g1_o_alpha.unwrap_or(0.0);
            out.glossy = true;
        }
        out
    }
}

impl BoxBoundLanes<f32> {
    /// A VPL without a bound: every box passes.
    pub const ALWAYS: Self = Self {
        position: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
        peak: f32::INFINITY,
        delta_xi: 0.0,
        flux: [0.0; 3],
        fresnel_a: [1.0; 3],
        fresnel_b: [0.0; 3],
        eta: 1.0,
        alpha: 1.0,
        omega_i: [0.0, 0.0, 1.0],
        omega_u: [0.0, 0.0, 1.0],
        cos_h_max: 0.0,
        g1_i: 0.0,
        g1_o_alpha: 0.0,
        glossy: false,
        dielectric: false,
        always: true,
    };
}

impl BoxBoundLanes<F8> {
    /// The bounds of eight VPLs, one per lane.
    pub fn gather(of: [&BoxBoundLanes<f32>; 8]) -> Self {
        let of = &of;
        Self {
            position: gather3(of, |b| b.position),
            normal: gather3(of, |b| b.normal),
            peak: gather(of, |b| b.peak),
            delta_xi: gather(of, |b| b.delta_xi),
            flux: gather3(of, |b| b.flux),
            fresnel_a: gather3(of, |b| b.fresnel_a),
            fresnel_b: gather3(of, |b| b.fresnel_b),
            eta: gather(of, |b| b.eta),
            alpha: gather(of, |b| b.alpha),
            omega_i: gather3(of, |b| b.omega_i),
            omega_u: gather3(of, |b| b.omega_u),
            cos_h_max: gather(of, |b| b.cos_h_max),
            g1_i: gather(of, |b| b.g1_i),
            g1_o_alpha: gather(of, |b| b.g1_o_alpha),
            glossy: gather_flags(of, |b| b.glossy),
            dielectric: gather_flags(of, |b| b.dielectric),
            always: gather_flags(of, |b| b.always),
        }
    }

    /// The eight lanes as `L` ([`Lanes8::load`]).
    #[inline(always)]
    pub fn load<L: Lanes8>(&self) -> BoxBoundLanes<L> {
        BoxBoundLanes {
            position: load_all(&self.position),
            normal: load_all(&self.normal),
            peak: L::load(&self.peak),
            delta_xi: L::load(&self.delta_xi),
            flux: load_all(&self.flux),
            fresnel_a: load_all(&self.fresnel_a),
            fresnel_b: load_all(&self.fresnel_b),
            eta: L::load(&self.eta),
            alpha: L::load(&self.alpha),
            omega_i: load_all(&self.omega_i),
            omega_u: load_all(&self.omega_u),
            cos_h_max: L::load(&self.cos_h_max),
            g1_i: L::load(&self.g1_i),
            g1_o_alpha: L::load(&self.g1_o_alpha),
            glossy: L::load_mask(&self.glossy),
            dielectric: L::load_mask(&self.dielectric),
            always: L::load_mask(&self.always),
        }
    }
}

impl<R: Real> BoxBoundLanes<R> {
    /// Whether p(ωo, l) > ξ may hold at some receiver in the box `[lo, hi]` (in the shader's
    /// coordinates, the same in every lane) for each lane's VPL: [`BoxBound::may_exceed_xi`]
    /// in f32 with the slacks of the module docs. False only where every offset the shader
    /// forms from a point of the box has p <= ξ. A box whose offsets are not finite (or whose
    /// squared length overflows) keeps every VPL, and so does a threshold δ ξ l² below 2⁻¹⁰⁰,
    /// where f32 rounding is no longer relative.
    #[inline(always)]
    pub fn may_exceed_xi(&self, lo: [R; 3], hi: [R; 3]) -> R::Mask {
        let (zero, one) = (R::splat(0.0), R::splat(1.0));
        let q = self.position;
        let lo = [lo[0] - q[0], lo[1] - q[1], lo[2] - q[2]];
        let hi = [hi[0] - q[0], hi[1] - q[1], hi[2] - q[2]];
        // No closures here: one is compiled without the AVX2 kernel's target features, and
        // the intrinsics inside it become calls.
        let gap = [
            max(max(lo[0], -hi[0]), zero),
            max(max(lo[1], -hi[1]), zero),
            max(max(lo[2], -hi[2]), zero),
        ];
        let l2_min = dot(gap, gap);
        let around = !l2_min.gt(zero);
        let big = R::splat(f32::MAX);
        let finite = dot(lo, lo).le(big) & dot(hi, hi).le(big);
        let threshold = self.delta_xi * l2_min;
        let normal_threshold = threshold.gt(R::splat(TINY_THRESHOLD));
        let bright = !self.peak.le(threshold);
        // h = the largest n·d over the box (at a corner): ωo·n <= h/|d|.
        let n = self.normal;
        let h = max(n[0] * lo[0], n[0] * hi[0])
            + max(n[1] * lo[1], n[1] * hi[1])
            + max(n[2] * lo[2], n[2] * hi[2]);
        let far = [
            max(abs(lo[0]), abs(hi[0])),
            max(abs(lo[1]), abs(hi[1])),
            max(abs(lo[2]), abs(hi[2])),
        ];
        let slack_sq = R::splat((CONE_SLACK * CONE_SLACK) as f32);
        let below = zero.gt(h) & (h * h).gt(slack_sq * dot(far, far));
        let cone = Cone::around(lo, hi);
        let plane_cos = max(h, zero) / l2_min.sqrt() + R::splat(CONE_SLACK as f32);
        let cos_o = min(cone.max_cos(n), plane_cos);
        let facing = cos_o.gt(zero);
        // A glossy lobe: D(cos(θ_min/2)) of eq. (7) with sin²(θ/2) = (1 − cos θ)/2.
        let sin2 = R::splat(0.5) * (one - cone.max_cos(self.omega_u));
        let a2 = self.alpha * self.alpha;
        let denom = a2 + (one - a2) * sin2;
        let d = a2 / (R::splat(PI) * denom * denom);
        // G1(ωo) <= G1 of the smallest α at the largest cos θo (eq. 8), or 1.
        let c = min(cos_o, one);
        let g1 = g1_over_cos_lanes(self.g1_o_alpha * self.g1_o_alpha, c) * c;
        let g1_o = R::select(self.g1_o_alpha.gt(zero), g1, one);
        // The smallest ωi·ωh over the cone, no smaller than cos θh_max; F at it.
        let cos_h = max(
            max(R::splat(0.5) * (one + cone.min_cos(self.omega_i)), zero).sqrt(),
            self.cos_h_max,
        );
        let t = one - clamp01(cos_h);
        let m = t * (t * t) * (t * t);
        // A dielectric's far end a few ulps further, as `Fresnel::max_from` takes it.
        let past = cos_h * R::splat(1.0 - DIELECTRIC_ULPS * f32::EPSILON);
        let far = crate::branch!(R, self.dielectric, dielectric_lanes(self.eta, past), zero);
        let (a, b) = (self.fresnel_a, self.fresnel_b);
        let fresnel = [
            R::select(self.dielectric, max(a[0], far), a[0] + b[0] * m),
            R::select(self.dielectric, max(a[1], far), a[1] + b[1] * m),
            R::select(self.dielectric, max(a[2], far), a[2] + b[2] * m),
        ];
        let flux = self.flux;
        let f = max(
            max(flux[0] * fresnel[0], flux[1] * fresnel[1]),
            flux[2] * fresnel[2],
        );
        let value = R::select(self.glossy, f * self.g1_i * g1_o * d, self.peak * cos_o);
        let rejects = normal_threshold & (!bright | below | !facing | value.le(threshold));
        self.always | around | !finite | !rejects
    }
}

/// Below this δ ξ l² (2⁻¹⁰⁰) the test keeps every VPL: products near the subnormal range
/// round by more than their relative slack.
const TINY_THRESHOLD: f32 = 7.888_609e-31;

/// |v| as the larger of v and −v.
#[inline(always)]
fn abs<R: Real>(v: R) -> R {
    max(v, -v)
}

/// The cone of directions from the origin to the ball around the box `[lo, hi]`: axis, cos
/// and sin of its half-angle (sin grown by [`CONE_SLACK`]), and where it is bounded (the ball
/// does not reach the origin).
struct Cone<R: Real> {
    axis: [R; 3],
    cos_b: R,
    sin_b: R,
    bounded: R::Mask,
}

impl<R: Real> Cone<R> {
    #[inline(always)]
    fn around(lo: [R; 3], hi: [R; 3]) -> Self {
        let half = R::splat(0.5);
        let center = [
            half * (lo[0] + hi[0]),
            half * (lo[1] + hi[1]),
            half * (lo[2] + hi[2]),
        ];
        let size = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let radius = half * dot(size, size).sqrt();
        let distance = dot(center, center).sqrt();
        let sin_b = radius / distance + R::splat(CONE_SLACK as f32);
        Self {
            axis: [
                center[0] / distance,
                center[1] / distance,
                center[2] / distance,
            ],
            cos_b: (R::splat(1.0) - sin_b * sin_b).sqrt(),
            sin_b,
            bounded: R::splat(1.0).gt(sin_b),
        }
    }

    /// The cosine (clamped to [−1, 1]) and sine of the angle between the unit vector `u` and
    /// the axis, the sine as |u × a| (see the module docs).
    #[inline(always)]
    fn angle_to(&self, u: [R; 3]) -> (R, R) {
        let sin = cross(u, self.axis);
        (clamp_cos(dot(u, self.axis)), dot(sin, sin).sqrt())
    }

    /// The largest cosine between the unit vector `u` and a direction of the cone,
    /// cos(max(0, ∠(u, a) − β)), plus [`COS_SLACK`] (at most 1).
    #[inline(always)]
    fn max_cos(&self, u: [R; 3]) -> R {
        let one = R::splat(1.0);
        let (cos_g, sin_g) = self.angle_to(u);
        let v = min(
            cos_g * self.cos_b + sin_g * self.sin_b + R::splat(COS_SLACK),
            one,
        );
        R::select(self.bounded & self.cos_b.gt(cos_g), v, one)
    }

    /// The smallest cosine between `u` and a direction of the cone, cos(min(π, ∠(u, a) + β)),
    /// minus [`COS_SLACK`] (at least −1).
    #[inline(always)]
    fn min_cos(&self, u: [R; 3]) -> R {
        let one = R::splat(1.0);
        let (cos_g, sin_g) = self.angle_to(u);
        let v = max(
            cos_g * self.cos_b - sin_g * self.sin_b - R::splat(COS_SLACK),
            -one,
        );
        R::select(self.bounded & cos_g.gt(-self.cos_b), v, -one)
    }
}

/// `c` clamped to [−1, 1].
#[inline(always)]
fn clamp_cos<R: Real>(c: R) -> R {
    let one = R::splat(1.0);
    max(min(c, one), -one)
}

#[cfg(test)]
mod tests;
