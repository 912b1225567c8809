// Shading by virtual spherical Gaussian lights (Tokuyoshi 2015, section 3.2, eq. 2-5), the GPU
// twin of crates/cpu-ref/src/vsgl/shading.rs shade_vsgls without visibility: each pixel with
// a sample sums, over the VSGLs, for each lobe c_v G(w; xi_v, lambda_v) of the VSGL's radiant
// intensity, c_v times the reflected radiance of the incoming SG of eq. (5)
//   L_in(w) = 1/(2 pi sigma_v^2) G(w; -xi_v, lambda_v) G(w; xi_mu, lambda_sigma),
//   xi_mu = (mu_v - x_p)/|mu_v - x_p|, lambda_sigma = |mu_v - x_p|^2 / sigma_v^2 (eq. 4),
// a product of two SGs, shaded in closed form as crates/bounds/src/sg/shading.rs SgSurface
// does: kd/pi times its irradiance plus the warped GGX lobe's weight times an inner product
// (specular.rs SpecularLobeSg). fresnel_ggx.wgsl, sg.wgsl and gsample.wgsl come first.
// Structs mirror src/vsgl_types.rs; one invocation per pixel, linear workgroup index
// wid.y * num_workgroups.x + wid.x (buffers::Grid).

struct VsglParams {
    pixel_count: u32,
    vsgl_count: u32,
    pad0: u32,
    pad1: u32,
}

// One VSGL prepared for shading (shading.rs Emitter): mu_v and sigma_v^2, and per lobe
// c_v (rgb, zero for a lobe left out) and the emitted lobe's axis -xi_v with lambda_v.
struct Vsgl {
    mu_sigma2: vec4<f32>,
    // c_v of the diffuse lobe (xyz), 1 / (2 pi sigma_v^2) of eq. (1) and (5) (w).
    diffuse_c_density: vec4<f32>,
    diffuse_lobe: vec4<f32>,
    specular_c: vec4<f32>,
    specular_lobe: vec4<f32>,
}

