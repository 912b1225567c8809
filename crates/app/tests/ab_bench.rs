//! `tools/ab-bench`, two builds' `slc bench` alternated round by round: run here with this
//! build's `slc` as both the old and the new one on a tiny frame, its table and JSON hold
//! every pass of every round, the frame as the sum of the passes and each round's ratio; and
//! it refuses what it cannot compare.
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn ab_bench(work: &Path, args: &[&str]) -> Output {
    let slc = env!("CARGO_BIN_EXE_slc");
    let root = root();
    Command::new("python3")
        .arg(root.join("tools/ab-bench"))
        .args(["--old-bin", slc, "--new-bin", slc, "--no-build"])
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
    for run in ["old-1", "new-1", "old-2", "new-2", "old-3", "new-3"] {
        assert!(
            work.join("runs").join(run).join("bench.csv").is_file(),
            "{run}"
        );
    }
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(work.join("ab-bench.json")).unwrap()).unwrap();
    let rows = report["rows"].as_array().unwrap();
    let strategies: Vec<&str> = rows
        .iter()
        .map(|r| r["key"]["strategy"].as_str().unwrap())
        .collect();
    assert_eq!(strategies, ["ellipsoid", "binned"]);
    let passes = [
        "gbuffer",
        "rsm",
        "vpl_generation",
        "direct",
        "culling",
        "shading",
        "denoise",
    ];
    let values = |row: &serde_json::Value, pass: &str, side: &str| -> Vec<f64> {
        row["passes"][pass][side]
            .as_array()
            .unwrap_or_else(|| panic!("{pass} {side}"))
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    for row in rows {
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
    // No `--` before slc bench's arguments, and an --out that is ab-bench's to choose.
    for (args, says) in [
        (&["--rounds", "1"][..], "after --"),
        (&["--", "--out", "x"][..], "leave --out"),
        (&["--rounds", "0", "--"][..], "at least 1"),
    ] {
        let out = ab_bench(&work, args);
        assert!(!out.status.success(), "{args:?}");
        assert!(text(&out).contains(says), "{args:?}: {}", text(&out));
    }
    let _ = std::fs::remove_dir_all(&work);
}
