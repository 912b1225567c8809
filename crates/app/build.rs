//! Records what slc is built from and with, for the provenance of `report.json`: the git
//! commit (where it is built from a git checkout; `SLC_GIT_COMMIT`, with `-dirty` when tracked
//! files differ), the compiler's version (`SLC_RUSTC_VERSION`) and the build profile with its
//! optimisation level (`SLC_BUILD_PROFILE`).
use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn main() {
    if let Some(dir) = git(&["rev-parse", "--git-dir"]) {
        let dir = std::path::Path::new(&dir);
        for f in ["HEAD", "index"] {
            println!("cargo:rerun-if-changed={}", dir.join(f).display());
        }
    }
    let commit = git(&["rev-parse", "HEAD"]).map(|c| {
        let dirty =
            git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
        if dirty {
            format!("{c}-dirty")
        } else {
            c
        }
    });
    println!(
        "cargo:rustc-env=SLC_GIT_COMMIT={}",
        commit.unwrap_or_default()
    );
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string());
    println!(
        "cargo:rustc-env=SLC_RUSTC_VERSION={}",
        version.unwrap_or_else(|| "rustc (version unknown)".into())
    );
    let var = |name: &str| std::env::var(name).unwrap_or_else(|_| "unknown".into());
    println!(
        "cargo:rustc-env=SLC_BUILD_PROFILE={} (opt-level {})",
        var("PROFILE"),
        var("OPT_LEVEL")
    );
}
