//! VSGLs and VPLs sampled at equal count from a prepared frame's RSMs, for `compare` and
//! `sweep`: both warp the same points through the same importance (see
//! `slc_cpu_ref::sampled_lights`). VSGLs run on the command's backend, sampled VPLs on the CPU.
use crate::backend::message;
use slc_core::frame::{LightSampling, Method, Shaded};
use slc_core::shader::{SampledVplShader, ShadeInput, Shader, VsglShader};
use slc_core::Renderer;
use slc_cpu_ref::CpuRenderer;

/// One of the two estimators from `N` sampled lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimator {
    /// `N` VSGLs at the filtered mip level (VSGL section 4.2), shaded analytically.
    Vsgl,
    /// The `N` sampled texels' VPLs, shaded exactly: unbiased against every VPL.
    Vpl,
}

/// Both estimators, VPLs first.
pub const ESTIMATORS: [Estimator; 2] = [Estimator::Vpl, Estimator::Vsgl];

/// The passes of the paper's Table 1 as the sampled-light shaders name them, with the paper's
/// row names.
pub const PASSES: [(&str, &str); 4] = [
    ("vsgl_mip", "additional RSM (mipmap)"),
    ("importance_map", "importance map"),
    ("light_sampling", "VPL/VSGL sampling"),
    ("light_shading", "radiance evaluation"),
];

impl Estimator {
    /// The folder and CSV name: `vsgl` or `vpl_sampled`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Vsgl => "vsgl",
            Self::Vpl => "vpl_sampled",
        }
    }

    /// The render method, for reports.
    pub fn method(self, sampling: LightSampling) -> Method {
        match self {
            Self::Vsgl => Method::Vsgl(sampling),
            Self::Vpl => Method::SampledVpls(sampling),
        }
    }

    /// Shades with `sampling.count` lights from the points of the inputs' seed: VSGLs on `r`
    /// from `on_r`, sampled VPLs on the CPU from `cpu` (the same frame). Returns the name of
    /// the backend that shaded.
    pub fn shade<R: Renderer>(
        self,
        r: &R,
        on_r: ShadeInput<'_, R>,
        cpu: ShadeInput<'_, CpuRenderer>,
        sampling: LightSampling,
    ) -> Result<(Shaded, &'static str), String> {
        let shaded = match self {
            Self::Vsgl => VsglShader(sampling)
                .shade(r, on_r, &|_| {})
                .map(|s| (s, r.name())),
            Self::Vpl => SampledVplShader(sampling)
                .shade(&CpuRenderer, cpu, &|_| {})
                .map(|s| (s, "cpu")),
        };
        shaded.map_err(message)
    }
}
