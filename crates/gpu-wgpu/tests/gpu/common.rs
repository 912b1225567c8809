//! The device shared by the tests and the no-adapter policy, and the small stochastic frame
//! the renderer tests compare strategies on.
use slc_core::frame::{LobeSelection, Method, RenderSettings, Stochastic};
use slc_core::Strategy;
use slc_gpu_wgpu::{GpuContext, GpuError};

/// A device for one test. No adapter: with `CI` set the test fails (CI installs lavapipe, so
/// a missing adapter is a broken setup); otherwise a notice is printed and `None` returned,
/// and the test passes without checking anything. Any other device error fails the test.
/// (lavapipe warns when `XDG_RUNTIME_DIR` is unset; harmless, `.ci/run` sets it.)
pub fn gpu() -> Option<GpuContext> {
    match GpuContext::new() {
        Ok(ctx) => Some(ctx),
        Err(e @ GpuError::NoAdapter(_)) => {
            if std::env::var_os("CI").is_some() {
                panic!("CI is set but no GPU adapter was found: {e}");
            }
            eprintln!("notice: GPU test skipped, no adapter ({e})");
            None
        }
        Err(e) => panic!("GPU device could not be created: {e}"),
    }
}

/// A 64x48 frame of `strategy` (RSM 16², δ 1e-3, K 4, with metrics), denoised or not.
pub fn small_frame(strategy: Strategy, denoise: bool) -> RenderSettings {
    RenderSettings {
        width: 64,
        height: 48,
        rsm_resolution: 16,
        seed: 2,
        method: Method::Stochastic(Stochastic {
            delta: 1e-3,
            strategy,
            interleave: 4,
            denoise,
            metrics: true,
        }),
        visibility: false,
        spp: 1,
        lobes: LobeSelection::Both,
    }
}
