// One G-buffer pixel (GpuSample in src/gpu_types.rs): present = 1 for a sample, 0 for an
// empty (sky) pixel; fresnel the Fresnel model (FRESNEL_SCHLICK with f0, FRESNEL_DIELECTRIC
// with eta = omega_o_eta.w). The position lives in its own array ([x, y, z, 1], zero where
// empty), which the culling passes read too, so that a 1920 x 1080 G-buffer fits lavapipe's
// 128 MiB storage binding (64 bytes per sample).
struct Sample {
    normal_alpha: vec4<f32>,
    omega_o_eta: vec4<f32>,
    kd: vec3<f32>,
    present: u32,
    f0: vec3<f32>,
    fresnel: u32,
}
