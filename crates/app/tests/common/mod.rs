//! Helpers shared by the integration tests of the `slc` command. Each test file compiles
//! this module on its own and uses part of it, hence `allow(dead_code)` below.
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `slc` binary under test.
#[allow(dead_code)]
pub fn slc() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slc"))
}

/// `slc ARGS --out OUT` (ARGS split at spaces).
#[allow(dead_code)]
pub fn command(args: &str, out: &Path) -> Command {
    let mut c = slc();
    c.args(args.split(' ')).arg("--out").arg(out);
    c
}

/// Runs `slc ARGS --out OUT` (ARGS split at spaces) to its end.
#[allow(dead_code)]
pub fn run(args: &str, out: &Path) -> Output {
    command(args, out).output().unwrap()
}

/// Runs `slc ARGS --out OUT` (ARGS split at spaces) and asserts it succeeded.
#[allow(dead_code)]
pub fn run_ok(args: &str, out: &Path) {
    let o = run(args, out);
    assert!(
        o.status.success(),
        "slc {args} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A fresh output folder for this test process (removed if a previous run left it; not
/// created), removed again when dropped, unless the test is failing: then it stays for a look.
#[allow(dead_code)]
pub fn out_dir(name: &str) -> OutFolder {
    let d = std::env::temp_dir().join(format!("slc-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    OutFolder(d)
}

/// [`out_dir`]'s folder: a path that removes its folder when dropped, unless the thread is
/// panicking (a failing test).
pub struct OutFolder(PathBuf);

impl std::ops::Deref for OutFolder {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for OutFolder {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<std::ffi::OsStr> for OutFolder {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.as_os_str()
    }
}

impl Drop for OutFolder {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("the failing test's output stays at {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// Whether a GPU adapter is there for the `--backend gpu` tests. None: with `CI` set the test
/// fails (CI installs lavapipe, so a missing adapter is a broken setup); otherwise a notice is
/// printed and the test passes without checking (as `crates/gpu-wgpu/tests/gpu/common.rs`).
#[allow(dead_code)]
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

/// The RGB pixels of the first layer of an EXR file.
#[allow(dead_code)]
pub fn read_exr(path: &Path) -> Vec<[f32; 3]> {
    use exr::prelude::*;
    let img = read_first_rgba_layer_from_file(
        path,
        |res, _| (res.width(), vec![[0.0; 3]; res.width() * res.height()]),
        |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| px[pos.y() * *w + pos.x()] = [r, g, b],
    )
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    img.layer_data.channel_data.pixels.1
}
