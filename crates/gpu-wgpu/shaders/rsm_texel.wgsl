// What one RSM texel saw (GpuRsmTexel in src/raster_types.rs): position (xyz) and 1 where the
// texel holds a photon (w); shading normal and GGX alpha; omega_i towards the light and a
// dielectric's eta; flux; kd; Schlick F0; info = (Fresnel model, unused...).
struct RsmTexel {
    position: vec4<f32>,
    normal_alpha: vec4<f32>,
    omega_i_eta: vec4<f32>,
    flux: vec4<f32>,
    kd: vec4<f32>,
    f0: vec4<f32>,
    info: vec4<u32>,
    // geometric normal (xyz), 1 where normal-mapped (w)
    geometric: vec4<f32>,
    // the BRDF's anisotropy: tangent (xyz), alpha_t (w), zero where isotropic
    anisotropy: vec4<f32>,
}
