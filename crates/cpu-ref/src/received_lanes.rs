//! The receivers' side of the shading in lanes: for one VPL and the eight receivers of a chunk
//! where the roulette accepted it ([`Passing`]), the weighted contribution
//! f(x; ωl, ωo) I(ω) cos θx / (l² p) of eq. (1) and (3) with the receiver's BRDF (eq. 6-8),
//! as [`crate::vpl_shading::received`] forms it. Each lane performs the shader's IEEE
//! operations in the same order ([`slc_bounds::lanes`]), so the two agree bit for bit. Lanes
//! this does not model (an anisotropic receiver, a dielectric one, or a half vector the shader
//! forms in f64) are left to the scalar shader.
use core::f32::consts::FRAC_1_PI;
use slc_bounds::lanes::{dot, load_all, max, store_all, Lanes8, F8};
use slc_bounds::{Fresnel, StochasticParams};
use slc_core::GSample;
use slc_cull::ggx_lanes::{g1_over_cos, HalfVector};
use slc_cull::receiver_chunks::Passing;

/// The BRDF inputs of eight receivers (lane k: receiver k of a chunk of
/// `slc_cull::ReceiverChunks`); what the shader derives from them per pair (kd/π, 1 − F0,
/// α², n·ωo, G1(ωo)) the lanes derive with the same operations.
#[derive(Clone, Copy, Debug)]
pub struct ReceiverBrdfs {
    normal: [F8; 3],
    omega_o: [F8; 3],
    kd: [F8; 3],
    /// Schlick's F0.
    f0: [F8; 3],
    alpha: F8,
    /// Bit k set where receiver k is modelled here: an isotropic lobe with Schlick's Fresnel.
    modelled: u8,
}

impl ReceiverBrdfs {
    /// The BRDF inputs of `receivers` (at most eight: lane k is receiver k; the others
    /// model nothing).
    pub fn of_chunk<'g>(receivers: impl IntoIterator<Item = &'g GSample>) -> Self {
        let mut c = Self::EMPTY;
        for (lane, g) in receivers.into_iter().take(8).enumerate() {
            let brdf = &g.brdf;
            let (Fresnel::Schlick(f0), None) = (brdf.fresnel, brdf.anisotropy) else {
                continue;
            };
            for axis in 0..3 {
                c.normal[axis].0[lane] = g.normal[axis];
                c.omega_o[axis].0[lane] = g.omega_o[axis];
                c.kd[axis].0[lane] = brdf.kd[axis];
                c.f0[axis].0[lane] = f0[axis];
            }
            c.alpha.0[lane] = brdf.alpha;
            c.modelled |= 1 << lane;
        }
        c
    }

    /// Eight lanes modelling nothing (finite values).
    const EMPTY: Self = Self {
        normal: [F8([0.0; 8]), F8([0.0; 8]), F8([1.0; 8])],
        omega_o: [F8([0.0; 8]), F8([0.0; 8]), F8([1.0; 8])],
        kd: [F8([0.0; 8]); 3],
        f0: [F8([0.0; 8]); 3],
        alpha: F8([1.0; 8]),
        modelled: 0,
    };
}

/// The contributions of `passing`'s VPL (with roulette `params`) at the receivers `brdfs` of
/// its chunk, per channel into `out`; returns the lanes whose value is the shader's
/// `received` bit for bit (0 where it returns 0): those of `passing.bits` with the shader's
/// own ωo, l² and I(ωo) ([`Passing::exact_bits`]) at a modelled receiver. Without AVX2 it
/// models no lane.
pub(crate) fn received_lanes(
    brdfs: &ReceiverBrdfs,
    passing: &Passing,
    params: &StochasticParams,
    out: &mut [F8; 3],
) -> u8 {
    let candidates = passing.bits & passing.exact_bits() & brdfs.modelled;
    if candidates == 0 {
        return 0;
    }
    let (omega, l2, intensity) = passing.lanes();
    candidates & received_pairs(brdfs, omega, l2, intensity, params, out)
}

