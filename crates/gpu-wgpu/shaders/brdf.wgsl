// The surface BRDF of crates/bounds (brdf.rs, ggx.rs, fresnel.rs) in WGSL: the one-sided
// Lambertian diffuse kd/pi plus the GGX microfacet lobe of eq. (6) with D of eq. (7) and the
// separable Smith G2 = G1(wi) G1(wo) of eq. (8). Every formula keeps the CPU's operation order
// so f32 results agree to a few ulps. Prepended to shade.wgsl, after fresnel_ggx.wgsl.
//
// One place needs care: where the CPU forms the half vector in f64 (|wi + wo|^2 alpha^2 <=
// 1e-6: wi and wo almost opposite, i.e. grazing incidence near the mirror direction, with a
// smooth lobe), WGSL has no f64. A plain f32 half vector of renormalised inputs is off by
// ~1e-7 / |wi + wo| rad there, which moves D near its peak by ~4e-7 / (alpha |wi + wo|)
// relative (2.5e-2 measured at alpha = 1e-3, a view 1e-4 rad above the surface). Instead the
// f64 result is emulated with error-free f32 transformations (fma products, TwoSum): measured
// 2.2e-7 relative on lavapipe. A compiler that reassociates floating-point sums (fast math)
// would undo TwoSum and fall back to the plain f32 error in that domain only; elsewhere both
// sides evaluate the same f32 formulas.

const FRAC_1_PI: f32 = 0.318309886183791;

// The Fresnel model of eq. (6): Schlick with RGB F0 (supplemental eq. 1) or the unpolarised
// dielectric factor with relative index eta (supplemental eq. 3-5). Mirrors
// slc_bounds::Fresnel.
struct FresnelModel {
    kind: u32,
    f0: vec3<f32>,
    eta: f32,
}

// A BRDF as brdf.rs's Brdf: diffuse reflectance, Fresnel model, GGX roughness alpha, and an
// anisotropy's unit tangent and alpha_t (alpha_t = 0: isotropic; alpha is then the roughness
// along the bitangent cross(n, tangent), slc_bounds::anisotropy).
struct Material {
    kd: vec3<f32>,
    fresnel: FresnelModel,
    alpha: f32,
    tangent: vec3<f32>,
    alpha_t: f32,
}

// The BRDF of a G-buffer sample (gsample.wgsl; GpuSample::brdf): the tangent rebuilt from its
// angle in the frame of frame.wgsl (Anisotropy::from_angle).
fn sample_material(s: Sample) -> Material {
    let n = s.normal_alpha.xyz;
    let phi = s.omega_o_phi.w;
    let tangent = frame_x(n) * cos(phi) + frame_y(n) * sin(phi);
    return Material(s.kd_alpha_t.xyz, FresnelModel(sample_fresnel_kind(s), s.f0_eta, s.f0_eta.x),
                    s.normal_alpha.w, tangent, s.kd_alpha_t.w);
}

// GGX D of eq. (7) from cos and sin^2 of the microfacet angle (ggx.rs d_with_sin2).
fn ggx_d_with_sin2(alpha: f32, cos_m: f32, sin2_m: f32) -> f32 {
    if cos_m <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let denom = a2 * cos_m * cos_m + max(sin2_m, 0.0);
    return a2 / (PI * denom * denom);
}

// The anisotropic GGX D (ggx.rs d_anisotropic, Heitz 2014 eq. 85) of a micro-normal with
// components (m_t, m_b, m_n) in the frame (t, b, n).
fn ggx_d_anisotropic(alpha_t: f32, alpha_b: f32, m_t: f32, m_b: f32, m_n: f32) -> f32 {
    if m_n <= 0.0 {
        return 0.0;
    }
    let x = m_t / alpha_t;
    let y = m_b / alpha_b;
    let denom = x * x + y * y + m_n * m_n;
    return 1.0 / (PI * alpha_t * alpha_b * denom * denom);
}

// G1(w) / |w.n| of the anisotropic Smith function (ggx.rs g1_over_cos_anisotropic, Heitz 2014
// eq. 86).
fn ggx_g1_over_cos_anisotropic(alpha_t: f32, alpha_b: f32, w_t: f32, w_b: f32, w_n: f32) -> f32 {
    let x = alpha_t * w_t;
    let y = alpha_b * w_b;
    let c = abs(w_n);
    return 2.0 / (c + sqrt(c * c + x * x + y * y));
}

fn fresnel_eval(f: FresnelModel, cos_h: f32) -> vec3<f32> {
    if f.kind == FRESNEL_SCHLICK {
        return fresnel_schlick(f.f0, cos_h);
    }
    return vec3<f32>(fresnel_dielectric(f.eta, cos_h));
}

fn length_sq(v: vec3<f32>) -> f32 {
    return dot(v, v);
}

