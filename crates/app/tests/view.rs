//! `slc view` as a script runs it: `--frames N --screenshot` under Xvfb on the GPU adapter
//! (lavapipe in CI). Skipped with a notice where xvfb-run or an adapter is missing, except
//! with `CI` set, where CI's setup installs both and their absence fails.
#![cfg(feature = "view")]
use image::RgbImage;
use std::path::Path;
use std::process::{Command, Output};
use std::sync::Mutex;

mod common;
use common::{gpu_available, out_dir, OutFolder};

/// One X server at a time: parallel `xvfb-run -a` can race for the same display number.
static XVFB: Mutex<()> = Mutex::new(());

/// A fresh, empty folder for this test's files, removed when the test passes.
fn temp(name: &str) -> OutFolder {
    let dir = out_dir(&format!("view-{name}"));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Whether windows can be opened: xvfb-run and a GPU adapter are there.
fn can_view() -> bool {
    let xvfb = Command::new("xvfb-run").arg("--help").output().is_ok();
    if !xvfb {
        if std::env::var_os("CI").is_some() {
            panic!("CI is set but xvfb-run is missing (.ci/run installs xvfb)");
        }
        eprintln!("notice: view test skipped, xvfb-run is not installed (apt-get install xvfb)");
        return false;
    }
    gpu_available()
}

/// `program` run on a virtual X server with a 24-bit screen (xvfb-run's default has 8).
fn under_xvfb(program: &str) -> Command {
    let mut c = Command::new("xvfb-run");
    c.args(["-a", "-s", "-screen 0 1280x1024x24", program]);
    c
}

/// `slc view ARGS` under a virtual X server; panics (with its output) unless it succeeds.
fn view(args: &[&str]) -> Output {
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let out = under_xvfb(env!("CARGO_BIN_EXE_slc"))
        .arg("view")
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "slc view {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// A screenshot of `args` at 320 x 240, checked for its size and for more than a blank.
fn screenshot(dir: &Path, name: &str, args: &[&str]) -> RgbImage {
    let png = dir.join(format!("{name}.png"));
    let size = ["--width", "320", "--height", "240", "--frames", "3"];
    let shot = ["--screenshot", png.to_str().unwrap()];
    let all: Vec<&str> = size.iter().chain(&shot).chain(args).copied().collect();
    let out = view(&all);
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (320, 240), "{name}");
    let mut colours: Vec<_> = img.pixels().map(|p| p.0).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 50, "{name}: only {} colours", colours.len());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("gbuffer") && stdout.contains("frame"),
        "{stdout}"
    );
    img
}

/// The share of pixels that differ by more than a few levels.
fn changed(a: &RgbImage, b: &RgbImage) -> f64 {
    let n = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 8))
        .count();
    n as f64 / (a.width() * a.height()) as f64
}

#[test]
fn frames_save_a_screenshot_the_overlays_and_the_camera_change() {
    if !can_view() {
        return;
    }
    let dir = temp("shots");
    let plain = screenshot(&dir, "plain", &[]);
    let heat = screenshot(&dir, "heat", &["--overlay", "heatmap"]);
    assert!(changed(&plain, &heat) > 0.3, "{}", changed(&plain, &heat));
    // K = 2: a grid line every 32 pixels (K changes the estimate, so both frames have K = 2).
    let k2 = screenshot(&dir, "k2", &["--interleave", "2", "--rsm", "16"]);
    let grid_args = ["--interleave", "2", "--rsm", "16", "--overlay", "grid"];
    let grid = screenshot(&dir, "grid", &grid_args);
    assert!(changed(&k2, &grid) > 0.03, "{}", changed(&k2, &grid));
    let moved = screenshot(&dir, "moved", &["--camera-script", "look:120:0,w*2"]);
    assert!(changed(&plain, &moved) > 0.3, "{}", changed(&plain, &moved));
    let back = screenshot(&dir, "back", &["--camera-script", "look:120:0,w,reset"]);
    assert!(changed(&plain, &back) < 0.01, "{}", changed(&plain, &back));
}

