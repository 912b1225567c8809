//! The GGX microfacet terms of paper eq. (6)-(8) in lanes ([`slc_bounds::lanes`]), shared by the
//! roulette (the VPL's lobe, the `acceptance` module) and the shading of the receivers' BRDF:
//! each lane performs the IEEE operations of `slc_bounds::brdf::microfacet` (isotropic, the
//! half vector formed in f32) in the same order, so the two agree bit for bit there.
use core::f32::consts::PI;
use slc_bounds::lanes::{clamp01, cross, dot, max, Real};

/// `ggx::g1_over_cos` of eq. (8), `2 / (c + sqrt((1 − α²) c² + α²))`, for a cosine c > 0
/// (the scalar takes |c|; every caller has already required c > 0 where the value is used).
pub use slc_bounds::ggx::g1_over_cos_lanes as g1_over_cos;

/// What the half vector ωh = (ωi + ωo)/|ωi + ωo| of unit ωi, ωo gives `microfacet`.
#[derive(Clone, Copy, Debug)]
pub struct HalfVector<R: Real> {
    /// D(ωh) of eq. (7) as `ggx::d_with_sin2` forms it from n·ωh and |n × ωh|².
    pub d: R,
    /// Schlick's (1 − clamp(ωi·ωh))⁵ as `powi(5)` forms it, t·(t²·t²).
    pub schlick: R,
    /// Where `microfacet` forms ωh in f32, as here (s² α² > 1e-6 with s = ωi + ωo); elsewhere
    /// it forms ωh in f64 and these values are not its own.
    pub well_conditioned: R::Mask,
}

impl<R: Real> HalfVector<R> {
    /// The half-vector terms of `microfacet(n, ωi, ωo, α, None, ·)`; `alpha_sq` is α·α.
    #[inline(always)]
    pub fn new(normal: [R; 3], omega_i: [R; 3], omega_o: [R; 3], alpha: R, alpha_sq: R) -> Self {
        let zero = R::splat(0.0);
        let s = [
            omega_i[0] + omega_o[0],
            omega_i[1] + omega_o[1],
            omega_i[2] + omega_o[2],
        ];
        let s2 = dot(s, s);
        let well_conditioned = (s2 * alpha * alpha).gt(R::splat(1e-6));
        let s_len = s2.sqrt();
        let h = [s[0] / s_len, s[1] / s_len, s[2] / s_len];
        let cos_m = dot(normal, h);
        let nh = cross(normal, h);
        let sin2_m = dot(nh, nh);
        let denom = alpha_sq * cos_m * cos_m + max(sin2_m, zero);
        let d = R::select(
            !cos_m.le(zero),
            alpha_sq / (R::splat(PI) * denom * denom),
            zero,
        );
        let t = R::splat(1.0) - clamp01(dot(omega_i, h));
        let t2 = t * t;
        Self {
            d,
            schlick: t * (t2 * t2),
            well_conditioned,
        }
    }
}
