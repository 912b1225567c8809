//! Results cannot be torn: the output folder is locked and checked before any work, results
//! are committed by renames, and non-finite results are errors.
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{command, out_dir, run};

/// `slc render ARGS --out OUT` (ARGS split at spaces).
fn render(args: &str, out: &Path) -> Output {
    run(&format!("render {args}"), out)
}

fn spawn_render(args: &str, out: &Path) -> Child {
    command(&format!("render {args}"), out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// What a user sees under `dir`: every file outside slc's own names (`.slc*` at the top),
/// read through slc's links, with its bytes (a link that resolves to nothing is no file).
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(dir).unwrap().to_path_buf();
            if rel.to_string_lossy().starts_with(".slc") {
                continue;
            }
            if p.is_dir() {
                stack.push(p);
            } else if let Ok(bytes) = std::fs::read(&p) {
                files.insert(rel, bytes);
            }
        }
    }
    files
}

/// Polls `cond` every millisecond for up to 60 s.
fn wait_for(what: &str, mut cond: impl FnMut() -> bool) {
    let start = Instant::now();
    while !cond() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "timed out: {what}"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
}

/// The version folder of a live run (one `.slc-result` does not point to), once it holds a
/// file.
fn staged_file(out: &Path) -> bool {
    let current = std::fs::read_link(out.join(".slc-result")).ok();
    std::fs::read_dir(out).is_ok_and(|entries| {
        entries.flatten().any(|e| {
            let name = e.file_name();
            name.to_string_lossy().starts_with(".slc-result-")
                && current.as_deref() != Some(Path::new(&name))
                && std::fs::read_dir(e.path()).is_ok_and(|mut d| d.next().is_some())
        })
    })
}

#[test]
fn a_second_run_into_a_busy_folder_is_refused_naming_the_holder() {
    let out = out_dir("busy");
    let mut first = spawn_render("--width 320 --height 240 --rsm 16 --spp 8", &out);
    let lock = out.join(".slc.lock");
    wait_for("the first run's lock", || {
        std::fs::read_to_string(&lock).is_ok_and(|s| s.contains("pid"))
    });
    let second = render("--width 8 --height 8 --rsm 2", &out);
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(!second.status.success());
    assert!(
        err.contains("in use by another slc run") && err.contains(&format!("pid {}", first.id())),
        "{err}"
    );
    assert!(first.wait().unwrap().success());
    assert!(out.join("report.json").is_file());
}

#[test]
fn a_run_killed_while_writing_leaves_the_previous_result_intact() {
    let out = out_dir("killed");
    let small = "--width 16 --height 12 --rsm 2 --seed 1";
    assert!(render(small, &out).status.success());
    let before = snapshot(&out);
    // Large images with few VPLs: the writing takes long enough to be caught in the middle.
    let mut run = spawn_render("--width 1600 --height 1200 --rsm 2 --seed 2", &out);
    wait_for("the second run's first staged file", || staged_file(&out));
    run.kill().unwrap();
    run.wait().unwrap();
    let after = snapshot(&out);
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        before.keys().collect::<Vec<_>>()
    );
    assert!(after == before, "a file at a final name changed");
    // The next run removes the killed run's version folder.
    assert!(render(small, &out).status.success());
    assert!(!staged_file(&out));
    let versions = std::fs::read_dir(&out)
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            name.to_string_lossy().starts_with(".slc-result-")
        })
        .count();
    assert_eq!(versions, 1);
}

#[test]
fn an_unwritable_output_fails_before_any_work() {
    let start = Instant::now();
    // A big render that would take long: it must fail at once.
    let o = render(
        "--width 1920 --height 1080 --rsm 64",
        Path::new("/proc/slc-no-such-folder"),
    );
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("/proc/slc-no-such-folder"), "{err}");
    assert!(start.elapsed() < Duration::from_secs(10), "{err}");
    // A file where the folder should be.
    let file = out_dir("file");
    std::fs::write(&file, "").unwrap();
    let o = render("--width 8 --height 8 --rsm 2", &file);
    assert!(String::from_utf8_lossy(&o.stderr).contains("not a folder"));
    std::fs::remove_file(&file).ok();
}

