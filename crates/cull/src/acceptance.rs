//! The roulette of eq. (2)-(3) evaluated in lanes: whether p(ωo, l) = min(I(ωo)/(δ l²), 1)
//! exceeds the VPL's ξ, with I(ωo) = Φ f(ωi, ωo) max(ωo·n, 0) of eq. (4), f the VPL's lobe
//! (kd/π, or the GGX microfacet BRDF of eq. 6-8). Each lane performs the IEEE operations of
//! the shader (`vpl_contribution` → `Vpl::intensity` → `Brdf::specular` →
//! `StochasticParams::probability`) in the same order, so for diffuse VPLs and glossy ones
//! with Schlick's Fresnel it decides exactly as the shader does. Where the shader forms
//! things differently the test errs on the side of passing:
//! - a glossy VPL whose half vector the shader forms in f64 (ωi and ωo nearly opposite with a
//!   tiny α, `s² α² <= 1e-6` in `slc_bounds::brdf::microfacet`) always passes;
//! - a dielectric Fresnel factor is replaced by 1, its upper bound (`fresnel::dielectric` is
//!   at most 1 in f32 too: each ratio it squares has a numerator no larger than its
//!   denominator). Its largest value over the reachable half vectors (supplemental eq. 6)
//!   would be tighter, but the f32 cosine the shader evaluates it at can fall a few ulps
//!   below that range's end, where for η < 1 near total internal reflection the factor's
//!   slope is unbounded;
//! - a VPL on a tilted shading normal (`Vpl::is_tilted`: the adjoint cosine of
//!   `slc_bounds::shading_normal` replaces ωo·n) or with an anisotropic lobe
//!   (`slc_bounds::anisotropy`) always passes where ωo·n > 0; its own bound (`reach`) still
//!   applies where the shading formed it (`VplReach::without_bounds` leaves it out).
use crate::ggx_lanes::{g1_over_cos, HalfVector};
use core::f32::consts::FRAC_1_PI;
use slc_bounds::lanes::{
    dot, gather, gather3, gather_flags, load_all, max, splat_all, Lanes8, Real, F8,
};
use slc_bounds::{ggx, Fresnel, StochasticParams};
use slc_core::{Vpl, VplLobe};

/// One VPL's constants of the roulette test, in lanes of `R`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Acceptance<R: Real> {
    /// ωi (unit, towards where the photon came from).
    omega_i: [R; 3],
    alpha: R,
    /// α² as `ggx` forms it.
    alpha_sq: R,
    /// G1(ωi)/cos θi of eq. (8), constant per VPL.
    g1_over_cos_i: R,
    /// Per channel, F(c) = a + b (1 − c)⁵ (Schlick: a = F0, b = 1 − F0; dielectric: its
    /// bound 1 and 0; diffuse: 1 and 0).
    fresnel_a: [R; 3],
    fresnel_b: [R; 3],
    /// What multiplies f cos θo: the flux Φ of a glossy VPL, Φ (kd/π) of a diffuse one (the
    /// shader's `flux * (kd * FRAC_1_PI)`), 0 for a VPL that reflects nothing.
    emitted: [R; 3],
    /// Set for a glossy VPL (the microfacet lobe), clear for a diffuse one.
    glossy: R::Mask,
    /// Set for a VPL whose intensity the lanes do not form (a tilted shading normal, an
    /// anisotropic lobe): it passes wherever ωo·n > 0.
    unmodelled: R::Mask,
    /// Set where the lanes form the shader's own intensity (not unmodelled, and diffuse or
    /// with Schlick's Fresnel): then, with a well-conditioned half vector, bit for bit.
    exact: R::Mask,
    xi: R,
    delta: R,
}