/// `--backend cpu`: the CPU reference renderer draws the frames (its passes in the table,
/// the CPU named as the renderer), a raster baseline it lacks is a clear error, and the
/// picture is the GPU's scene: the two backends differ only where rasterization and ray
/// tracing do (shadow-map texels, the filter's edges).
#[test]
fn the_cpu_backend_renders_the_view() {
    if !can_view() {
        return;
    }
    let dir = temp("cpu");
    let gpu = screenshot(&dir, "gpu", &[]);
    let cpu = screenshot(&dir, "cpu", &["--backend", "cpu"]);
    let differ = changed(&gpu, &cpu);
    assert!(differ < 0.25, "{differ}");
    let out = view(&[
        "--backend",
        "cpu",
        "--frames",
        "2",
        "--width",
        "64",
        "--height",
        "48",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("on CPU (") && stdout.contains("denoise"),
        "{stdout}"
    );
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let refused = under_xvfb(env!("CARGO_BIN_EXE_slc"))
        .args([
            "view",
            "--backend",
            "cpu",
            "--frames",
            "1",
            "--culling",
            "splatting",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(stderr.contains("--backend gpu"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// `scenes/cornell-gltf.toml`, whose scene file is in `../shared`; `None` (with a notice)
/// where `../shared` is not beside the repository, which fails under `CI`.
fn cornell_gltf() -> Option<&'static str> {
    let shared = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/scenes");
    if !Path::new(shared).is_dir() {
        assert!(std::env::var_os("CI").is_none(), "CI without ../shared");
        eprintln!("notice: test skipped, ../shared is not beside the repository");
        return None;
    }
    Some(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/cornell-gltf.toml"
    ))
}

#[test]
fn saved_settings_render_with_slc_render() {
    if !can_view() {
        return;
    }
    let dir = temp("settings");
    let Some(scene) = cornell_gltf() else { return };
    let saved = dir.join("saved.toml");
    let args = [
        scene,
        "--width",
        "96",
        "--height",
        "64",
        "--frames",
        "2",
        "--camera-script",
        "d*2",
        "--save-settings",
        saved.to_str().unwrap(),
    ];
    view(&args);
    let text = std::fs::read_to_string(&saved).unwrap();
    assert!(
        text.contains("[camera]") && text.contains("slc render"),
        "{text}"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_slc"))
        .args([
            "render",
            saved.to_str().unwrap(),
            "--width",
            "48",
            "--height",
            "32",
        ])
        .args(["--rsm", "8", "--out", dir.join("render").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("render/total.png").is_file());
}

#[test]
fn settings_of_a_built_in_scene_are_a_clear_error() {
    if !can_view() {
        return;
    }
    let dir = temp("builtin");
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let saved = dir.join("saved.toml");
    let out = under_xvfb(env!("CARGO_BIN_EXE_slc"))
        .args(["view", "--width", "64", "--height", "48", "--frames", "1"])
        .args(["--save-settings", saved.to_str().unwrap()])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("built-in scene"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn without_a_display_the_error_says_so() {
    let out = Command::new(env!("CARGO_BIN_EXE_slc"))
        .args(["view", "--frames", "1", "--width", "64", "--height", "48"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("no display"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn without_a_gpu_backend_the_error_says_so() {
    if !can_view() {
        return;
    }
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    // No DirectX 12 on Linux: no backend, no adapter.
    let out = under_xvfb(env!("CARGO_BIN_EXE_slc"))
        .args(["view", "--frames", "1"])
        .env("WGPU_BACKEND", "dx12")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("no GPU adapter"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn bad_view_options_are_clear_errors() {
    for (args, says) in [
        (vec!["--camera-script", "w*x"], "--camera-script"),
        (
            vec!["--frames", "1", "--camera-script", "w*3"],
            "more than --frames",
        ),
        (vec!["--culling", "nope"], "unknown culling strategy"),
        (vec!["--rsm", "0"], "RSM resolution"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_slc"))
            .arg("view")
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// Real key presses and mouse moves in the window (sent with xdotool): P saves a screenshot,
/// held W flies forward, the mouse moved right with the right button held over the picture
/// turns right, K saves the settings with the moved camera.
#[test]
fn keys_in_the_window_fly_and_save() {
    if !can_view() {
        return;
    }
    if Command::new("xdotool").arg("version").output().is_err() {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI without xdotool (.ci/run installs it)"
        );
        eprintln!("notice: key test skipped, xdotool is not installed");
        return;
    }
    let Some(scene) = cornell_gltf() else { return };
    let dir = temp("keys");
    let script = r#"
        "$SLC" view "$SCENE" --width 96 --height 64 --out "$DIR" &
        pid=$!
        trap 'kill $pid 2>/dev/null' EXIT
        wid=$(timeout 120 xdotool search --sync --name "slc view" | head -1)
        [ -n "$wid" ] || exit 10
        wait_for() {
            for _ in $(seq 600); do
                [ -e "$1" ] && return 0
                kill -0 $pid 2>/dev/null || return 1
                sleep 0.1
            done
            return 1
        }
        xdotool windowfocus --sync "$wid"
        xdotool key p
        wait_for "$DIR/slc-view-001.png" || exit 11
        xdotool keydown w
        sleep 2
        xdotool keyup w
        sleep 1
        # The 96 x 64 picture is centred in the 760-pixel-high window, left of the panel.
        xdotool mousemove --window "$wid" 48 380
        sleep 0.5
        xdotool mousedown 3
        sleep 0.5
        xdotool mousemove_relative -- 60 0
        sleep 1
        xdotool mouseup 3
        sleep 1
        xdotool key k
        wait_for "$DIR/slc-view-002.toml" || exit 12
    "#;
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let out = under_xvfb("bash")
        .args(["-c", script])
        .env("SLC", env!("CARGO_BIN_EXE_slc"))
        .env("SCENE", scene)
        .env("DIR", &dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{:?}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let shot = image::open(dir.join("slc-view-001.png")).unwrap();
    assert_eq!((shot.width(), shot.height()), (96, 64));
    let saved = std::fs::read_to_string(dir.join("slc-view-002.toml")).unwrap();
    let vec3 = |key: &str| -> Vec<f32> {
        let line = saved
            .lines()
            .find_map(|l| l.strip_prefix(key))
            .expect(&saved);
        let numbers = line.trim_matches(|c| c == '[' || c == ']');
        numbers.split(", ").map(|v| v.parse().unwrap()).collect()
    };
    let (position, target) = (vec3("position = "), vec3("target = "));
    // The scene's camera is at z = 3.8 looking down -z: W moved it forward, the mouse turned
    // it right (+x).
    assert!(position[2] < 3.79, "{saved}");
    assert!(target[0] - position[0] > 0.05, "{saved}");
}
