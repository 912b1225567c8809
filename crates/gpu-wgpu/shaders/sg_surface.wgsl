// A receiver of SG light (crates/bounds/src/sg/shading.rs SgSurface) in f32: its domain check,
// its diffuse and warped GGX lobes, and the radiance it reflects for an incoming SG. Shared by
// the VSGL shading (receivers are G-buffer pixels) and the VSGL construction (an RSM texel's
// own lobes are a surface seen from its light, reciprocity). fresnel_ggx.wgsl, sg.wgsl and
// gsample.wgsl come first.

// specular.rs MIN_COS_O: views more grazing are warped as at this cosine.
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
    if s.fresnel_kind == FRESNEL_SCHLICK {
        return all(s.f0_eta >= vec3<f32>(0.0)) && all(s.f0_eta <= vec3<f32>(1.0));
    }
    let eta = s.f0_eta.x;
    return eta > 0.0 && sg_finite(eta);
}

// SgSurface::new with SpecularLobeSg::new and ggx_ndf_sg: D(h) ~ 1/(pi a^2) G(h; n, 2/a^2)
// moved to the mirror direction with its sharpness over 4 wo.n, weight
// F(wo.n) G1(wo.n)^2 / (4 wo.n); a view below the surface shades to zero.
fn make_surface(s: SurfaceIn) -> Surface {
    let n = s.normal / length(s.normal);
    let wo = s.omega_o / length(s.omega_o);
    let a2 = s.alpha * s.alpha;
    let cos_o = dot(n, wo);
    if cos_o <= 0.0 {
        return Surface(vec3<f32>(0.0), n, Sg(n, 2.0 / a2, 0.0), vec3<f32>(0.0));
    }
    let c = max(cos_o, MIN_COS_O);
    var mirror = normalize(2.0 * cos_o * n - wo);
    if !finite3(mirror) {
        mirror = n;
    }
    let g = ggx_g1_over_cos(s.alpha, c);
    var f: vec3<f32>;
    if s.fresnel_kind == FRESNEL_SCHLICK {
        f = fresnel_schlick(s.f0_eta, c);
    } else {
        f = vec3<f32>(fresnel_dielectric(s.f0_eta.x, c));
    }
    let lobe = Sg(mirror, (2.0 / a2) / (4.0 * c), 1.0 / (PI * a2));
    return Surface(s.kd * (1.0 / PI), n, lobe, f * (0.25 * g * g * c));
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