impl Acceptance<f32> {
    /// The roulette test of `vpl` under `params` (its δ and ξ). `dark` marks a VPL the shader
    /// gives 0 at every pair (see `reach`): its intensity is 0, so it passes only where a
    /// glossy half vector is formed in f64 or the VPL is unmodelled (and there the bound test of
    /// `reach`, whose limit is −1 for such a VPL, rejects it first).
    pub(crate) fn new(vpl: &Vpl, params: &StochasticParams, dark: bool) -> Self {
        let brdf = &vpl.brdf;
        let glossy = vpl.lobe == VplLobe::Glossy;
        let (fresnel_a, fresnel_b, emitted) = if glossy {
            let (a, b) = match brdf.fresnel {
                Fresnel::Schlick(f0) => (f0, glam::Vec3::ONE - f0),
                Fresnel::Dielectric(_) => (glam::Vec3::ONE, glam::Vec3::ZERO),
            };
            (a, b, vpl.flux)
        } else {
            (
                glam::Vec3::ONE,
                glam::Vec3::ZERO,
                vpl.flux * (brdf.kd * FRAC_1_PI),
            )
        };
        let emitted = if dark { glam::Vec3::ZERO } else { emitted };
        let unmodelled = vpl.is_tilted() || brdf.anisotropy.is_some();
        let dielectric = glossy && matches!(brdf.fresnel, Fresnel::Dielectric(_));
        Self {
            omega_i: vpl.omega_i.to_array(),
            alpha: brdf.alpha,
            alpha_sq: brdf.alpha * brdf.alpha,
            g1_over_cos_i: ggx::g1_over_cos(brdf.alpha, vpl.normal.dot(vpl.omega_i)),
            fresnel_a: fresnel_a.to_array(),
            fresnel_b: fresnel_b.to_array(),
            emitted: emitted.to_array(),
            glossy,
            unmodelled,
            exact: !(unmodelled || dielectric),
            xi: params.xi(),
            delta: params.delta(),
        }
    }

    /// A lane that never passes (past the end of a chunk).
    pub(crate) const NEVER: Self = Self {
        omega_i: [0.0; 3],
        alpha: 1.0,
        alpha_sq: 1.0,
        g1_over_cos_i: 1.0,
        fresnel_a: [1.0; 3],
        fresnel_b: [0.0; 3],
        emitted: [0.0; 3],
        glossy: false,
        unmodelled: false,
        exact: false,
        xi: 0.5,
        delta: 1.0,
    };
}

impl Acceptance<F8> {
    /// The eight lanes as `L` ([`Lanes8::load`]).
    #[inline(always)]
    pub(crate) fn load<L: Lanes8>(&self) -> Acceptance<L> {
        Acceptance {
            omega_i: load_all(&self.omega_i),
            alpha: L::load(&self.alpha),
            alpha_sq: L::load(&self.alpha_sq),
            g1_over_cos_i: L::load(&self.g1_over_cos_i),
            fresnel_a: load_all(&self.fresnel_a),
            fresnel_b: load_all(&self.fresnel_b),
            emitted: load_all(&self.emitted),
            glossy: L::load_mask(&self.glossy),
            unmodelled: L::load_mask(&self.unmodelled),
            exact: L::load_mask(&self.exact),
            xi: L::load(&self.xi),
            delta: L::load(&self.delta),
        }
    }

    /// The tests of eight VPLs, one per lane.
    pub(crate) fn lanes(of: [&Acceptance<f32>; 8]) -> Self {
        let of = &of;
        Self {
            omega_i: gather3(of, |a| a.omega_i),
            alpha: gather(of, |a| a.alpha),
            alpha_sq: gather(of, |a| a.alpha_sq),
            g1_over_cos_i: gather(of, |a| a.g1_over_cos_i),
            fresnel_a: gather3(of, |a| a.fresnel_a),
            fresnel_b: gather3(of, |a| a.fresnel_b),
            emitted: gather3(of, |a| a.emitted),
            glossy: gather_flags(of, |a| a.glossy),
            unmodelled: gather_flags(of, |a| a.unmodelled),
            exact: gather_flags(of, |a| a.exact),
            xi: gather(of, |a| a.xi),
            delta: gather(of, |a| a.delta),
        }
    }
}

