//! Early exits for (pixel, VPL) pairs whose contribution is exactly zero, tested before the
//! GGX evaluation of p(ωo, l) (eq. 2) and of the BRDFs: the VPL's own bound (outside it
//! p <= ξ, so eq. (3) weights the pair 0) and the sign of the cosine at either end (eq. 1 and
//! the max(ωo·n, 0) of eq. 4). Each test keeps a margin well above float rounding, so it
//! never rejects a pair that the full evaluation accepts: the estimate stays bit for bit the
//! same, only cheaper.
use crate::vpl_bounds::{GlossyBound, LocalBound};
use glam::{DMat3, DVec3, Vec3};
use slc_bounds::StochasticParams;
use slc_core::{CullError, Vpl, VplLobe};

/// Relative margin of the sign tests: a pair is rejected only when the cosine at one end,
/// formed from the unnormalised offset, is below −1e-5. The shader's cosine of the same
/// direction (normalised first, then dotted) differs from it by a few ulps (about 1e-6 with
/// unit normals), so the sign cannot flip within the margin.
pub const SIGN_MARGIN: f32 = 1e-5;

/// The bound part of [`VplReach`], relative to the VPL's position q.
#[derive(Clone, Copy, Debug, PartialEq)]
enum OwnBound {
    /// The VPL reflects nothing: every pair is zero.
    Never,
    /// No bound (an r = 0 bound of a VPL that the shader does not reject exactly): only the
    /// sign tests apply.
    Unbounded,
    /// The section-6 sphere (centre relative to q, squared radius).
    Sphere { center: DVec3, radius_sq: f64 },
    /// The spheroid of eq. (12)-(15) as its stretch S = diag(1/r) Rᵀ and S·(c − q): the
    /// spheroid is the unit ball of S x − S c.
    Spheroid { stretch: DMat3, center: DVec3 },
}

/// What one VPL needs for the early exits: its own bound (the tightest one: the spheroid for
/// a glossy VPL, whatever the culling strategy, since every strategy's bound contains every
/// pair with p > ξ) and its normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VplReach {
    bound: OwnBound,
    normal: Vec3,
}

impl VplReach {
    /// The early exits of `vpl` under the roulette `params` (its δ and ξ, eq. 2-3). Errors
    /// when the VPL is outside the domain of slc-bounds (see `slc_bounds::BoundsError`).
    pub fn new(vpl: &Vpl, params: &StochasticParams) -> Result<Self, CullError> {
        let bound = if reflects_nothing(vpl) {
            OwnBound::Never
        } else {
            match LocalBound::new(vpl, params, GlossyBound::Ellipsoid)? {
                LocalBound::Empty => OwnBound::Unbounded,
                LocalBound::Sphere { center, radius_sq } => OwnBound::Sphere { center, radius_sq },
                LocalBound::Spheroid {
                    center,
                    rotation,
                    semi_axes,
                } => {
                    let stretch = DMat3::from_diagonal(semi_axes.as_dvec3().recip())
                        * rotation.as_dmat3().transpose();
                    OwnBound::Spheroid {
                        stretch,
                        center: stretch * center,
                    }
                }
            }
        };
        Ok(Self {
            bound,
            normal: vpl.normal,
        })
    }

    /// Whether the roulette of eq. (3) may accept this VPL at the offset `d = x − q` (formed
    /// in f32 as the shader forms it). False only where p(ωo, l) <= ξ for sure: outside the
    /// VPL's own bound, or behind the VPL (ωo·n < 0 beyond the margin: I(ωo) = 0 by eq. 4).
    #[inline]
    pub fn may_accept(&self, d: Vec3) -> bool {
        if behind(-self.normal.dot(d), d) {
            return false;
        }
        let d = d.as_dvec3();
        match self.bound {
            OwnBound::Never => false,
            OwnBound::Unbounded => true,
            OwnBound::Sphere { center, radius_sq } => (d - center).length_squared() <= radius_sq,
            OwnBound::Spheroid { stretch, center } => {
                (stretch * d - center).length_squared() <= 1.0
            }
        }
    }

    /// Whether the pair of this VPL and a receiver with unit normal `receiver_normal` at the
    /// offset `d = x − q` may contribute: [`Self::may_accept`], and the receiver not facing
    /// away (cos θx of eq. 1 not below −[`SIGN_MARGIN`]). False only where the contribution
    /// of eq. (1), weighted by eq. (3), is exactly 0.
    #[inline]
    pub fn may_contribute(&self, d: Vec3, receiver_normal: Vec3) -> bool {
        !behind(receiver_normal.dot(d), d) && self.may_accept(d)
    }
}

/// Whether `t = −n·d` (a cosine times |d|) is below −[`SIGN_MARGIN`] |d|: compared squared,
/// with no square root.
#[inline]
fn behind(t: f32, d: Vec3) -> bool {
    t > 0.0 && t * t > SIGN_MARGIN * SIGN_MARGIN * d.length_squared()
}

/// Whether the shader's own tests give every pair of `vpl` exactly 0: ωi·n <= 0 (the one-sided
/// BRDF of eq. 6 and the diffuse lobe, the same f32 dot product the BRDF forms), no flux, or
/// for a diffuse VPL no channel with both flux and kd.
fn reflects_nothing(vpl: &Vpl) -> bool {
    let dark = match vpl.lobe {
        VplLobe::Diffuse => (vpl.flux.cmpeq(Vec3::ZERO) | vpl.brdf.kd.cmpeq(Vec3::ZERO)).all(),
        VplLobe::Glossy => vpl.flux.cmpeq(Vec3::ZERO).all(),
    };
    dark || vpl.normal.dot(vpl.omega_i) <= 0.0
}
