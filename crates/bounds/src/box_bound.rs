//! A bound of a VPL's roulette probability p(ωo, l) of eq. (2) over a box of receivers:
//! the refinement behind the `tight` culling strategies (docs/tight-bounds.md), and in f32
//! ([`lanes`]) the first test of every VPL against a window's receivers in the CPU shading.
//!
//! The spheroid of eq. (12)-(15) drops three factors of the glossy intensity
//! `I(ωo) = Φ F(ωi·ωh) G1(ωi) G1(ωo) D(ωh·n) / (4 ωi·n)` (eq. 4, 6, 8; the cosine ωo·n of eq. 4
//! cancels the BRDF's): it bounds F by its largest value over every half vector (supplemental
//! eq. 2, 6), G1(ωo) by 1, and only then couples D with the distance. Over a box of receivers
//! seen from the VPL inside a cone of directions (axis a, half-angle β) every factor is
//! bounded at once, each by its largest value over the cone:
//!
//! - D(ωh·n) <= D(cos(θ_min/2)) with θ the angle between ωo and the mirror direction ω_u
//!   (eq. 10-11), θ_min = max(0, ∠(a, ω_u) − β);
//! - F(ωi·ωh): the half vector makes half the angle φ between ωi and ωo with ωi, and
//!   φ <= min(∠(a, ωi) + β, π); Schlick's F grows with that angle, a dielectric's is
//!   quasiconvex in it (supplemental eq. 6), so its largest value is at an end of the range;
//!   and the angle never exceeds θh_max(ωi) of supplemental eq. (2);
//! - G1(ωo) grows with ωo·n (eq. 8), so it is at most G1 of the largest ωo·n over the box:
//!   the cone's largest cosine to n, or h/l_min with h the largest n·(x − q) at a corner
//!   (the VPL's tangent plane), whichever is smaller; 0 when the box lies below that plane
//!   (I = 0 there, eq. 4);
//! - l² >= the squared distance from q to the box.
//!
//! A diffuse VPL (eq. 4 with f = kd/π) has I(ωo) = Φk/π ωo·n, bounded by the cone's largest
//! cosine to n. The box is tested only where p could exceed ξ: where the bound is at most ξ
//! every point of the box has p <= ξ and eq. (3) weights the pair 0.
use crate::fresnel::{cos_theta_h_max, Fresnel};
use crate::ggx;
use crate::stochastic::{scalar_intensity, StochasticParams};
use crate::{DiffuseLobe, GlossyLobe};
use core::f64::consts::FRAC_1_PI;
use glam::{DMat3, DVec3, Vec3};

mod eight;
pub mod lanes;

pub use eight::SchlickLobes;

/// Added to sin β of the cone of directions: covers the f32 rounding of the shader's unit
/// direction ωo (about 1e-7 rad) and half vector (at most about 1e-4 α rad where the shader
/// forms it in f32, see `brdf::microfacet`), with a margin of 10 for α >= 0.01.
pub const CONE_SLACK: f64 = 1e-5;

/// Relative growth of the bound of p: covers the f32 rounding of the shader's I/(δ l²)
/// (about 20 roundings of 6e-8) and of the f32 Fresnel factors, a hundredfold.
pub const PROBABILITY_SLACK: f64 = 1e-3;

/// Which lobe, with what its intensity bound needs beyond the normal.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Lobe {
    /// Φk/π of eq. (4) with f = kd/π.
    Diffuse { peak: f64 },
    /// The glossy lobe of eq. (6): flux (times `GlossyLobe::bound_factor` of a tilted or
    /// anisotropic lobe), Fresnel, α (`GlossyLobe::alpha`), ωi, ω_u, θh_max(ωi) as a cosine,
    /// G1(ωi)/(4 ωi·n), and the α whose G1 bounds G1(ωo) over the cone (the lobe's smallest;
    /// none for a tilted shading normal: the factor covers it).
    Glossy {
        flux: Vec3,
        fresnel: Fresnel,
        alpha: f64,
        omega_i: DVec3,
        omega_u: DVec3,
        cos_h_max: f64,
        g1_i: f64,
        g1_o_alpha: Option<f32>,
    },
}

/// What [`BoxBound::glossy`] takes from a glossy lobe, in f32 as the lobe forms it: its unit
/// normal n, ωi and mirror direction ω_u, α (`GlossyLobe::alpha`) and the α whose G1 bounds
/// G1(ωo) (none on a tilted shading normal), the flux times `GlossyLobe::bound_factor`, the
/// Fresnel model, G1(ωi)/(ωi·n) and cos θh_max(ωi).
struct GlossyParts {
    normal: Vec3,
    omega_i: Vec3,
    reflection: Vec3,
    alpha: f32,
    g1_o_alpha: Option<f32>,
    flux: Vec3,
    fresnel: Fresnel,
    g1_over_cos: f32,
    cos_h_max: f32,
}