#[test]
fn a_result_that_cannot_be_placed_replaces_nothing() {
    let out = out_dir("inway");
    assert!(render("--width 16 --height 12 --rsm 2", &out)
        .status
        .success());
    let before = std::fs::read(out.join("report.json")).unwrap();
    std::fs::remove_file(out.join("total.png")).unwrap();
    std::fs::create_dir(out.join("total.png")).unwrap();
    let o = render("--width 16 --height 12 --rsm 2 --seed 9", &out);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("total.png") && err.contains("move it away"),
        "{err}"
    );
    assert_eq!(std::fs::read(out.join("report.json")).unwrap(), before);
}

fn compare(args: &str, out: &Path) -> Output {
    run(&format!("compare {args}"), out)
}

/// The case: a plain file where compare puts a strategy folder stops the second run
/// before any work, and every file of the first run stays as it was; a render into the
/// folder then replaces the compare whole, leaving no strategy folder behind.
#[test]
fn a_file_in_the_way_of_a_strategy_folder_stops_compare_before_any_work() {
    let out = out_dir("compare-inway");
    let args = "--width 16 --height 16 --rsm 4 --no-reference --culling none,ellipsoid";
    let first = compare(&format!("{args} --seed 1"), &out);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let before = snapshot(&out);
    std::fs::remove_dir_all(out.join("ellipsoid")).unwrap();
    std::fs::write(out.join("ellipsoid"), "mine").unwrap();
    let o = compare(&format!("{args} --seed 2"), &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("ellipsoid") && err.contains("nothing was written") && !err.contains("VPLs"),
        "{err}"
    );
    let after = snapshot(&out);
    for (file, bytes) in &before {
        if !file.starts_with("ellipsoid") {
            assert_eq!(after.get(file), Some(bytes), "{}", file.display());
        }
    }
    std::fs::remove_file(out.join("ellipsoid")).unwrap();
    assert!(render("--width 8 --height 8 --rsm 2", &out)
        .status
        .success());
    let left: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with(".slc"))
        .collect();
    assert!(
        left.iter()
            .all(|n| !["none", "ellipsoid"].contains(&n.as_str())),
        "{left:?}"
    );
}

/// A floor quad under a light of the given intensity, as OBJ + scene settings.
fn floor_with_light(dir: &Path, intensity: &str) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("floor.obj"),
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 0 -1.5\nv 1 0 -1.5\nv 1 1 -1.5\nv -1 1 -1.5\nf 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\n",
    )
    .unwrap();
    let toml = dir.join("scene.toml");
    std::fs::write(
        &toml,
        format!(
            "scene = \"floor.obj\"\n[camera]\nposition = [0.0, 1.0, 2.5]\ntarget = [0.0, 0.2, 0.0]\nyfov_deg = 60.0\n[[lights]]\ntype = \"point\"\nposition = [0.0, 0.5, 0.0]\nintensity = {intensity}\n"
        ),
    )
    .unwrap();
    toml
}

#[test]
fn an_overflowing_light_is_refused_when_loaded() {
    let dir = out_dir("overflow");
    let toml = floor_with_light(&dir, "3e38");
    let out = dir.join("out");
    let o = render(
        &format!("{} --width 16 --height 12 --rsm 4", toml.display()),
        &out,
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("intensity") && err.contains("1e20"), "{err}");
    assert!(!out.join("report.json").exists());
    // Within the limit, the same scene renders finite images.
    let toml = floor_with_light(&dir, "1e19");
    let o = render(
        &format!("{} --width 16 --height 12 --rsm 4", toml.display()),
        &out,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