impl<R: Real> Acceptance<R> {
    /// One VPL's test in every lane (the lanes are then receivers).
    #[inline(always)]
    pub(crate) fn splat(of: &Acceptance<f32>) -> Self {
        Self {
            omega_i: splat_all(&of.omega_i),
            alpha: R::splat(of.alpha),
            alpha_sq: R::splat(of.alpha_sq),
            g1_over_cos_i: R::splat(of.g1_over_cos_i),
            fresnel_a: splat_all(&of.fresnel_a),
            fresnel_b: splat_all(&of.fresnel_b),
            emitted: splat_all(&of.emitted),
            glossy: R::flag(of.glossy),
            unmodelled: R::flag(of.unmodelled),
            exact: R::flag(of.exact),
            xi: R::splat(of.xi),
            delta: R::splat(of.delta),
        }
    }

    /// Whether the roulette of eq. (3) may accept the VPL with unit normal `normal` at the
    /// offset `d = x − q` (formed as the shader forms it): false only where the shader finds
    /// p(ωo, l) <= ξ, or I(ωo) = 0.
    #[inline(always)]
    pub(crate) fn may_accept(&self, normal: [R; 3], d: [R; 3]) -> R::Mask {
        self.evaluate(normal, d).may_accept
    }

    /// [`Self::may_accept`], with the values it was decided on.
    #[inline(always)]
    pub(crate) fn evaluate(&self, normal: [R; 3], d: [R; 3]) -> Roulette<R> {
        let zero = R::splat(0.0);
        // vpl_contribution: ωo = d / |d|.
        let l2 = dot(d, d);
        let len = l2.sqrt();
        let omega = [d[0] / len, d[1] / len, d[2] / len];
        // Vpl::intensity: cos θo, then the lobe.
        let cos_o = dot(normal, omega);
        // microfacet (eq. 6-8), f32 half vector.
        let g = self.g1_over_cos_i * g1_over_cos(self.alpha_sq, cos_o);
        let half = HalfVector::new(normal, self.omega_i, omega, self.alpha, self.alpha_sq);
        let k = R::select(self.glossy, R::splat(0.25) * half.d * g, R::splat(1.0));
        let channel = |c: usize| {
            let f = (self.fresnel_a[c] + self.fresnel_b[c] * half.schlick) * k;
            self.emitted[c] * f * cos_o
        };
        let channels = [channel(0), channel(1), channel(2)];
        // scalar_intensity (the largest channel), then eq. (2)-(3).
        let intensity = max(channels[0], max(channels[1], channels[2]));
        let p = intensity / (self.delta * l2);
        let accepted = cos_o.gt(zero) & intensity.gt(zero) & !p.le(self.xi);
        let ill_conditioned = self.glossy & !half.well_conditioned;
        Roulette {
            may_accept: accepted | ((self.unmodelled | ill_conditioned) & cos_o.gt(zero)),
            exact: accepted & self.exact & !ill_conditioned,
            l2,
            omega,
            intensity: channels,
        }
    }
}

/// The roulette of one pair (or eight) and what it was decided on: l² = |d|², ωo = d/|d| and
/// the VPL's intensity I(ωo) per channel (eq. 4), each formed with the shader's operations
/// (`vpl_contribution`, `Vpl::intensity`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Roulette<R: Real> {
    /// [`Acceptance::may_accept`].
    pub may_accept: R::Mask,
    /// Where the shader accepts the pair and `l2`, `omega` and `intensity` are the shader's
    /// own values bit for bit: a diffuse VPL, or a glossy one with Schlick's Fresnel and a
    /// half vector the shader forms in f32, neither tilted nor anisotropic.
    pub exact: R::Mask,
    pub l2: R,
    pub omega: [R; 3],
    pub intensity: [R; 3],
}
