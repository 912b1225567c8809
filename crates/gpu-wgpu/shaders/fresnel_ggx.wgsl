// GGX and Fresnel functions of crates/bounds (ggx.rs, fresnel.rs) shared by every shader that
// needs them (bounds.wgsl, brdf.wgsl): one definition, prepended by the passes' `concat!`.

const PI: f32 = 3.14159265358979;
const FRESNEL_SCHLICK: u32 = 0u;

// G1(v) / |v.n| of eq. (8): 2 / (|cos| + sqrt((1 - a2) cos^2 + a2)), finite at grazing
// incidence (ggx.rs g1_over_cos).
fn ggx_g1_over_cos(alpha: f32, cos_v: f32) -> f32 {
    let c = abs(cos_v);
    let a2 = alpha * alpha;
    return 2.0 / (c + sqrt((1.0 - a2) * c * c + a2));
}

// Schlick, supplemental eq. (1): F0 + (1 - F0) (1 - cos)^5 (x^5 as powi: (x^2)^2 x).
fn fresnel_schlick(f0: vec3<f32>, cos_h: f32) -> vec3<f32> {
    let x = 1.0 - clamp(cos_h, 0.0, 1.0);
    let x2 = x * x;
    let m = x2 * x2 * x;
    return f0 + (vec3<f32>(1.0) - f0) * m;
}

// The unpolarised dielectric Fresnel factor, supplemental eq. (3)-(5); total internal
// reflection gives 1 (fresnel.rs dielectric).
fn fresnel_dielectric(eta: f32, cos_h: f32) -> f32 {
    let c = clamp(cos_h, 0.0, 1.0);
    let g2 = (eta * eta - 1.0) + c * c;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = sqrt(g2);
    let e2c = eta * eta * c;
    let perp = (c - g) / (c + g);
    let par = (g - e2c) / (g + e2c);
    return 0.5 * (perp * perp + par * par);
}