/// One VPL's bound of p over boxes of receivers, in the frame its vectors were given in
/// ([`Self::rotated`] moves it to another, e.g. a culling view). Its directions are
/// normalised in f64: a cosine near 1 must resolve 1 − cos of order α², far below the f32
/// rounding of a unit vector's length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxBound {
    lobe: Lobe,
    normal: DVec3,
    /// The largest intensity in any direction: Φk/π, or for a glossy VPL
    /// scalar(Φ F_max(ωi)) G1(ωi)/(4 ωi·n) D(1) (eq. 9 at its peak, the r/α sphere), Φ times
    /// `GlossyLobe::bound_factor` on a tilted shading normal or an anisotropic lobe.
    peak: f64,
    /// δ ξ of eq. (2)-(3) (p > ξ needs I > δ ξ l²), divided by 1 + [`PROBABILITY_SLACK`].
    delta_xi_shrunk: f64,
}

impl BoxBound {
    /// The bound of a glossy VPL for the roulette `params`.
    pub fn glossy(lobe: &GlossyLobe, params: &StochasticParams) -> Self {
        let cos_i = lobe.cos_i();
        // A tilted shading normal: the flux times `bound_factor`, and G1(ωo) bounded by 1
        // below (`g1_tilt_max` covers G1(ωo)(ωo·n_g)/(ωo·n) in the factor). An anisotropic
        // lobe: the isotropic one of its largest α with the flux times `bound_factor`, and
        // G1(ωo) bounded by the isotropic G1 of its smallest α (`crate::anisotropy`).
        Self::glossy_of(
            &GlossyParts {
                normal: lobe.normal(),
                omega_i: lobe.omega_i(),
                reflection: lobe.reflection(),
                alpha: lobe.alpha(),
                g1_o_alpha: (!lobe.is_tilted()).then(|| lobe.alpha_min()),
                flux: lobe.flux() * lobe.bound_factor(),
                fresnel: lobe.fresnel(),
                g1_over_cos: ggx::g1_over_cos(lobe.alpha(), cos_i),
                cos_h_max: cos_theta_h_max(cos_i, lobe.sin_i()),
            },
            params,
        )
    }

    /// The glossy bound of `parts` (a lobe's f32 values, from [`Self::glossy`] or from
    /// [`SchlickLobes::box_bounds`]): the directions normalised again in f64, and the largest
    /// intensity scalar(Φ F_max(ωi)) G1(ωi)/(4 ωi·n) D(1) with F_max at θh_max
    /// (supplemental eq. 2).
    fn glossy_of(parts: &GlossyParts, params: &StochasticParams) -> Self {
        let alpha = f64::from(parts.alpha);
        let g1_i = 0.25 * f64::from(parts.g1_over_cos);
        let f_max = f64::from(scalar_intensity(
            parts.flux * parts.fresnel.max_from(parts.cos_h_max),
        ));
        Self {
            lobe: Lobe::Glossy {
                flux: parts.flux,
                g1_o_alpha: parts.g1_o_alpha,
                fresnel: parts.fresnel,
                alpha,
                omega_i: parts.omega_i.as_dvec3().normalize(),
                omega_u: parts.reflection.as_dvec3().normalize(),
                cos_h_max: f64::from(parts.cos_h_max),
                g1_i,
            },
            normal: parts.normal.as_dvec3().normalize(),
            peak: f_max * g1_i / (core::f64::consts::PI * alpha * alpha),
            delta_xi_shrunk: delta_xi_shrunk(params),
        }
    }

    /// The bound of a diffuse VPL for the roulette `params`.
    pub fn diffuse(lobe: &DiffuseLobe, params: &StochasticParams) -> Self {
        let peak = f64::from(lobe.reflected_flux()) * FRAC_1_PI;
        Self {
            lobe: Lobe::Diffuse { peak },
            normal: lobe.normal().as_dvec3().normalize(),
            peak,
            delta_xi_shrunk: delta_xi_shrunk(params),
        }
    }

    /// The same bound with its directions rotated by `rotation` (a rotation matrix, up to
    /// rounding: the rotated directions are normalised again), for boxes given in the rotated
    /// frame.
    pub fn rotated(&self, rotation: DMat3) -> Self {
        let mut out = *self;
        out.normal = (rotation * self.normal).normalize();
        if let Lobe::Glossy {
            omega_i, omega_u, ..
        } = &mut out.lobe
        {
            *omega_i = (rotation * *omega_i).normalize();
            *omega_u = (rotation * *omega_u).normalize();
        }
        out
    }

