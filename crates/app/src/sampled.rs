//! VSGLs and VPLs sampled at equal count from a prepared frame's RSMs, for `compare` and
//! `sweep`: both warp the same points through the same importance (see
//! `slc_cpu_ref::sampled_lights`). VSGLs run on the command's backend, sampled VPLs on the CPU.
use crate::backend::message;
use slc_core::frame::{LightSampling, Shaded};
use slc_core::shader::{SampledLights, SampledShader, ShadeInput, Shader};
use slc_core::Renderer;
use slc_cpu_ref::CpuRenderer;

/// The passes of the paper's Table 1 as the sampled-light shaders name them, with the paper's
/// row names.
pub const PASSES: [(&str, &str); 4] = [
    ("vsgl_mip", "additional RSM (mipmap)"),
    ("importance_map", "importance map"),
    ("light_sampling", "VPL/VSGL sampling"),
    ("light_shading", "radiance evaluation"),
];

/// Shades `sampling.count` `lights` from the points of the inputs' seed: VSGLs on `r` from
/// `on_r`, sampled VPLs (a CPU estimator) on the CPU from `cpu`, the same frame. Returns the
/// name of the backend that shaded.
pub fn shade_sampled<R: Renderer>(
    lights: SampledLights,
    r: &R,
    on_r: ShadeInput<'_, R>,
    cpu: ShadeInput<'_, CpuRenderer>,
    sampling: LightSampling,
) -> Result<(Shaded, &'static str), String> {
    let shader = SampledShader { lights, sampling };
    let shaded = match lights {
        SampledLights::Vsgl => shader.shade(r, on_r, &|_| {}).map(|s| (s, r.name())),
        SampledLights::Vpl => shader
            .shade(&CpuRenderer::default(), cpu, &|_| {})
            .map(|s| (s, CpuRenderer::default().name())),
    };
    shaded.map_err(message)
}
