//! The `slc` command as a user runs it: outputs, report fields and errors.
use std::path::PathBuf;
use std::process::Command;

fn slc() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slc"))
}

fn out_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slc-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn render_writes_images_and_report() {
    let out = out_dir("render");
    let status = slc()
        .args([
            "render", "--width", "24", "--height", "16", "--rsm", "4", "--seed", "3", "--out",
        ])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    for f in [
        "direct.exr",
        "indirect.exr",
        "total.exr",
        "total.png",
        "report.json",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let report = std::fs::read_to_string(out.join("report.json")).unwrap();
    for key in [
        "\"scene\": \"cornell-glossy\"",
        "\"backend\": \"cpu\"",
        "\"width\": 24",
        "\"height\": 16",
        "\"seed\": 3",
        "\"delta\": 0.001",
        "\"culling\": \"none\"",
        "\"shader\": \"vpl\"",
        "\"total\":",
        "\"false_discovery_rate\": null",
    ] {
        assert!(report.contains(key), "report.json lacks {key}:\n{report}");
    }
    let png = image::open(out.join("total.png")).unwrap();
    assert_eq!((png.width(), png.height()), (24, 16));
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn references_are_named_in_the_report() {
    let out = out_dir("reference");
    let ok = slc()
        .args([
            "render",
            "--width",
            "8",
            "--height",
            "8",
            "--reference",
            "path",
            "--spp",
            "2",
            "--out",
        ])
        .arg(&out)
        .status()
        .unwrap();
    assert!(ok.success());
    let report = std::fs::read_to_string(out.join("report.json")).unwrap();
    assert!(
        report.contains("\"reference\": \"path\"") && report.contains("\"delta\": null"),
        "{report}"
    );
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn bad_input_is_a_clear_error() {
    let o = slc()
        .args(["render", "no-such-scene.gltf", "--out"])
        .arg(out_dir("missing"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("no-such-scene.gltf"), "{err}");
    let o = slc()
        .args(["render", "--width", "0", "--out"])
        .arg(out_dir("zero"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("width"));
}
