// GGX and Fresnel functions of crates/bounds (ggx.rs, fresnel.rs) shared by every shader that
// needs them (bounds.wgsl, brdf.wgsl): one definition, prepended by the passes' `concat!`.

const PI: f32 = 3.14159265358979;
const FRESNEL_SCHLICK: u32 = 0u;

// The largest channel: the scalar intensity convention of crates/bounds (stochastic.rs).
fn scalar(v: vec3<f32>) -> f32 {
    return max(v.x, max(v.y, v.z));
}

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

// The largest F over half vectors at angles from omega_i of at least acos(cos_h)
// (fresnel.rs Fresnel::max_from): Schlick's at cos_h; a dielectric's, quasiconvex in the
// angle (supplemental eq. 6), at one of the ends, evaluated 4 f32 ulps past cos_h
// (DIELECTRIC_ULPS).
fn fresnel_max_from(model: u32, f0: vec3<f32>, eta: f32, cos_h: f32) -> vec3<f32> {
    if model == FRESNEL_SCHLICK {
        return fresnel_schlick(f0, cos_h);
    }
    let past = cos_h * (1.0 - 4.0 * 1.1920929e-7);
    return vec3<f32>(max(fresnel_dielectric(eta, 1.0), fresnel_dielectric(eta, past)));
}
