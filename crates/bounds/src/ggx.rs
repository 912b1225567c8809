//! The GGX (Trowbridge-Reitz) microfacet distribution and its Smith masking function.
use core::f32::consts::PI;

/// GGX normal distribution function, paper eq. (7):
/// `D(cos θm) = α² χ⁺(cos θm) / (π (α² cos² θm + sin² θm)²)`.
#[inline]
pub fn d(alpha: f32, cos_m: f32) -> f32 {
    if cos_m <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let c2 = cos_m * cos_m;
    let s2 = (1.0 - c2).max(0.0);
    let denom = a2 * c2 + s2;
    a2 / (PI * denom * denom)
}

/// `G1_dist(ω) / |ω·n|` of paper eq. (8): `2 / (|cos| + sqrt((1-α²) cos² + α²))`.
/// Finite at grazing incidence (cos -> 0), where G1 itself goes to 0.
#[inline]
pub fn g1_over_cos(alpha: f32, cos_v: f32) -> f32 {
    let c = cos_v.abs();
    let a2 = alpha * alpha;
    2.0 / (c + ((1.0 - a2) * c * c + a2).sqrt())
}

/// Smith masking function for GGX, paper eq. (8):
/// `G1_dist(ω) = 2|ω·n| / (|ω·n| + sqrt((1-α²)(ω·n)² + α²))`.
#[inline]
pub fn g1(alpha: f32, cos_v: f32) -> f32 {
    cos_v.abs() * g1_over_cos(alpha, cos_v)
}

/// The separable Smith masking-shadowing function `G2 = G1(ωi) G1(ωo)` (section 4.1).
#[inline]
pub fn g2_separable(alpha: f32, cos_i: f32, cos_o: f32) -> f32 {
    g1(alpha, cos_i) * g1(alpha, cos_o)
}
