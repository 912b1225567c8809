//! One check of every option before any work, for every command: the inputs give a
//! clear error at once (a count out of its range, in `--help` too), or a correct result with
//! a warning where the result would otherwise mislead.
use std::os::unix::ffi::OsStrExt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

mod common;
use common::{gpu_available, out_dir, run, slc};

#[test]
fn counts_out_of_range_are_refused_at_once_by_every_command() {
    let out = out_dir("ranges");
    for (args, says) in [
        ("render --spp 4294967295", "spp must be in 1..=65536"),
        ("render --repeat 4294967295", "repetitions must be in 1..=1000"),
        ("sweep --shader vsgl --seeds 4294967295", "seeds must be in 1..=1000"),
        // The compare cases, refused before any strategy runs.
        (
            "compare --width 32 --height 32 --rsm 16 --shader vsgl --vsgls 4294967295 --no-reference",
            "must be in 1..=16777216",
        ),
        (
            "compare --shader vsgl --camera-vsgls 4294967295 --backend gpu",
            "camera VSGLs must be in 1..=16777216",
        ),
        ("compare --shader vsgl --vsgls 0", "(got 0)"),
        ("compare --shader vsgl --camera-vsgls 0", "(got 0)"),
        (
            "compare --width 32 --height 32 --rsm 8 --shader vsgl --lobes diffuse --no-reference",
            "the lobes must be both",
        ),
        ("bench --rsms 4097", "RSM resolution must be in 1..=4096"),
        ("bench --resolutions 0x16", "the width must be in 1..=16384"),
        ("render --delta 0", "not a finite number above 0"),
        ("sweep --delta 1e-3,inf", "not a finite number above 0"),
        ("compare --heat-max 0", "heat map's maximum must be in"),
    ] {
        let start = Instant::now();
        let o = run(args, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args}");
        assert!(err.contains(says), "{args}: {err}");
        assert!(!err.contains("VPLs"), "{args}: work began: {err}");
        assert!(start.elapsed() < Duration::from_secs(20), "{args}");
    }
    assert!(!out.join("report.json").exists());
}

#[test]
fn help_gives_the_range_of_every_count() {
    for (command, options) in [
        (
            "render",
            &[
                "--width",
                "--height",
                "--rsm",
                "--spp",
                "--repeat",
                "--vsgls",
                "--camera-vsgls",
                "--interleave",
            ][..],
        ),
        ("compare", &["--vsgls", "--heat-max", "--repeat"]),
        ("sweep", &["--vsgls", "--seeds", "--repeat"]),
        ("bench", &["--rsms", "--repeat"]),
    ] {
        let o = slc().args([command, "--help"]).output().unwrap();
        let help = String::from_utf8_lossy(&o.stdout);
        for option in options {
            // The option's line and its description, up to the next option.
            let mut lines = help
                .lines()
                .skip_while(|l| !l.trim_start().starts_with(&format!("{option} <")));
            let first = lines.next().unwrap_or_else(|| panic!("{command} {option}"));
            let text: Vec<&str> = std::iter::once(first)
                .chain(lines.take_while(|l| !l.trim_start().starts_with('-')))
                .collect();
            let text = text.join("\n");
            assert!(text.contains("..="), "{command} {option}: {text}");
        }
    }
}

#[cfg(feature = "view")]
#[test]
fn a_view_wider_than_the_window_allows_with_its_panel_is_refused() {
    // The case panicked when the panel was added after the width was checked.
    let o = slc()
        .args([
            "view", "--width", "16300", "--height", "64", "--frames", "1",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the view's width (the window adds the side panel) must be in 1..=16054"),
        "{err}"
    );
}

/// A lit floor as OBJ + settings in `dir`, the settings file named `name`.
fn floor_scene(dir: &Path, name: &std::ffi::OsStr) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("floor.obj"),
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 0 -1.5\nv 1 0 -1.5\nv 1 1 -1.5\nv -1 1 -1.5\nf 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\n",
    )
    .unwrap();
    let toml = dir.join(name);
    std::fs::write(
        &toml,
        "scene = \"floor.obj\"\n[camera]\nposition = [0.0, 1.0, 2.5]\ntarget = [0.0, 0.2, 0.0]\nyfov_deg = 60.0\n[[lights]]\ntype = \"point\"\nposition = [0.0, 0.5, 0.0]\nintensity = 1\n",
    )
    .unwrap();
    toml
}