/// For eight pairs, lane k the receiver k of `brdfs` and a VPL with roulette `params` seen
/// in the unit direction `omega` at squared distance `l2` with intensity `intensity` (per
/// channel), `vpl_shading::received` per channel into `out`; returns the lanes whose value
/// is the shader's bit for bit: every modelled receiver where the shader returns 0 or forms
/// the half vector in f32. Without AVX2 it models no lane.
pub fn received_pairs(
    brdfs: &ReceiverBrdfs,
    omega: &[F8; 3],
    l2: &F8,
    intensity: &[F8; 3],
    params: &StochasticParams,
    out: &mut [F8; 3],
) -> u8 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return brdfs.modelled & unsafe { received_avx2(brdfs, omega, l2, intensity, params, out) };
    }
    0
}

/// [`received`] in AVX registers, into `out`; returns the lanes it formed as the shader does.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn received_avx2(
    brdfs: &ReceiverBrdfs,
    omega: &[F8; 3],
    l2: &F8,
    intensity: &[F8; 3],
    params: &StochasticParams,
    out: &mut [F8; 3],
) -> u8 {
    use slc_bounds::lanes_avx::A8;
    let (c, formed) = received::<A8>(
        brdfs,
        load_all(omega),
        A8::load(l2),
        load_all(intensity),
        params,
    );
    *out = store_all(&c);
    A8::bits(formed)
}

/// `vpl_shading::received(g, ω, l², || I, Some(params))` in each lane of `L`, with the
/// receivers `brdfs` and the unit direction `omega` from the VPL, `l2` and the VPL's
/// intensity per channel: the contribution per channel, and where it is the shader's own
/// (everywhere the shader returns 0 or forms the half vector in f32).
#[inline(always)]
fn received<L: Lanes8>(
    brdfs: &ReceiverBrdfs,
    omega: [L; 3],
    l2: L,
    intensity: [L; 3],
    params: &StochasticParams,
) -> ([L; 3], L::Mask) {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    let normal = load_all(&brdfs.normal);
    // cos θx = −n·ωo.
    let cos_x = -dot(normal, omega);
    // scalar_intensity, then `StochasticParams::probability` (eq. 2) and
    // `estimator_weight` (eq. 3).
    let i_max = max(intensity[0], max(intensity[1], intensity[2]));
    let p = i_max / (L::splat(params.delta()) * l2);
    let p = L::select(zero.le(p) & one.gt(p), p, one);
    let p = L::select(i_max.gt(zero), p, zero);
    let accepted = p.gt(L::splat(params.xi()));
    let weight = one / p;
    // Brdf::eval(n, −ωo, ωo of the receiver): kd/π + microfacet (eq. 6-8).
    let omega_i = [-omega[0], -omega[1], -omega[2]];
    let omega_o = load_all(&brdfs.omega_o);
    let cos_i = dot(normal, omega_i);
    let cos_o = dot(normal, omega_o);
    let live = cos_x.gt(zero) & accepted & cos_i.gt(zero) & cos_o.gt(zero);
    let alpha = L::load(&brdfs.alpha);
    let alpha_sq = alpha * alpha;
    let g = g1_over_cos(alpha_sq, cos_i) * g1_over_cos(alpha_sq, cos_o);
    let half = HalfVector::new(normal, omega_i, omega_o, alpha, alpha_sq);
    let k = L::splat(0.25) * half.d * g;
    let factor = weight * cos_x / l2;
    let mut out = [zero; 3];
    for (c, out) in out.iter_mut().enumerate() {
        // Schlick's F0 + (1 − F0) m (supplemental eq. 1), then kd/π + F D G / 4.
        let f0 = L::load(&brdfs.f0[c]);
        let fresnel = f0 + (one - f0) * half.schlick;
        let f = L::load(&brdfs.kd[c]) * L::splat(FRAC_1_PI) + fresnel * k;
        *out = L::select(live, f * intensity[c] * factor, zero);
    }
    (out, !live | half.well_conditioned)
}
