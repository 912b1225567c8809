//! `tools/ab-bench`, two builds' `slc bench` alternated round by round: run here with this
//! build's `slc` as both the old and the new one on a tiny frame, the runs alternate, its
//! table and JSON hold every pass of every round, the frame as the sum of the passes and each
//! round's ratio; with stand-ins for the two builds, a time of 0 has no ratio, a row one
//! build lacks is left out, a row without every pass has no frame; and it refuses what it
//! cannot compare.
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn ab_bench(work: &Path, args: &[&str]) -> Output {
    let slc = Path::new(env!("CARGO_BIN_EXE_slc"));
    ab_bench_of(slc, slc, work, args)
}

/// `tools/ab-bench` with `old` and `new` as the two builds, both run in the repository.
fn ab_bench_of(old: &Path, new: &Path, work: &Path, args: &[&str]) -> Output {
    let root = root();
    Command::new("python3")
        .arg(root.join("tools/ab-bench"))
        .arg("--old-bin")
        .arg(old)
        .arg("--new-bin")
        .arg(new)
        .arg("--no-build")
        .arg("--old-dir")
        .arg(&root)
        .arg("--new-dir")
        .arg(&root)
        .arg("--work")
        .arg(work)
        .args(args)
        .output()
        .expect("python3 runs tools/ab-bench")
}

/// The comparison ab-bench wrote into `work`.
fn report(work: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(work.join("ab-bench.json")).unwrap()).unwrap()
}

