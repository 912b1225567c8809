//! The one place the command opens a backend: each command is written once over the
//! renderer API (`slc_core::Renderer`, with `slc_app::cpu_frames::CpuFrames` for what only the CPU
//! computes) and run here on the backend `--backend` names. Without the `gpu` feature the
//! GPU backend is an error naming the feature.
use crate::args::{Backend, BackendChoice};
use slc_app::cpu_frames::CpuFrames;
use slc_core::RenderError;
use slc_cpu_ref::CpuRenderer;

/// A command written once for every backend.
pub trait OnBackend {
    fn run<R: CpuFrames>(self, r: &R) -> Result<(), String>;
}

/// Runs `command` on the backend `on` names.
pub fn run_on(on: BackendChoice, command: impl OnBackend) -> Result<(), String> {
    match on.backend {
        Backend::Cpu => command.run(&CpuRenderer::default()),
        Backend::Gpu => run_on_gpu(on, command),
    }
}

#[cfg(feature = "gpu")]
fn run_on_gpu(on: BackendChoice, command: impl OnBackend) -> Result<(), String> {
    let gpu = slc_gpu_wgpu::GpuRenderer::new()
        .map_err(|e| e.to_string())?
        .with_one_pass(on.one_pass)
        .with_hardware_conservative(on.hardware_conservative);
    warn_if_software(gpu.context());
    command.run(&gpu)
}

/// Warns on stderr when `ctx` runs on a software rasterizer.
#[cfg(feature = "gpu")]
pub fn warn_if_software(ctx: &slc_gpu_wgpu::GpuContext) {
    if let Some(warning) = ctx.software_warning() {
        eprintln!("warning: {warning}");
    }
}

#[cfg(not(feature = "gpu"))]
fn run_on_gpu(_on: BackendChoice, _command: impl OnBackend) -> Result<(), String> {
    Err(
        "this slc was built without the `gpu` feature; rebuild with it (the default) or use \
         --backend cpu"
            .into(),
    )
}

/// A library error as the command reports it: what a backend lacks points to the one that
/// has it.
pub fn message(e: RenderError) -> String {
    match e {
        RenderError::Unsupported {
            instead: Some(backend),
            ..
        } => format!("{e} (--backend {backend})"),
        _ => e.to_string(),
    }
}
