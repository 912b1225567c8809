//! [`BoxBound::glossy`] of eight lobes at once: the lobes' checks (`GlossyLobe::new`) and
//! their f32 values (the renormalised n and ωi, ωi·n, |n × ωi|, cos θh_max, G1(ωi)/(ωi·n) and
//! the mirror direction ω_u) in lanes, the same IEEE operations as the lobe forms them one at
//! a time, so the bounds are the same bit for bit; then each lane's f64 normalisations and
//! largest intensity as [`BoxBound::glossy`] forms them. A culler that forms every VPL's
//! bound each frame (a million at RSM 1024) otherwise waits on each lobe's chain of square
//! roots and divisions, and on building and checking the lobe itself.
use super::{BoxBound, GlossyParts};
use crate::check::UNIT_TOLERANCE;
use crate::fresnel::cos_theta_h_max_lanes;
use crate::ggx::g1_over_cos_lanes;
use crate::lanes::{
    all3, cross, dot, max, normalize, store_all, within, within1, Lanes8, Real, F8,
};
use crate::{Fresnel, StochasticParams};
use glam::Vec3;

/// Eight glossy lobes as [`crate::GlossyLobe::new`] takes them (before its checks; the position
/// aside), lane k one lobe: each isotropic, on a shading normal equal to its geometric one, with
/// Schlick's Fresnel factor of `f0`.
#[derive(Clone, Copy, Debug)]
pub struct SchlickLobes<L> {
    pub normal: [L; 3],
    pub omega_i: [L; 3],
    pub alpha: L,
    pub flux: [L; 3],
    pub f0: [L; 3],
}

impl<L: Lanes8> SchlickLobes<L> {
    /// [`BoxBound::glossy`] of lane k's lobe for the roulette `params[k]`, handed to
    /// `each(k, bound)` for every lane k in `wanted` (bit k) below `params.len()` that
    /// `GlossyLobe::new` accepts: the same bound bit for bit. Returns the lanes handed on; a
    /// lane it leaves is one the lobe's checks refuse (or not wanted), which the caller's
    /// `GlossyLobe::new` names.
    #[inline(always)]
    pub fn box_bounds(
        &self,
        wanted: u8,
        params: &[StochasticParams],
        mut each: impl FnMut(usize, BoxBound),
    ) -> u8 {
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let (n, unit_n) = unit(self.normal);
        let (wi, unit_wi) = unit(self.omega_i);
        let accepted = unit_n
            & unit_wi
            & self.alpha.gt(zero)
            & self.alpha.le(one)
            & all3(within(self.flux, zero, L::splat(f32::MAX)))
            & all3(within(self.f0, zero, one));
        let lanes = wanted & L::bits(accepted) & (((1u16 << params.len().min(8)) - 1) as u8);
        if lanes == 0 {
            return 0;
        }
        // GlossyLobe::cos_i, sin_i and reflection, cos_theta_h_max and g1_over_cos (which takes
        // |ωi·n|: a zero of either sign gives the same quotient).
        let cos_i = dot(n, wi);
        let sin_i = {
            let c = cross(n, wi);
            dot(c, c).sqrt()
        };
        let cos_h_max = cos_theta_h_max_lanes(cos_i, sin_i);
        let g1_over_cos = g1_over_cos_lanes(self.alpha * self.alpha, max(cos_i, -cos_i));
        let two_cos = L::splat(2.0) * cos_i;
        let mirror = [
            two_cos * n[0] - wi[0],
            two_cos * n[1] - wi[1],
            two_cos * n[2] - wi[2],
        ];
        let reflection = normalize(mirror);
        let stored = Stored {
            normal: store_all(&n),
            omega_i: store_all(&wi),
            reflection: store_all(&reflection),
            alpha: self.alpha.store(),
            flux: store_all(&self.flux),
            f0: store_all(&self.f0),
            g1_over_cos: g1_over_cos.store(),
            cos_h_max: cos_h_max.store(),
        };
        let mut left = lanes;
        while left != 0 {
            let k = left.trailing_zeros() as usize;
            left &= left - 1;
            each(k, BoxBound::glossy_of(&stored.parts(k), &params[k]));
        }
        lanes
    }
}

/// The lanes' values, read one lobe at a time.
struct Stored {
    normal: [F8; 3],
    omega_i: [F8; 3],
    reflection: [F8; 3],
    alpha: F8,
    flux: [F8; 3],
    f0: [F8; 3],
    g1_over_cos: F8,
    cos_h_max: F8,
}

impl Stored {
    /// Lane k as [`BoxBound::glossy`] takes a lobe: not tilted and isotropic, so G1(ωo) is
    /// bounded with the lobe's α and the bound factor is 1 (the flux times 1.0 is the flux).
    #[inline(always)]
    fn parts(&self, k: usize) -> GlossyParts {
        let alpha = self.alpha.0[k];
        GlossyParts {
            normal: lane3(&self.normal, k),
            omega_i: lane3(&self.omega_i, k),
            reflection: lane3(&self.reflection, k),
            alpha,
            g1_o_alpha: Some(alpha),
            flux: lane3(&self.flux, k),
            fresnel: Fresnel::Schlick(lane3(&self.f0, k)),
            g1_over_cos: self.g1_over_cos.0[k],
            cos_h_max: self.cos_h_max.0[k],
        }
    }
}

/// Lane `k` of three lanes as a vector (a function, not a closure: this runs in the AVX2
/// kernel, where a closure could be compiled without AVX2).
#[inline(always)]
fn lane3(v: &[F8; 3], k: usize) -> Vec3 {
    Vec3::new(v[0].0[k], v[1].0[k], v[2].0[k])
}

/// `check::unit` in lanes: `v / |v|`, and where `v` is finite with |v| within
/// [`UNIT_TOLERANCE`] of 1 (|d| <= t as −t <= d <= t, both false for NaN).
#[inline(always)]
fn unit<L: Real>(v: [L; 3]) -> ([L; 3], L::Mask) {
    let len = dot(v, v).sqrt();
    let tolerance = L::splat(UNIT_TOLERANCE);
    let ok = all3(within(v, L::splat(-f32::MAX), L::splat(f32::MAX)))
        & within1(len - L::splat(1.0), -tolerance, tolerance);
    ([v[0] / len, v[1] / len, v[2] / len], ok)
}

#[cfg(test)]
mod tests;
