//! The one place the command opens a backend: each command is written once over the
//! renderer API (`slc_core::Renderer`, with `slc_app::cpu_frames::CpuFrames` for what only the CPU
//! computes) and run here on the backend `--backend` names (`slc_app::backends`). Without
//! the `gpu` feature the GPU backend is an error naming the feature.
use crate::args::BackendChoice;
use slc_app::backends::{self, Backend};
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
    let gpu = backends::open_gpu()?
        .with_one_pass(on.one_pass)
        .with_hardware_conservative(on.hardware_conservative);
    command.run(&gpu)
}

#[cfg(not(feature = "gpu"))]
fn run_on_gpu(_on: BackendChoice, _command: impl OnBackend) -> Result<(), String> {
    Err(backends::gpu_not_built("--backend cpu"))
}

/// A library error as the command reports it: what a backend lacks points to the one that
/// has it (`--backend NAME`).
pub fn message(e: RenderError) -> String {
    backends::message(&e, |b| format!("--backend {}", b.name()))
}
