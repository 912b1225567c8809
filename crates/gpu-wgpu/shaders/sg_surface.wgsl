// A receiver of SG light (crates/bounds/src/sg/shading.rs SgSurface) in f32: its domain check,
// its diffuse and fitted GGX lobes, and the radiance it reflects for an incoming SG. Shared by
// the VSGL shading (receivers are G-buffer pixels) and the VSGL construction (an RSM texel's
// own lobes are a surface seen from its light, reciprocity). fresnel_ggx.wgsl, sg.wgsl and
// gsample.wgsl and specular_table.wgsl come first.

// specular.rs MIN_COS_O (specular_fit.rs TABLE_MIN_COS): views more grazing are fitted as at
// this cosine.
const MIN_COS_O: f32 = 1e-6;
// check.rs UNIT_TOLERANCE: a unit vector's length within this of 1.
const UNIT_TOLERANCE: f32 = 1e-3;

// What SgSurface::new takes: unit normal and view, kd, the isotropic GGX alpha
// (Brdf::isotropic_alpha) and the Fresnel model (FRESNEL_SCHLICK with F0 = f0_eta, else a
// dielectric of eta = f0_eta.x).
struct SurfaceIn {
    normal: vec3<f32>,
    omega_o: vec3<f32>,
    kd: vec3<f32>,
    alpha: f32,
    fresnel_kind: u32,
    f0_eta: vec3<f32>,
}

// The receiver of SgSurface: kd/pi (zero when viewed from below), its normal, and the
// specular lobe of SpecularLobeSg with its weight.
struct Surface {
    kd_over_pi: vec3<f32>,
    normal: vec3<f32>,
    lobe: Sg,
    weight: vec3<f32>,
}

fn finite3(v: vec3<f32>) -> bool {
    return sg_finite(v.x) && sg_finite(v.y) && sg_finite(v.z);
}

// Whether the surface is inside the domain SgSurface::new accepts (check.rs): unit normal and
// view, kd finite and >= 0, alpha in (0, 1], F0 in [0, 1] or eta finite and > 0, and a GGX
// SG sharpness 2/alpha^2 that fits f32.
fn valid_surface(s: SurfaceIn) -> bool {
    if !(finite3(s.normal) && finite3(s.omega_o) && finite3(s.kd)) {
        return false;
    }
    if abs(length(s.normal) - 1.0) > UNIT_TOLERANCE || abs(length(s.omega_o) - 1.0) > UNIT_TOLERANCE {
        return false;
    }
    if !(s.alpha > 0.0 && s.alpha <= 1.0) || !sg_finite(2.0 / (s.alpha * s.alpha)) || any(s.kd < vec3<f32>(0.0)) {
        return false;
    }
    let cos_o = dot(s.normal / length(s.normal), s.omega_o / length(s.omega_o));
    if cos_o > 0.0 && !sg_finite(fitted_sharpness(s.alpha, max(cos_o, MIN_COS_O))) {
        return false;
    }
    if s.fresnel_kind == FRESNEL_SCHLICK {
        return all(s.f0_eta >= vec3<f32>(0.0)) && all(s.f0_eta <= vec3<f32>(1.0));
    }
    let eta = s.f0_eta.x;
    return eta > 0.0 && sg_finite(eta);
}