// The fault record: smallest pixel whose surface is outside the SG math's domain, smallest
// VSGL whose lambda_sigma or product left f32 (u32::MAX: none).
struct VsglStatus {
    bad_pixel: atomic<u32>,
    overflow_vsgl: atomic<u32>,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> params: VsglParams;
@group(0) @binding(1) var<storage, read> samples: array<Sample>;
@group(0) @binding(2) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vsgls: array<Vsgl>;
// RGB per pixel.
@group(0) @binding(4) var<storage, read_write> image: array<f32>;
@group(0) @binding(5) var<storage, read_write> status: VsglStatus;

const WORKGROUP: u32 = 64u;
// specular.rs MIN_COS_O: views more grazing are warped as at this cosine.
const MIN_COS_O: f32 = 1e-6;
// check.rs UNIT_TOLERANCE: a unit vector's length within this of 1.
const UNIT_TOLERANCE: f32 = 1e-3;

// The receiver of shading.rs SgSurface: kd/pi (zero when viewed from below), its normal, and
// the specular lobe of SpecularLobeSg with its weight.
struct Surface {
    kd_over_pi: vec3<f32>,
    normal: vec3<f32>,
    lobe: Sg,
    weight: vec3<f32>,
}

fn finite3(v: vec3<f32>) -> bool {
    return sg_finite(v.x) && sg_finite(v.y) && sg_finite(v.z);
}

// Brdf::isotropic_alpha: an anisotropic lobe's SG stands on sqrt(alpha_t alpha).
fn isotropic_alpha(s: Sample) -> f32 {
    if s.kd_alpha_t.w > 0.0 {
        return sqrt(s.kd_alpha_t.w * s.normal_alpha.w);
    }
    return s.normal_alpha.w;
}

// Whether the sample is inside the domain SgSurface::new accepts (check.rs): unit normal and
// view, kd finite and >= 0, alpha in (0, 1], F0 in [0, 1] or eta finite and > 0, and a GGX
// SG sharpness 2/alpha^2 that fits f32.
fn valid_surface(s: Sample) -> bool {
    let n = s.normal_alpha.xyz;
    let wo = s.omega_o_phi.xyz;
    let alpha = isotropic_alpha(s);
    let kd = s.kd_alpha_t.xyz;
    if !(finite3(n) && finite3(wo) && finite3(kd)) {
        return false;
    }
    if abs(length(n) - 1.0) > UNIT_TOLERANCE || abs(length(wo) - 1.0) > UNIT_TOLERANCE {
        return false;
    }
    if !(alpha > 0.0 && alpha <= 1.0) || !sg_finite(2.0 / (alpha * alpha)) || any(kd < vec3<f32>(0.0)) {
        return false;
    }
    if sample_fresnel_kind(s) == FRESNEL_SCHLICK {
        return all(s.f0_eta >= vec3<f32>(0.0)) && all(s.f0_eta <= vec3<f32>(1.0));
    }
    let eta = s.f0_eta.x;
    return eta > 0.0 && sg_finite(eta);
}

// SgSurface::new with SpecularLobeSg::new and ggx_ndf_sg: D(h) ~ 1/(pi a^2) G(h; n, 2/a^2)
// moved to the mirror direction with its sharpness over 4 wo.n, weight
// F(wo.n) G1(wo.n)^2 / (4 wo.n); a view below the surface shades to zero.
fn make_surface(s: Sample) -> Surface {
    let n = s.normal_alpha.xyz / length(s.normal_alpha.xyz);
    let wo = s.omega_o_phi.xyz / length(s.omega_o_phi.xyz);
    let alpha = isotropic_alpha(s);
    let a2 = alpha * alpha;
    let cos_o = dot(n, wo);
    if cos_o <= 0.0 {
        return Surface(vec3<f32>(0.0), n, Sg(n, 2.0 / a2, 0.0), vec3<f32>(0.0));
    }
    let c = max(cos_o, MIN_COS_O);
    var mirror = normalize(2.0 * cos_o * n - wo);
    if !finite3(mirror) {
        mirror = n;
    }
    let g = ggx_g1_over_cos(alpha, c);
    var f: vec3<f32>;
    if sample_fresnel_kind(s) == FRESNEL_SCHLICK {
        f = fresnel_schlick(s.f0_eta, c);
    } else {
        f = vec3<f32>(fresnel_dielectric(s.f0_eta.x, c));
    }
    let lobe = Sg(mirror, (2.0 / a2) / (4.0 * c), 1.0 / (PI * a2));
    return Surface(s.kd_alpha_t.xyz * (1.0 / PI), n, lobe, f * (0.25 * g * g * c));
}

// SgSurface::radiance: diffuse + specular of VSGL eq. (2) for the incoming SG light, each
// saturated at F32_MAX.
fn surface_radiance(surface: Surface, light: Sg) -> vec3<f32> {
    let diffuse = min(surface.kd_over_pi * sg_irradiance(light, surface.normal), vec3<f32>(F32_MAX));
    let specular = min(surface.weight * sg_inner_product(light, surface.lobe), vec3<f32>(F32_MAX));
    return min(diffuse + specular, vec3<f32>(F32_MAX));
}

// The radiance one VSGL reflects at the receiver (xyz), w = 1 when the positional SG left
// f32 (the pixel's sum stops there, as it always did).
fn vsgl_contribution(surface: Surface, x: vec3<f32>, v: u32) -> vec4<f32> {
    let e = vsgls[v];
    let sigma2 = e.mu_sigma2.w;
    let density = e.diffuse_c_density.w;
    // Emitter::radiance: the positional SG of eq. (4); constant at mu_v itself.
    let d = e.mu_sigma2.xyz - x;
    let r2 = dot(d, d);
    var position = Sg(vec3<f32>(0.0, 0.0, 1.0), 0.0, density);
    if r2 > 0.0 {
        position = Sg(d / sqrt(r2), r2 / sigma2, density);
        if !sg_finite(position.sharpness) {
            atomicMin(&status.overflow_vsgl, v);
            return vec4<f32>(0.0, 0.0, 0.0, 1.0);
        }
    }
    var radiance = vec3<f32>(0.0);
    let lobes = array<vec4<f32>, 2>(e.diffuse_lobe, e.specular_lobe);
    let colours = array<vec3<f32>, 2>(e.diffuse_c_density.xyz, e.specular_c.xyz);
    let clamped = e.specular_c.w != 0.0;
    for (var k = 0u; k < 2u; k++) {
        let c = colours[k];
        if all(c == vec3<f32>(0.0)) || (clamped && k == 0u) {
            continue;
        }
        let emitted = Sg(lobes[k].xyz, lobes[k].w, 1.0);
        let light = sg_product(emitted, position);
        if !(sg_finite(light.sharpness) && sg_finite(light.amplitude)) {
            atomicMin(&status.overflow_vsgl, v);
        }
        radiance += c * surface_radiance(surface, light);
    }
    // The clamped-cosine diffuse intensity (DiffuseEmission::ClampedCosine): the
    // peak times the vMF-convolved clamped cosine towards the receiver (a quarter
    // at mu_v itself), carried by the positional SG.
    let peak = e.diffuse_c_density.xyz;
    if clamped && any(peak != vec3<f32>(0.0)) {
        var towards = 0.25;
        if r2 > 0.0 {
            towards = sg_normalized_irradiance(e.diffuse_lobe.w, -dot(e.diffuse_lobe.xyz, position.axis));
        }
        if towards > 0.0 {
            radiance += peak * towards * surface_radiance(surface, position);
        }
    }
    return vec4<f32>(radiance, 0.0);
}

fn write_pixel(pixel: u32, sum: vec3<f32>) {
    image[3u * pixel] = sum.x;
    image[3u * pixel + 1u] = sum.y;
    image[3u * pixel + 2u] = sum.z;
}

// Without visibility (shade_vsgls(..., visibility = false, ...)).
@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if pixel >= params.pixel_count {
        return;
    }
    let s = samples[pixel];
    var sum = vec3<f32>(0.0);
    if sample_present(s) {
        if valid_surface(s) {
            let surface = make_surface(s);
            let x = positions[pixel].xyz;
            for (var v = 0u; v < params.vsgl_count; v++) {
                let r = vsgl_contribution(surface, x, v);
                if r.w != 0.0 {
                    break;
                }
                sum += r.xyz;
            }
        } else {
            atomicMin(&status.bad_pixel, pixel);
        }
    }
    write_pixel(pixel, sum);
}