fn text(out: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

#[test]
fn rounds_alternate_and_every_pass_is_compared() {
    let work = std::env::temp_dir().join(format!("slc-ab-bench-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    let out = ab_bench(
        &work,
        &[
            "--rounds",
            "3",
            "--",
            "--resolutions",
            "32x24",
            "--rsms",
            "8",
            "--culling",
            "ellipsoid,binned",
            "--repeat",
            "1",
        ],
    );
    assert!(out.status.success(), "{}", text(&out));
    // Three rounds of each side, the order alternating: old first in the first round.
    let written = |run: &str| {
        std::fs::metadata(work.join("runs").join(run).join("bench.csv"))
            .and_then(|m| m.modified())
            .unwrap_or_else(|e| panic!("{run}: {e}"))
    };
    let order = ["old-1", "new-1", "new-2", "old-2", "old-3", "new-3"];
    for pair in order.windows(2) {
        assert!(written(pair[0]) < written(pair[1]), "{pair:?}");
    }
    let report = report(&work);
    assert_eq!(
        report["order"],
        serde_json::json!([["old", "new"], ["new", "old"], ["old", "new"]])
    );
    let rows = report["rows"].as_array().unwrap();
    let strategies: Vec<&str> = rows
        .iter()
        .map(|r| r["key"]["strategy"].as_str().unwrap())
        .collect();
    assert_eq!(strategies, ["ellipsoid", "binned"]);
    let values = |row: &serde_json::Value, pass: &str, side: &str| -> Vec<f64> {
        row["passes"][pass][side]
            .as_array()
            .unwrap_or_else(|| panic!("{pass} {side}"))
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    for row in rows {
        // Every pass `slc bench` times (each `*_ms` column but the sum of two of them): the
        // frame must be their sum, so a pass added to the bench and not to the tool fails.
        let passes: Vec<&str> = row["passes"]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .filter(|p| !["frame", "culling_plus_shading"].contains(p))
            .collect();
        assert!(passes.len() >= 7, "{passes:?}");
        for side in ["old", "new"] {
            let frame = values(row, "frame", side);
            assert_eq!(frame.len(), 3);
            for round in 0..3 {
                let sum: f64 = passes.iter().map(|p| values(row, p, side)[round]).sum();
                assert!((frame[round] - sum).abs() <= 1e-9 * sum, "{frame:?} {sum}");
            }
        }
        for pass in passes.iter().chain(&["frame"]) {
            let (old, new) = (values(row, pass, "old"), values(row, pass, "new"));
            let ratio = values(row, pass, "ratio");
            for k in 0..3 {
                assert!(old[k] > 0.0 && new[k] > 0.0, "{pass}: {old:?} {new:?}");
                assert!(
                    (ratio[k] - new[k] / old[k]).abs() <= 1e-12 * ratio[k],
                    "{pass}"
                );
            }
        }
    }
    let table = std::fs::read_to_string(work.join("ab-bench.md")).unwrap();
    assert!(
        table.contains("| pass | old | new | new / old |"),
        "{table}"
    );
    assert!(table.contains("| frame | "), "{table}");
    std::fs::remove_dir_all(&work).unwrap();
}

#[test]
fn what_it_cannot_compare_is_refused() {
    let work = std::env::temp_dir().join(format!("slc-ab-bench-refused-{}", std::process::id()));
    // No `--` before slc bench's arguments, an --out that is ab-bench's to choose, no
    // rounds, and an old build given twice.
    for (args, says) in [
        (&["--rounds", "1"][..], "after --"),
        (&["--", "--out", "x"][..], "leave --out"),
        (&["--rounds", "0", "--"][..], "at least 1"),
        (&["--old", "HEAD", "--"][..], "not --old"),
    ] {
        let out = ab_bench(&work, args);
        assert!(!out.status.success(), "{args:?}");
        assert!(text(&out).contains(says), "{args:?}: {}", text(&out));
    }
    let _ = std::fs::remove_dir_all(&work);
}

/// A stand-in for `slc` that writes `csv` as its bench.csv into the folder after `--out`.
fn fake_slc(dir: &Path, name: &str, csv: &str) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join(name);
    let script = format!(
        "#!/bin/sh\nwhile [ \"$1\" != --out ]; do shift; done\nmkdir -p \"$2\"\n\
         cat > \"$2/bench.csv\" <<'EOF'\n{csv}EOF\n"
    );
    std::fs::write(&path, script).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

#[test]
fn zero_times_missing_rows_and_missing_passes() {
    let work = std::env::temp_dir().join(format!("slc-ab-bench-fake-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    let header = "scene,width,height,rsm,strategy,gbuffer_ms,rsm_ms,vpl_generation_ms,\
                  direct_ms,culling_ms,shading_ms,denoise_ms\n";
    // The old build: the filter at 0 ms, a row the new one lacks, and (binned) no filter
    // column value.
    let old = fake_slc(
        &work,
        "old",
        &format!(
            "{header}s,8,8,4,ellipsoid,2,1,1,1,4,8,0\ns,8,8,4,tight,2,1,1,1,4,8,1\n\
             s,8,8,4,binned,2,1,1,1,4,8,\n"
        ),
    );
    let new = fake_slc(
        &work,
        "new",
        &format!("{header}s,8,8,4,ellipsoid,1,1,1,1,2,2,3\ns,8,8,4,binned,1,1,1,1,2,2,3\n"),
    );
    let out = ab_bench_of(&old, &new, &work.join("ab"), &["--rounds", "2", "--"]);
    assert!(out.status.success(), "{}", text(&out));
    let report = report(&work.join("ab"));
    let rows = report["rows"].as_array().unwrap();
    // `tight` is the old build's only: left out, and said so.
    assert_eq!(rows.len(), 2, "{report}");
    assert!(text(&out).contains("tight"), "{}", text(&out));
    let ellipsoid = &rows[0]["passes"];
    assert_eq!(
        ellipsoid["denoise"]["ratio"],
        serde_json::json!([null, null])
    );
    assert_eq!(ellipsoid["culling"]["ratio"], serde_json::json!([0.5, 0.5]));
    assert_eq!(ellipsoid["frame"]["old"], serde_json::json!([17.0, 17.0]));
    assert_eq!(ellipsoid["frame"]["new"], serde_json::json!([11.0, 11.0]));
    let ratio = 11.0 / 17.0;
    assert_eq!(
        ellipsoid["frame"]["ratio"],
        serde_json::json!([ratio, ratio])
    );
    // binned: the old build wrote no filter time, so neither the filter nor the frame.
    let binned = &rows[1]["passes"];
    assert!(
        binned.get("denoise").is_none() && binned.get("frame").is_none(),
        "{binned}"
    );
    assert_eq!(binned["shading"]["ratio"], serde_json::json!([0.25, 0.25]));
    let table = std::fs::read_to_string(work.join("ab/ab-bench.md")).unwrap();
    assert!(
        table.contains("| denoise | 0.0, 0.0 | 3.0, 3.0 | -, - |"),
        "{table}"
    );
    std::fs::remove_dir_all(&work).unwrap();
}