// SpecularFit::lookup: [mirror weight, lambda alpha^2 (cos + alpha), integral, Fresnel's cosine] bilinear in
// the table's cells (alpha in steps of 1/16, sqrt(1 - cos) in steps of 1/32), clamped.
fn specular_fit(alpha: f32, cos_o: f32) -> vec4<f32> {
    let last_a = f32(SPECULAR_ALPHA_STEPS - 1u);
    let a = min(clamp(alpha, 0.0, 1.0) * last_a, last_a);
    let i = min(u32(max(floor(a), 0.0)), SPECULAR_ALPHA_STEPS - 2u);
    let fa = a - f32(i);
    // t = 32 sqrt(1 - c) and r = 32 - t = 32 c / (1 + sqrt(1 - c)), the node weights t - j and
    // r - (31 - j): no cancellation in the far node's weight at grazing views.
    let c = clamp(cos_o, 0.0, 1.0);
    let last = f32(SPECULAR_VIEW_STEPS - 1u);
    let r = last * c / (1.0 + sqrt(1.0 - c));
    let t = last - r;
    let j = min(u32(max(floor(t), 0.0)), SPECULAR_VIEW_STEPS - 2u);
    let w_hi = t - f32(j);
    let w_lo = r - f32(SPECULAR_VIEW_STEPS - 2u - j);
    let k = i * SPECULAR_VIEW_STEPS + j;
    let lo = specular_table[k] * w_lo + specular_table[k + 1u] * w_hi;
    let hi = specular_table[k + SPECULAR_VIEW_STEPS] * w_lo + specular_table[k + SPECULAR_VIEW_STEPS + 1u] * w_hi;
    return lo * (1.0 - fa) + hi * fa;
}

// SpecularFit::sharpness: the fit's lambda at a view cosine c >= MIN_COS_O, from
// lambda alpha^2 (c + alpha) (divided in steps: alpha^2 c would underflow for tiny alpha).
fn fitted_sharpness(alpha: f32, c: f32) -> f32 {
    return specular_fit(alpha, c).y / alpha / alpha / (c + alpha);
}

// SgSurface::new with SpecularLobeSg::new: the SG of specular_fit, its axis the peak
// normalize(w r + (1 - w) n) between the mirror direction r and n, its amplitude integral / A(lambda), its weight Fresnel at
// the fit's cosine; a view below the surface shades to zero.
fn make_surface(s: SurfaceIn) -> Surface {
    let n = s.normal / length(s.normal);
    let wo = s.omega_o / length(s.omega_o);
    let cos_o = dot(n, wo);
    if cos_o <= 0.0 {
        return Surface(vec3<f32>(0.0), n, Sg(n, 2.0 / (s.alpha * s.alpha), 0.0), vec3<f32>(0.0));
    }
    let c = max(cos_o, MIN_COS_O);
    let fit = specular_fit(s.alpha, c);
    let sharpness = fit.y / s.alpha / s.alpha / (c + s.alpha);
    var mirror = normalize(2.0 * cos_o * n - wo);
    if !finite3(mirror) {
        mirror = n;
    }
    var axis = normalize(mirror * fit.x + n * (1.0 - fit.x));
    if !finite3(axis) {
        axis = n;
    }
    let x = clamp(fit.w, 0.0, 1.0);
    var f: vec3<f32>;
    if s.fresnel_kind == FRESNEL_SCHLICK {
        f = fresnel_schlick(s.f0_eta, x);
    } else {
        f = vec3<f32>(fresnel_dielectric(s.f0_eta.x, x));
    }
    let lobe = Sg(axis, sharpness, fit.z / sg_integral(sharpness));
    return Surface(s.kd * (1.0 / PI), n, lobe, f);
}

// SgSurface::radiance: diffuse + specular of VSGL eq. (2) for the incoming SG light, each
// saturated at F32_MAX.
fn surface_radiance(surface: Surface, light: Sg) -> vec3<f32> {
    let diffuse = min(surface.kd_over_pi * sg_irradiance(light, surface.normal), vec3<f32>(F32_MAX));
    let specular = min(surface.weight * sg_inner_product(light, surface.lobe), vec3<f32>(F32_MAX));
    return min(diffuse + specular, vec3<f32>(F32_MAX));
}

// The receiver of a G-buffer sample (sg_surface.wgsl SurfaceIn; Brdf::isotropic_alpha: an
// anisotropic lobe's SG stands on sqrt(alpha_t alpha)).
fn sample_surface(s: Sample) -> SurfaceIn {
    var alpha = s.normal_alpha.w;
    if s.kd_alpha_t.w > 0.0 {
        alpha = sqrt(s.kd_alpha_t.w * s.normal_alpha.w);
    }
    return SurfaceIn(s.normal_alpha.xyz, s.omega_o_phi.xyz, s.kd_alpha_t.xyz, alpha,
                     sample_fresnel_kind(s), s.f0_eta);
}
