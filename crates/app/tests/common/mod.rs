//! Helpers shared by the integration tests of the `slc` command.

/// Whether a GPU adapter is there for the `--backend gpu` tests. None: with `CI` set the test
/// fails (CI installs lavapipe, so a missing adapter is a broken setup); otherwise a notice is
/// printed and the test passes without checking (as `crates/gpu-wgpu/tests/gpu/common.rs`).
pub fn gpu_available() -> bool {
    use slc_gpu_wgpu::{GpuContext, GpuError};
    match GpuContext::new() {
        Ok(_) => true,
        Err(e @ GpuError::NoAdapter(_)) => {
            if std::env::var_os("CI").is_some() {
                panic!("CI is set but no GPU adapter was found: {e}");
            }
            eprintln!("notice: GPU test skipped, no adapter ({e})");
            false
        }
        Err(e) => panic!("GPU device could not be created: {e}"),
    }
}
