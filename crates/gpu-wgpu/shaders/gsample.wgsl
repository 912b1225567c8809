// One G-buffer pixel (GpuSample in src/gpu_types.rs). flags: SAMPLE_PRESENT for a sample
// (0 for an empty, sky pixel) | SAMPLE_DIELECTRIC for a dielectric Fresnel with eta =
// f0_eta.x (Schlick with F0 = f0_eta otherwise). An anisotropic lobe has alpha_t =
// kd_alpha_t.w > 0 and its tangent at the angle omega_o_phi.w around the normal in the frame
// of frame.wgsl (slc_bounds::Anisotropy::angle). The position lives in its own array
// ([x, y, z, 1], zero where empty), which the culling passes read too, so that a
// 1920 x 1080 G-buffer fits lavapipe's 128 MiB storage binding (64 bytes per sample).
struct Sample {
    normal_alpha: vec4<f32>,
    omega_o_phi: vec4<f32>,
    kd_alpha_t: vec4<f32>,
    f0_eta: vec3<f32>,
    flags: u32,
}

const SAMPLE_PRESENT: u32 = 1u;
const SAMPLE_DIELECTRIC: u32 = 2u;

fn sample_present(s: Sample) -> bool {
    return (s.flags & SAMPLE_PRESENT) != 0u;
}

// The Fresnel model code of gpu_types.rs (FRESNEL_SCHLICK 0, FRESNEL_DIELECTRIC 1).
fn sample_fresnel_kind(s: Sample) -> u32 {
    return select(0u, 1u, (s.flags & SAMPLE_DIELECTRIC) != 0u);
}
