// VPL generation, the GPU twin of crates/cpu-ref/src/vpls.rs generate_vpls: texel k of one
// light's map (global texel index base + k over the concatenated maps) makes a diffuse VPL
// with id 2 (base + k) where kd > 0 and a glossy VPL with id 2 (base + k) + 1 where the
// specular layer reflects (max over half vectors of F at normal incidence > 0,
// Fresnel::max_over_half_vectors(1, 0)), each if the lobe is wanted; xi = vpl_xi(seed, id)
// (rng.wgsl). Run twice like the tiled culler: CULL_COUNT writes each texel's VPL count,
// the scan (scan.wgsl) turns counts into offsets, CULL_WRITE writes the VPLs at their
// offsets: the same order as the CPU (texel-major, diffuse before glossy), compacted.
// rng.wgsl and fresnel_ggx.wgsl are prepended; structs mirror src/raster_types.rs and
// src/gpu_types.rs.

struct VplGenParams {
    texel_count: u32,
    base: u32,
    seed: u32,
    // bit 0 diffuse, bit 1 glossy
    lobes: u32,
    mode: u32,
    cos_h_max: f32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> params: VplGenParams;
@group(0) @binding(1) var<storage, read> texels: array<RsmTexel>;
// Counts (CULL_COUNT) or offsets after the scan (CULL_WRITE), per global texel.
@group(0) @binding(2) var<storage, read_write> counts: array<u32>;
@group(0) @binding(3) var<storage, read_write> vpls: array<Vpl>;

const CULL_COUNT: u32 = 0u;
const LOBE_DIFFUSE: u32 = 0u;
const LOBE_GLOSSY: u32 = 1u;
const WORKGROUP: u32 = 64u;

fn max3(v: vec3<f32>) -> f32 {
    return max(v.x, max(v.y, v.z));
}

// Fresnel::max_over_half_vectors(1, 0) > 0 for the texel's Fresnel model.
fn reflects(t: RsmTexel) -> bool {
    let c = params.cos_h_max;
    if t.info.x == FRESNEL_SCHLICK {
        return max3(fresnel_schlick(t.f0.xyz, c)) > 0.0;
    }
    let eta = t.omega_i_eta.w;
    return max(fresnel_dielectric(eta, 1.0), fresnel_dielectric(eta, c)) > 0.0;
}

// The factor GpuVpl::new stores in geometric_tilt.w, formed in f32 so that the VPLs
// never leave the GPU: a diffuse VPL's flux_scale, a glossy one's
// GlossyLobe::bound_factor. The CPU forms the tilt and anisotropy factors in f64 with a
// relative margin of 1e-5; here the margin is 1e-4, which covers f32's relative rounding (a
// few 1e-7) with room, the tilt's sine grows by 1e-6 for its absolute rounding, and the
// diffuse ratio by 1e-6: the factor is never below the CPU's.
fn vpl_bound_factor(v: Vpl) -> f32 {
    let n = v.normal_alpha.xyz;
    let n_g = v.geometric_tilt.xyz;
    let wi = v.omega_i_eta.xyz;
    var scale = 1.0;
    let tilted = any(n != n_g);
    if tilted {
        // shading_normal::flux_scale.
        let ci = dot(n, wi);
        let gi = dot(n_g, wi);
        if ci <= 0.0 || gi < MIN_COS_GEOMETRIC {
            return 0.0;
        }
        scale = ci / gi * (1.0 + 1e-6);
    }
    // LOBE_DIFFUSE.
    if v.info.x == 0u {
        return scale;
    }
    let alpha = v.normal_alpha.w;
    let alpha_t = v.anisotropy.w;
    let alpha_min = select(alpha, min(alpha, alpha_t), alpha_t > 0.0);
    var factor = scale;
    if tilted {
        // shading_normal::g1_tilt_max: cos t + (2 / alpha_min) sin t, at least G1(1).
        let a = normalize(n);
        let b = normalize(n_g);
        let cos_t = clamp(dot(a, b), -1.0, 1.0);
        // The sine's f32 error is absolute (about 2e-7): 1e-6 more covers it before the
        // division by alpha magnifies it.
        let sin_t = min(length(cross(a, b)) + 1e-6, 1.0);
        let bound = max(cos_t, 0.0) + 2.0 * sin_t / alpha_min;
        factor *= max(bound, ggx_g1_over_cos(alpha_min, 1.0)) * (1.0 + 1e-4);
    }
    if alpha_t > 0.0 {
        factor *= anisotropy_bound_factor(v.anisotropy.xyz, alpha_t, alpha, n, wi);
    }
    return factor;
}

// Anisotropy::bound_factor: (alpha_max^2 / (alpha_t alpha_b)) times the ratio of G1(w_i)
// of the lobe to that of alpha_max (at least 1), times 1 / ((1 - eps/alpha_t)^2 |t_perp|^4)
// for a tangent eps off the normal's plane; infinite for eps >= alpha_t / 2.
fn anisotropy_bound_factor(t: vec3<f32>, alpha_t: f32, alpha_b: f32, n: vec3<f32>,
                           wi: vec3<f32>) -> f32 {
    let a_max = max(alpha_t, alpha_b);
    let eps = abs(dot(t, n));
    if eps >= 0.5 * alpha_t {
        return bitcast<f32>(0x7f800000u);
    }
    let perp2 = min(dot(t, t) - eps * eps, 1.0);
    let shrink = 1.0 - eps / alpha_t;
    let peak = a_max * a_max / (alpha_t * alpha_b * shrink * shrink * perp2 * perp2);
    let c = abs(dot(n, wi));
    let x = alpha_t * dot(t, wi);
    let y = alpha_b * dot(cross(n, t), wi);
    let g1_own = 1.0 / (c + sqrt(c * c + x * x + y * y));
    let cr = cross(n, wi);
    let g1_max = 1.0 / (c + sqrt(c * c + a_max * a_max * dot(cr, cr)));
    return peak * max(g1_own / g1_max, 1.0) * (1.0 + 1e-4);
}

fn make_vpl(t: RsmTexel, lobe: u32, id: u32) -> Vpl {
    var v = Vpl(
        vec4<f32>(t.position.xyz, vpl_xi(params.seed, id)),
        t.normal_alpha,
        t.omega_i_eta,
        t.flux,
        t.kd,
        t.f0,
        vec4<u32>(lobe, t.info.x, id, 0u),
        vec4<f32>(select(t.normal_alpha.xyz, t.geometric.xyz, t.geometric.w != 0.0), 1.0),
        t.anisotropy,
    );
    v.geometric_tilt.w = vpl_bound_factor(v);
    return v;
}

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if k >= params.texel_count {
        return;
    }
    let t = texels[k];
    let lit = t.position.w != 0.0;
    let diffuse = lit && (params.lobes & 1u) != 0u && max3(t.kd.xyz) > 0.0;
    let glossy = lit && (params.lobes & 2u) != 0u && reflects(t);
    let g = params.base + k;
    if params.mode == CULL_COUNT {
        counts[g] = u32(diffuse) + u32(glossy);
        return;
    }
    var at = counts[g];
    if diffuse {
        vpls[at] = make_vpl(t, LOBE_DIFFUSE, 2u * g);
        at += 1u;
    }
    if glossy {
        vpls[at] = make_vpl(t, LOBE_GLOSSY, 2u * g + 1u);
    }
}
