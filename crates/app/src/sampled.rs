//! VSGLs and VPLs sampled at equal count from a prepared frame's RSMs, for `compare` and
//! `sweep`: both warp the same points through the same importance (see
//! `slc_cpu_ref::sampled_lights`).
use slc_cpu_ref::sampled_lights::{shade_sampled_vpls, shade_vsgl};
use slc_cpu_ref::{LightSampling, Method, Prepared, SampledFrame, Timings};

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

/// The passes of the paper's Table 1 as `slc_cpu_ref::SampledFrame::timings` names them, with
/// the paper's row names.
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

    /// Shades `p` with `sampling.count` lights from the points of `seed`.
    pub fn shade(
        self,
        p: &Prepared,
        sampling: &LightSampling,
        seed: u32,
        visibility: bool,
    ) -> Result<SampledFrame, String> {
        let shade = match self {
            Self::Vsgl => shade_vsgl,
            Self::Vpl => shade_sampled_vpls,
        };
        shade(p, sampling, seed, visibility, &|_| {}).map_err(|e| e.to_string())
    }
}

/// Milliseconds of the pass `name` (0 if it did not run).
pub fn pass_ms(t: &Timings, name: &str) -> f64 {
    t.0.iter()
        .find(|(n, _)| *n == name)
        .map_or(0.0, |(_, v)| *v)
}
