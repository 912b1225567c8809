//! `tools/gpu-check --quick` on this machine's adapter (lavapipe in CI): every step runs,
//! and the report holds what the GPU check promises (adapter, tests with passed and failed,
//! Table 2 rows with method, lobes, culling + shading and how they were timed, for both lobe
//! sets and every method, the VSGL timings and the scaling sweep).
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// The GPU test binary cargo built beside this one (`target/<profile>/deps/gpu-*`), the
/// newest where several are left from earlier builds.
fn gpu_test_binary() -> Option<PathBuf> {
    let deps = Path::new(env!("CARGO_BIN_EXE_slc")).parent()?.join("deps");
    std::fs::read_dir(deps)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.starts_with("gpu-") && p.extension().is_none()
        })
        .max_by_key(|p| p.metadata().and_then(|m| m.modified()).ok())
}

#[test]
fn gpu_check_quick_writes_its_report() {
    if !common::gpu_available() {
        return;
    }
    let Some(tests) = gpu_test_binary() else {
        panic!("no GPU test binary beside {}", env!("CARGO_BIN_EXE_slc"));
    };
    let out = common::out_dir("gpu-check");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let status = Command::new("python3")
        .arg(root.join("tools/gpu-check"))
        .args(["--quick", "--out"])
        .arg(&out)
        .arg("--slc")
        .arg(env!("CARGO_BIN_EXE_slc"))
        .arg("--tests")
        .arg(&tests)
        .status()
        .expect("python3 runs tools/gpu-check");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("gpu-check.json")).unwrap())
            .unwrap();
    let md = std::fs::read_to_string(out.join("gpu-check.md")).unwrap();
    assert!(status.success(), "gpu-check failed:\n{md}");
    assert_eq!(report["ok"], true);
    assert!(report["adapter"].as_str().is_some_and(|a| !a.is_empty()));
    let t = &report["tests"];
    assert!(t["passed"].as_array().unwrap().len() >= 5, "{t}");
    assert!(t["failed"].as_array().unwrap().is_empty(), "{t}");
    let rows = report["table2"].as_array().unwrap();
    for lobes in ["glossy", "diffuse"] {
        let methods: Vec<&str> = rows
            .iter()
            .filter(|r| r["lobes"] == lobes)
            .map(|r| r["method_id"].as_str().unwrap())
            .collect();
        for m in [
            "ellipsoid",
            "splatting",
            "clustered-raster",
            "clustered",
            "tight",
            "binned",
            "ellipsoid, lists",
            "clustered-raster, software",
        ] {
            assert!(
                methods.contains(&m),
                "{lobes}: {m} missing from {methods:?}"
            );
        }
    }
    for r in rows {
        let ms = r["culling_shading_ms"].as_f64().unwrap();
        assert!(ms > 0.0 && ms.is_finite(), "{r}");
        // lavapipe's timestamps are not trusted; a GPU's are.
        assert!(["timestamps", "wall clock"].contains(&r["timed_by"].as_str().unwrap()));
        assert!(r["method"].as_str().is_some() && r["vpls"].as_u64().unwrap() > 0);
    }
    assert!(report["vsgl"].as_array().unwrap().len() == 2);
    let scaling = report["scaling"].as_array().unwrap();
    assert_eq!(scaling.len(), 6, "3 RSM sizes x 2 strategies");
    assert!(md.contains("## Table 2") && md.contains("## Tests"));
}
