// One VPL (GpuVpl in src/gpu_types.rs): position q and xi of eq. (3), normal n and GGX alpha,
// omega_i and a dielectric's eta, RGB flux, kd, Schlick F0; info = (lobe, Fresnel model, VPL
// id, unused).
struct Vpl {
    position_xi: vec4<f32>,
    normal_alpha: vec4<f32>,
    omega_i_eta: vec4<f32>,
    flux: vec4<f32>,
    kd: vec4<f32>,
    f0: vec4<f32>,
    info: vec4<u32>,
    // The geometric normal n_g (xyz; the shading normal unless normal-mapped) and the bound
    // factor (w: slc_bounds::shading_normal's flux_scale for a diffuse VPL,
    // GlossyLobe::bound_factor for a glossy one; 1 unless tilted or anisotropic; set by
    // GpuVpl::new).
    geometric_tilt: vec4<f32>,
    // The anisotropy's tangent (xyz) and alpha_t (w), zero where isotropic.
    anisotropy: vec4<f32>,
}

// slc_bounds::shading_normal::MIN_COS_GEOMETRIC.
const MIN_COS_GEOMETRIC: f32 = 1e-6;

// The factor GpuVpl::new stores in geometric_tilt.w, formed in f32 where the VPLs never
// leave the GPU (vpl_gen.wgsl): a diffuse VPL's flux_scale, a glossy one's
// GlossyLobe::bound_factor. The CPU forms the tilt and anisotropy factors in f64 with a
// relative margin of 1e-5; here the margin is 1e-4, which covers f32's rounding (a few
// 1e-7 relative) with room, so the factor is never below the CPU's.
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
        scale = ci / gi;
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
        let sin_t = min(length(cross(a, b)), 1.0);
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