    /// Whether p(ωo, l) > ξ may hold at some receiver of `receivers` for this VPL at `q`
    /// (in the box's frame). False only where the bound of the module docs, grown by
    /// [`CONE_SLACK`] and [`PROBABILITY_SLACK`], is at most ξ over the whole box. The box
    /// must contain the points the shader forms offsets from, its rounding included. The
    /// cheap tests come first: the distance against the largest intensity in any direction
    /// (the r/α sphere of section 7), then the tangent plane; the factors over the cone are
    /// formed without further branches (measured faster: those branches mispredict).
    pub fn may_exceed_xi(&self, receivers: &ReceiverBox, q: DVec3) -> bool {
        let (lo, hi) = (receivers.lo - q, receivers.hi - q);
        let l2_min = lo.max(-hi).max(DVec3::ZERO).length_squared();
        if l2_min <= 0.0 {
            return true;
        }
        let threshold = self.delta_xi_shrunk * l2_min;
        if self.peak <= threshold {
            return false;
        }
        // h = the largest n·d over the box (at a corner): ωo·n <= h/|d|.
        let h = (self.normal * lo).max(self.normal * hi).element_sum();
        if h < 0.0 && h * h >= CONE_SLACK * CONE_SLACK * lo.abs().max(hi.abs()).length_squared() {
            return false;
        }
        let cone = Cone::around(receivers.center - q, receivers.radius);
        // ωo·n <= h/l_min for h >= 0 (h/l_max <= 0 otherwise), plus the f32 slack.
        let plane_cos = h.max(0.0) / l2_min.sqrt() + CONE_SLACK;
        let cos_o = cone.max_cos(self.normal).min(plane_cos);
        if cos_o <= 0.0 {
            return false;
        }
        match self.lobe {
            Lobe::Diffuse { peak } => peak * cos_o > threshold,
            Lobe::Glossy {
                flux,
                fresnel,
                alpha,
                omega_i,
                omega_u,
                cos_h_max,
                g1_i,
                g1_o_alpha,
            } => {
                // D(cos(θ_min/2)) of eq. (7) with sin²(θ/2) = (1 − cos θ)/2.
                let sin2 = 0.5 * (1.0 - cone.max_cos(omega_u));
                let a2 = alpha * alpha;
                let denom = a2 + (1.0 - a2) * sin2;
                let d = a2 / (core::f64::consts::PI * denom * denom);
                let g1_o = g1_o_alpha.map_or(1.0, |a| f64::from(ggx::g1(a, cos_o as f32)));
                // The smallest cos(φ/2) = ωi·ωh over the cone, no smaller than cos θh_max.
                let cos_h = (0.5 * (1.0 + cone.min_cos(omega_i))).sqrt().max(cos_h_max);
                let f = f64::from(scalar_intensity(flux * fresnel.max_from(cos_h as f32)));
                f * g1_i * g1_o * d > threshold
            }
        }
    }
}

/// A box of receivers `[lo, hi]` (closed) with its bounding sphere, formed once per box and
/// tested against many VPLs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReceiverBox {
    lo: DVec3,
    hi: DVec3,
    center: DVec3,
    radius: f64,
}

impl ReceiverBox {
    /// The box `[lo, hi]` (lo <= hi per axis).
    pub fn new(lo: DVec3, hi: DVec3) -> Self {
        Self {
            lo,
            hi,
            center: 0.5 * (lo + hi),
            radius: 0.5 * (hi - lo).length(),
        }
    }
}

/// δ ξ / (1 + [`PROBABILITY_SLACK`]), in f64.
fn delta_xi_shrunk(params: &StochasticParams) -> f64 {
    f64::from(params.delta()) * f64::from(params.xi()) / (1.0 + PROBABILITY_SLACK)
}

/// The cone of directions from the origin to a box: axis a, and cos β, sin β of its
/// half-angle (grown by [`CONE_SLACK`]); `None` when the box's bounding sphere reaches the
/// origin, where the directions are not bounded.
struct Cone(Option<(DVec3, f64, f64)>);

impl Cone {
    /// The cone of the ball of `radius` around `center` (relative to the apex).
    fn around(center: DVec3, radius: f64) -> Self {
        let distance = center.length();
        let sin = radius / distance + CONE_SLACK;
        Self((sin < 1.0).then(|| (center / distance, (1.0 - sin * sin).sqrt(), sin)))
    }

    /// The largest cosine between the unit vector `u` and a direction of the cone:
    /// cos(max(0, ∠(u, a) − β)).
    fn max_cos(&self, u: DVec3) -> f64 {
        let Some((axis, cos_b, sin_b)) = self.0 else {
            return 1.0;
        };
        let cos_g = u.dot(axis).clamp(-1.0, 1.0);
        if cos_g >= cos_b {
            return 1.0;
        }
        cos_g * cos_b + (1.0 - cos_g * cos_g).sqrt() * sin_b
    }

    /// The smallest cosine between `u` and a direction of the cone: cos(min(π, ∠(u, a) + β)).
    fn min_cos(&self, u: DVec3) -> f64 {
        let Some((axis, cos_b, sin_b)) = self.0 else {
            return -1.0;
        };
        let cos_g = u.dot(axis).clamp(-1.0, 1.0);
        if cos_g <= -cos_b {
            return -1.0;
        }
        cos_g * cos_b - (1.0 - cos_g * cos_g).sqrt() * sin_b
    }
}

#[cfg(test)]
mod tests;
