//! The backends the front ends (the `slc` command and the Python package) render on: their
//! names, what each has ([`Capabilities`]), opening the GPU, and a refusal's message pointing
//! to the backend that has what is missing. The libraries know no backend but their own:
//! [`RenderError::Unsupported`] says what the settings need, and [`message`] finds who has it.
use slc_core::{Capabilities, RenderError};
use slc_cpu_ref::CpuRenderer;

/// Where a frame is rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Backend {
    /// The CPU reference renderer (rayon).
    Cpu,
    /// The whole frame on the GPU (wgpu): rasterized G-buffer and RSMs, VPLs, direct light
    /// with shadow maps, culling, shading and the filter.
    Gpu,
}

impl Backend {
    /// Every backend, in the order a refusal's hint tries them.
    pub const ALL: [Backend; 2] = [Backend::Cpu, Backend::Gpu];

    /// The name its renderer reports ([`slc_core::Renderer::name`]), `--backend` and
    /// Python's `backend=` take.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Cpu => CpuRenderer::NAME,
            Backend::Gpu => GPU_NAME,
        }
    }

    /// The backend called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|b| b.name() == name)
    }

    /// What the backend has on a device with every feature it uses; `None` for the GPU in
    /// a build without the `gpu` feature.
    pub fn capabilities(self) -> Option<Capabilities> {
        match self {
            Backend::Cpu => Some(CpuRenderer::CAPABILITIES),
            #[cfg(feature = "gpu")]
            Backend::Gpu => Some(slc_gpu_wgpu::GpuRenderer::CAPABILITIES),
            #[cfg(not(feature = "gpu"))]
            Backend::Gpu => None,
        }
    }

    /// Where a refusal by the backend called `refused` can be rendered instead: the first
    /// other backend whose capabilities cover `needs`.
    pub fn instead(refused: &str, needs: &Capabilities) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|b| b.name() != refused && b.capabilities().is_some_and(|c| c.covers(needs)))
    }
}

#[cfg(feature = "gpu")]
const GPU_NAME: &str = slc_gpu_wgpu::GpuRenderer::NAME;
#[cfg(not(feature = "gpu"))]
const GPU_NAME: &str = "gpu";

/// `e` as a front end reports it: a refusal ([`RenderError::Unsupported`]) names the backend
/// that has what is missing, chosen as `choose` spells it (`--backend cpu`,
/// `backend='cpu'`), or says that no backend has it.
pub fn message(e: &RenderError, choose: impl Fn(Backend) -> String) -> String {
    match e {
        RenderError::Unsupported { backend, needs, .. } => match Backend::instead(backend, needs) {
            Some(b) => format!("{e}; render on the {} backend ({})", b.name(), choose(b)),
            None => format!("{e}; no backend has it"),
        },
        _ => e.to_string(),
    }
}

/// The GPU renderer on the default adapter, with a warning on stderr when that adapter is a
/// software rasterizer.
#[cfg(feature = "gpu")]
pub fn open_gpu() -> Result<slc_gpu_wgpu::GpuRenderer, String> {
    let gpu = slc_gpu_wgpu::GpuRenderer::new().map_err(|e| e.to_string())?;
    warn_if_software(gpu.context());
    Ok(gpu)
}

/// Warns on stderr when `ctx` runs on a software rasterizer.
#[cfg(feature = "gpu")]
pub fn warn_if_software(ctx: &slc_gpu_wgpu::GpuContext) {
    if let Some(warning) = ctx.software_warning() {
        eprintln!("warning: {warning}");
    }
}

/// The error of the GPU backend in a build without it; `choose` spells how to choose the
/// CPU backend instead.
pub fn gpu_not_built(choose: &str) -> String {
    format!(
        "this slc was built without the `gpu` feature; rebuild with it (the default) or use \
         {choose}"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::ValueEnum;
    use slc_core::Strategy;

    #[test]
    fn names_are_the_renderers_and_the_flags() {
        for b in Backend::ALL {
            let flag = b.to_possible_value().expect("a visible value");
            assert_eq!(flag.get_name(), b.name());
            assert_eq!(Backend::from_name(b.name()), Some(b));
        }
        assert_eq!(Backend::from_name("tpu"), None);
    }

    /// The CPU's refusals point to the GPU and back, or to none where no backend has the
    /// combination (a raster baseline, GPU only, with visibility, CPU only).
    #[test]
    fn refusals_point_to_the_backend_that_has_it() {
        let flag = |b: Backend| format!("--backend {}", b.name());
        let refused = |by: Backend, needs: Capabilities| {
            let what = "it".into();
            let e = RenderError::Unsupported {
                backend: by.name(),
                what,
                needs,
            };
            message(&e, flag)
        };
        let raster = Capabilities::culling(Strategy::Splatting);
        let visible = Capabilities {
            vpl_visibility: true,
            ..Capabilities::NONE
        };
        let both = Capabilities {
            vpl_visibility: true,
            ..raster
        };
        let e = refused(Backend::Cpu, raster);
        #[cfg(feature = "gpu")]
        assert!(
            e.ends_with("render on the gpu backend (--backend gpu)"),
            "{e}"
        );
        #[cfg(not(feature = "gpu"))]
        assert!(e.ends_with("no backend has it"), "{e}");
        let e = refused(Backend::Gpu, visible);
        assert!(
            e.ends_with("render on the cpu backend (--backend cpu)"),
            "{e}"
        );
        for by in Backend::ALL {
            let e = refused(by, both);
            assert!(e.ends_with("no backend has it"), "{e}");
        }
        let plain = RenderError::Cancelled;
        assert_eq!(message(&plain, flag), "cancelled");
    }
}
