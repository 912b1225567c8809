// One VPL's weighted contribution to a pixel (paper eq. 2-4), shared by the shading passes
// (shade.wgsl from light lists, tiled_shade.wgsl culling and shading in one pass): the GPU
// twin of crates/cpu-ref/src/vpl_shading.rs vpl_contribution. brdf.wgsl, gsample.wgsl and
// gvpl.wgsl are prepended. ShadeParams mirrors GpuShadeParams in src/gpu_types.rs.

struct ShadeParams {
    width: u32,
    height: u32,
    pixel_count: u32,
    vpl_count: u32,
    list_count: u32,
    delta: f32,
    // K^2 of the interleaved sampling (section 6).
    scale: f32,
    pad: u32,
}

const LOBE_DIFFUSE: u32 = 0u;

fn vpl_material(v: Vpl) -> Material {
    return Material(v.kd.xyz, FresnelModel(v.info.y, v.f0.xyz, v.omega_i_eta.w), v.normal_alpha.w,
                    v.anisotropy.xyz, v.anisotropy.w);
}

// slc_bounds::shading_normal::emitted_cosine: max(w.n, 0) where n_g = n (eq. 4), else the
// adjoint correction (w_i.n)(w.n_g)/(w_i.n_g) above both planes.
fn emitted_cosine(n: vec3<f32>, n_g: vec3<f32>, wi: vec3<f32>, w: vec3<f32>) -> f32 {
    if all(n == n_g) {
        return max(dot(n, w), 0.0);
    }
    let gi = dot(n_g, wi);
    let go = dot(n_g, w);
    if gi < MIN_COS_GEOMETRIC || go <= 0.0 || dot(n, w) <= 0.0 {
        return 0.0;
    }
    return max(dot(n, wi), 0.0) * go / gi;
}

// Radiant intensity of eq. (4) towards unit direction w: Phi f(w_i, w) max(w.n, 0), f the
// VPL's lobe, with the adjoint cosine of a normal-mapped VPL (Vpl::intensity).
fn vpl_intensity(v: Vpl, w: vec3<f32>) -> vec3<f32> {
    let n = v.normal_alpha.xyz;
    let cos_o = emitted_cosine(n, v.geometric_tilt.xyz, v.omega_i_eta.xyz, w);
    if cos_o <= 0.0 {
        return vec3<f32>(0.0);
    }
    let m = vpl_material(v);
    var f: vec3<f32>;
    if v.info.x == LOBE_DIFFUSE {
        f = brdf_diffuse(m, n, v.omega_i_eta.xyz, w);
    } else {
        f = microfacet(n, v.omega_i_eta.xyz, w, m);
    }
    return v.flux.xyz * f * cos_o;
}

// p of eq. (2) (StochasticParams::probability): min(I / (delta l^2), 1); 0 for I <= 0.
fn probability(intensity: f32, delta: f32, distance_sq: f32) -> f32 {
    if intensity > 0.0 {
        let p = intensity / (delta * distance_sq);
        if p >= 0.0 && p < 1.0 {
            return p;
        }
        return 1.0;
    }
    return 0.0;
}

// A receiving pixel as the shading loops hold it: its position, its shading normal, the
// direction to the camera and its BRDF, formed once per pixel (sample_material turns the
// tangent's angle into a vector with a sine and a cosine) rather than once per VPL.
struct Receiver {
    x: vec3<f32>,
    n: vec3<f32>,
    omega_o: vec3<f32>,
    material: Material,
}

fn receiver(s: Sample, x: vec3<f32>) -> Receiver {
    return Receiver(x, s.normal_alpha.xyz, s.omega_o_phi.xyz, sample_material(s));
}

// One VPL's contribution to the radiance towards the camera, weighted by the estimator of
// eq. (3) (1/p if p > xi, else 0): vpl_contribution of vpl_shading.rs.
fn vpl_contribution(r: Receiver, v: Vpl, delta: f32) -> vec3<f32> {
    let d = r.x - v.position_xi.xyz;
    let l2 = length_sq(d);
    if l2 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let omega = d / sqrt(l2);
    let cos_x = -dot(r.n, omega);
    if cos_x <= 0.0 {
        return vec3<f32>(0.0);
    }
    let intensity = vpl_intensity(v, omega);
    let p = probability(max(intensity.x, max(intensity.y, intensity.z)), delta, l2);
    var weight = 0.0;
    if p > v.position_xi.w {
        weight = 1.0 / p;
    }
    if weight == 0.0 {
        return vec3<f32>(0.0);
    }
    return brdf_eval(r.material, r.n, -omega, r.omega_o) * intensity * (weight * cos_x / l2);
}