#[test]
fn a_scene_path_that_is_not_utf8_renders() {
    let dir = out_dir("non-utf8");
    let name = std::ffi::OsStr::from_bytes(b"sc\xffene.toml");
    let toml = floor_scene(&dir, name);
    let o = slc()
        .arg("render")
        .arg(&toml)
        .args(["--width", "16", "--height", "12", "--rsm", "4", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("out/report.json").is_file());
}

#[test]
fn a_settings_file_naming_a_pipe_says_so() {
    let dir = out_dir("fifo");
    let toml = floor_scene(&dir, std::ffi::OsStr::new("scene.toml"));
    std::fs::remove_file(dir.join("floor.obj")).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(dir.join("floor.obj"))
        .status()
        .is_ok_and(|s| s.success());
    if made {
        let o = run(
            &format!("render {} --width 8 --height 8", toml.display()),
            &dir.join("out"),
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("not a regular file") && !err.contains("not found"),
            "{err}"
        );
    } else {
        eprintln!("notice: mkfifo is not available; the pipe case was not checked");
    }
}

#[test]
fn a_delta_that_culls_every_pair_is_a_warning() {
    let out = out_dir("black");
    let o = run("render --width 16 --height 12 --rsm 4 --delta 1e10", &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("the indirect image is black") && err.contains("1e10"),
        "{err}"
    );
    let report = std::fs::read_to_string(out.join("report.json")).unwrap();
    assert!(report.contains("the indirect image is black"), "{report}");
    // The default δ gives no such warning, and nor does a scene whose indirect light is
    // black whatever δ is (a single plane cannot light itself).
    let o = run("render --width 16 --height 12 --rsm 4", &out);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("black"));
    let plane =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/narrow-spot/narrow-spot.gltf");
    let o = run(
        &format!("render {} --width 16 --height 16 --rsm 4", plane.display()),
        &out,
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && !err.contains("black"), "{err}");
}

#[test]
fn a_frame_beyond_the_adapters_binding_is_refused_before_work_naming_what_fits() {
    if !gpu_available() {
        return;
    }
    let out = out_dir("gpu-binding");
    // One face of RSM 1448² holds 1448² texels of 128 bytes (268 MB): beyond lavapipe's
    // 128 MiB binding; an adapter with room renders it. (A scene of one spot light: the
    // built-in scene's seven faces would be refused for memory first on a small machine.)
    let scene =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/narrow-spot/narrow-spot.gltf");
    let o = run(
        &format!(
            "render {} --backend gpu --width 16 --height 16 --rsm 1448",
            scene.display()
        ),
        &out,
    );
    let err = String::from_utf8_lossy(&o.stderr);
    if !o.status.success() {
        assert!(
            err.contains("RSM 1448²")
                && err.contains("at most --rsm")
                && err.contains("--backend cpu"),
            "{err}"
        );
        assert!(!err.contains("smaller batches"), "{err}");
        // 128 MiB holds 1024² texels, and their VPLs of both lobes in two bindings.
        if err.contains("more than the 134217728 bytes") {
            assert!(err.contains("at most --rsm 1024 here"), "{err}");
        }
    }
}

/// RSM 1024² with both lobes renders on the GPU wherever a binding holds 128 MiB (lavapipe's
/// limit, exactly its 1024² RSM texels of 128 bytes; the VPLs, two a texel, lie in two
/// buffers, and their bounds, sized by the 1,647,184 VPLs Sponza makes, take 126 MiB; the
/// tight strategies' bounds over boxes, 184 MB, lie in two buffers too): as many VPLs as the
/// CPU makes, with `binned` and with `tight`.
#[test]
fn rsm_1024_with_both_lobes_renders_on_a_128_mib_binding() {
    if !gpu_available() {
        return;
    }
    let scene = format!("{}/../../scenes/sponza.toml", env!("CARGO_MANIFEST_DIR"));
    let out = out_dir("gpu-rsm-1024");
    for culling in ["binned", "tight"] {
        let o = run(
            &format!(
                "render {scene} --backend gpu --width 32 --height 18 --rsm 1024 --culling {culling}"
            ),
            &out,
        );
        let text = String::from_utf8_lossy(&o.stdout);
        let err = String::from_utf8_lossy(&o.stderr);
        let small_binding = err
            .split("more than the ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next()?.parse::<u64>().ok())
            .is_some_and(|limit| limit < 1 << 27);
        assert!(o.status.success() || small_binding, "{culling}: {err}");
        if o.status.success() {
            assert!(text.contains("1647184 VPLs"), "{culling}: {text}");
        }
    }
}