// (s, e) with s = fl(a + b) and a + b = s + e exactly (Knuth's TwoSum).
fn two_sum(a: f32, b: f32) -> vec2<f32> {
    let s = a + b;
    let bb = s - a;
    return vec2<f32>(s, (a - (s - bb)) + (b - bb));
}

// |v|^2 - 1 to about f32 precision of the result itself (not of |v|^2): exact squares by fma,
// exact sums by TwoSum. For a unit vector in f32 it is ~1e-7, which plain f32 would round away.
fn norm2_minus_one(v: vec3<f32>) -> f32 {
    let p = v * v;
    let e = vec3<f32>(fma(v.x, v.x, -p.x), fma(v.y, v.y, -p.y), fma(v.z, v.z, -p.z));
    let s1 = two_sum(p.x, p.y);
    let s2 = two_sum(s1.x, p.z);
    let s3 = two_sum(s2.x, -1.0);
    return s3.x + ((s1.y + s2.y + s3.y) + (e.x + e.y + e.z));
}

// a b - c d with about one rounding (Kahan's fma algorithm).
fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let w = c * d;
    return fma(a, b, -w) + fma(-c, d, w);
}

fn accurate_cross(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        difference_of_products(a.y, b.z, a.z, b.y),
        difference_of_products(a.z, b.x, a.x, b.z),
        difference_of_products(a.x, b.y, a.y, b.x),
    );
}

// The GGX microfacet BRDF of eq. (6): F(wi.h) D(n.h) G1(wi) G1(wo) / (4 |wi.n| |wo.n|), zero
// unless both directions are above the surface (brdf.rs microfacet), D and G1 anisotropic
// where m is. sin^2 of the half vector's angle comes from |n x h|^2, which resolves D near its
// peak for tiny alpha.
fn microfacet(n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, m: Material) -> vec3<f32> {
    let alpha = m.alpha;
    let f = m.fresnel;
    let cos_i = dot(n, wi);
    let cos_o = dot(n, wo);
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return vec3<f32>(0.0);
    }
    let t = m.tangent;
    let b = cross(n, t);
    let anisotropic = m.alpha_t > 0.0;
    var g: f32;
    var alpha_min = alpha;
    if anisotropic {
        g = ggx_g1_over_cos_anisotropic(m.alpha_t, alpha, dot(t, wi), dot(b, wi), dot(n, wi))
            * ggx_g1_over_cos_anisotropic(m.alpha_t, alpha, dot(t, wo), dot(b, wo), dot(n, wo));
        alpha_min = min(m.alpha_t, alpha);
    } else {
        g = ggx_g1_over_cos(alpha, cos_i) * ggx_g1_over_cos(alpha, cos_o);
    }
    let s = wi + wo;
    let s2 = length_sq(s);
    var d: f32;
    var cos_ih: f32;
    if s2 * alpha_min * alpha_min > 1e-6 {
        let h = s / sqrt(s2);
        if anisotropic {
            d = ggx_d_anisotropic(m.alpha_t, alpha, dot(t, h), dot(b, h), dot(n, h));
        } else {
            d = ggx_d_with_sin2(alpha, dot(n, h), length_sq(cross(n, h)));
        }
        cos_ih = dot(wi, h);
    } else {
        // The CPU's f64 branch (see the header), emulated in f32: wi + wo is exact where its
        // components cancel (Sterbenz), the renormalisation of wi and wo becomes an exactly
        // computed first-order correction, and n x h uses error-compensated products.
        let ei = 0.5 * norm2_minus_one(wi);
        let eo = 0.5 * norm2_minus_one(wo);
        let sum = (wi + wo) - (wi * ei + wo * eo);
        let h = sum / sqrt(length_sq(sum));
        let n2 = length_sq(n);
        if anisotropic {
            let nn = n / sqrt(n2);
            d = ggx_d_anisotropic(m.alpha_t, alpha, dot(t, h), dot(cross(nn, t), h), dot(nn, h));
        } else {
            d = ggx_d_with_sin2(alpha, dot(n, h) / sqrt(n2), length_sq(accurate_cross(n, h)) / n2);
        }
        cos_ih = dot(wi, h) * (1.0 - ei);
    }
    return fresnel_eval(f, cos_ih) * (0.25 * d * g);
}

// The full one-sided BRDF kd/pi + eq. (6) (brdf.rs Brdf::eval); wi and wo point away from the
// surface.
fn brdf_eval(m: Material, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    if dot(n, wi) <= 0.0 || dot(n, wo) <= 0.0 {
        return vec3<f32>(0.0);
    }
    return m.kd * FRAC_1_PI + microfacet(n, wi, wo, m);
}

// The Lambertian part kd/pi alone, one-sided (brdf.rs Brdf::diffuse): a diffuse VPL's BRDF.
fn brdf_diffuse(m: Material, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    if dot(n, wi) <= 0.0 || dot(n, wo) <= 0.0 {
        return vec3<f32>(0.0);
    }
    return m.kd * FRAC_1_PI;
}
