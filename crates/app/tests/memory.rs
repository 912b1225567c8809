//! The memory estimate holds: for a few runs (the built-in scene at several sizes, RSMs,
//! lobes and shaders, and a generated mesh of 320,000 triangles whose BVH dominates) the peak
//! RSS `report.json` gives is at most the estimate the memory check used, and the estimate
//! is not far above it (within 4x, so a check that refuses everything fails here too). The
//! whole grid, with Sponza and larger sizes: `tools/memory/grid.py`, `docs/memory.md`.
use std::path::Path;

mod common;
use common::{out_dir, run_ok};

/// `(estimate, peak RSS)` of `slc render ARGS`.
fn memory(args: &str, out: &Path) -> (f64, f64) {
    run_ok(&format!("render {args}"), out);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let m = &report["memory"];
    (
        m["estimate_bytes"].as_f64().unwrap(),
        m["peak_rss_bytes"].as_f64().unwrap(),
    )
}

/// An OBJ grid of `n` x `n` quads with a settings file that lights it.
fn big_mesh(dir: &Path, n: usize) -> std::path::PathBuf {
    use std::fmt::Write;
    std::fs::create_dir_all(dir).unwrap();
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let _ = writeln!(obj, "v {} 0 {}", i as f32 / n as f32, j as f32 / n as f32);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = |di: usize, dj: usize| (j + dj) * (n + 1) + i + di + 1;
            let _ = writeln!(obj, "f {} {} {} {}", v(0, 0), v(0, 1), v(1, 1), v(1, 0));
        }
    }
    std::fs::write(dir.join("grid.obj"), obj).unwrap();
    let toml = dir.join("grid.toml");
    std::fs::write(
        &toml,
        "scene = \"grid.obj\"\n[camera]\nposition = [0.5, 1.0, 1.5]\ntarget = [0.5, 0.0, 0.5]\nyfov_deg = 50.0\n[[lights]]\ntype = \"point\"\nposition = [0.5, 0.5, 0.5]\nintensity = 1.0\n",
    )
    .unwrap();
    toml
}

#[test]
fn the_estimate_is_at_least_the_peak_and_not_far_above_it() {
    let out = out_dir("memory");
    let mesh = big_mesh(&out.join("scene"), 400);
    let cases = [
        "--width 64 --height 64 --rsm 16".to_string(),
        "--width 384 --height 256 --rsm 64".into(),
        "--width 256 --height 256 --rsm 96 --lobes glossy --culling clustered".into(),
        "--width 256 --height 256 --rsm 64 --metrics".into(),
        "--width 128 --height 128 --rsm 64 --shader vsgl --vsgls 2048".into(),
        format!("{} --width 32 --height 32 --rsm 8", mesh.display()),
    ];
    let mut table = String::new();
    let mut wrong = Vec::new();
    for (i, args) in cases.iter().enumerate() {
        let (estimate, peak) = memory(args, &out.join(i.to_string()));
        table += &format!(
            "{args}: estimate {:.0} MiB, peak {:.0} MiB\n",
            estimate / 1048576.0,
            peak / 1048576.0
        );
        if !(peak <= estimate && estimate <= 4.0 * peak) {
            wrong.push(args.clone());
        }
    }
    eprintln!("{table}");
    assert!(wrong.is_empty(), "{wrong:?}\n{table}");
}