// With visibility from imperfect shadow maps (ism.wgsl; ism_map.wgsl comes before this file):
// the geometric normal per pixel (xyz), the maps' parameters and their distances (one map of
// resolution^2 f32 bits per VSGL, in VSGL order).
@group(0) @binding(6) var<storage, read> geometric_normals: array<vec4<f32>>;
@group(0) @binding(7) var<uniform> ism: IsmParams;
@group(0) @binding(8) var<storage, read> ism_depth: array<u32>;

// V(x_p, mu_v) of eq. (3) from the map of VSGL v: the receiver x lifted by the tracer's
// epsilon along its geometric normal (Tracer::lift) is visible when its distance to mu_v is at
// most the map's distance in its direction plus the bias
//   lift + dist * texel_angle * (bias_constant + bias_slope * tan(incidence)),
// the incidence between the geometric normal and the direction to mu_v, its tangent capped at
// 20 (receivers more grazing than 87 degrees reflect next to nothing). Segments no longer than
// twice the lift are unoccluded, as Tracer::unoccluded has them.
fn ism_visible(v: u32, x: vec3<f32>, n_g: vec3<f32>, mu: vec3<f32>) -> bool {
    let d = x + n_g * ism.lift - mu;
    let dist = length(d);
    if dist <= 2.0 * ism.lift {
        return true;
    }
    let dir = d / dist;
    let res = ism.resolution;
    let t = oct_texel(dir, res);
    let z = bitcast<f32>(ism_depth[v * res * res + t.y * res + t.x]);
    let c = max(abs(dot(n_g, dir)), 0.05);
    let slope = sqrt(max(1.0 - c * c, 0.0)) / c;
    let bias = ism.lift + dist * ism.texel_angle * (ism.bias_constant + ism.bias_slope * slope);
    return dist <= z + bias;
}

// shade_vsgls(..., visibility = true, ...) with the maps for shadow rays: each VSGL that
// contributes is weighted by ism_visible.
@compute @workgroup_size(64)
fn main_visible(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if pixel >= params.pixel_count {
        return;
    }
    let s = samples[pixel];
    var sum = vec3<f32>(0.0);
    if sample_present(s) {
        if valid_surface(s) {
            let surface = make_surface(s);
            let x = positions[pixel].xyz;
            let n_g = geometric_normals[pixel].xyz;
            for (var v = 0u; v < params.vsgl_count; v++) {
                let r = vsgl_contribution(surface, x, v);
                if r.w != 0.0 {
                    break;
                }
                if any(r.xyz != vec3<f32>(0.0)) && ism_visible(v, x, n_g, vsgls[v].mu_sigma2.xyz) {
                    sum += r.xyz;
                }
            }
        } else {
            atomicMin(&status.bad_pixel, pixel);
        }
    }
    write_pixel(pixel, sum);
}
