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
