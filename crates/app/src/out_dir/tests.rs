use super::faults::{Fault, Faults};
use super::*;
use std::collections::BTreeMap;

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slc-outdir-{name}-{}", std::process::id()));
    fs::remove_dir_all(&d).ok();
    d
}

/// What a user sees in `root`: every file at a name outside slc's own (`.slc*` at the top),
/// read through the links; a link that resolves to nothing is no file.
fn shown(root: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        for e in fs::read_dir(root.join(&rel)).unwrap().flatten() {
            let path = rel.join(e.file_name());
            if rel.as_os_str().is_empty() && e.file_name().to_string_lossy().starts_with(".slc") {
                continue;
            }
            let meta = e.metadata().unwrap();
            if meta.is_dir() {
                stack.push(path);
            } else if let Ok(bytes) = fs::read(root.join(&path)) {
                out.insert(path, bytes);
            }
        }
    }
    out
}

/// Every folder under `root` outside slc's own names.
fn folders(root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        for e in fs::read_dir(root.join(&rel)).unwrap().flatten() {
            let path = rel.join(e.file_name());
            if !path.to_string_lossy().starts_with(".slc") && e.file_type().unwrap().is_dir() {
                out.push(path.to_string_lossy().into_owned());
                stack.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The names at the top of `root`, a version folder's number as N.
fn listing(root: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(root)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .map(|n| match version_of(&n) {
            Some(_) => ".slc-result-N".into(),
            None => n.to_string_lossy().into_owned(),
        })
        .collect();
    v.sort();
    v
}

type Files = &'static [(&'static str, &'static [u8])];

fn expected(files: Files) -> BTreeMap<PathBuf, Vec<u8>> {
    files
        .iter()
        .map(|(p, b)| (PathBuf::from(p), b.to_vec()))
        .collect()
}

/// One run writing `files` with `faults`; the steps it took.
fn run(root: &Path, files: Files, faults: Faults) -> (Result<(), String>, usize) {
    let mut out = OutDir::open_with(root, faults).unwrap();
    let mut result = Ok(());
    for (path, bytes) in files {
        result = result.and_then(|()| out.write(path, bytes));
    }
    if result.is_err() {
        let steps = out.faults.steps();
        return (result, steps);
    }
    let result = out.commit_in_place();
    (result, out.faults.steps())
}

// The previous result (a compare-like folder), the new one (some names kept, some new, some
// gone) and a later one.
const OLD: Files = &[
    ("report.json", b"old report"),
    ("none/total.exr", b"old none"),
    ("none/report.json", b"old none report"),
    ("ellipsoid/report.json", b"old ellipsoid"),
    ("compare.json", b"old table"),
];
const NEW: Files = &[
    ("report.json", b"new report"),
    ("none/total.exr", b"new none"),
    ("none/report.json", b"new none report"),
    ("vsgl/deep/report.json", b"new vsgl"),
    ("total.exr", b"new total"),
];
const LATER: Files = &[("report.json", b"later"), ("none/total.exr", b"later none")];

#[test]
fn every_fault_at_every_step_leaves_the_previous_or_the_new_result_whole() {
    let user = (PathBuf::from("notes.txt"), b"mine".to_vec());
    let mut k = 0;
    let mut kills_after_switch = 0;
    loop {
        let mut done = true;
        for fault in [Fault::Fail(k), Fault::Kill(k)] {
            let root = temp(&format!("fault-{k}"));
            assert!(run(&root, OLD, Faults::default()).0.is_ok());
            fs::write(root.join(&user.0), &user.1).unwrap();
            let mut old = expected(OLD);
            old.insert(user.0.clone(), user.1.clone());
            let mut new = expected(NEW);
            new.insert(user.0.clone(), user.1.clone());
            let (result, steps) = run(&root, NEW, Faults::planned(fault));
            done &= steps <= k;
            let after = shown(&root);
            match fault {
                Fault::Fail(_) if result.is_err() => {
                    assert_eq!(after, old, "{fault:?}: {result:?}");
                    let e = result.unwrap_err();
                    assert!(!e.contains(".slc-result"), "a hidden path in {e}");
                }
                Fault::Fail(_) => assert_eq!(after, new, "{fault:?}"),
                Fault::Kill(_) => {
                    assert!(after == old || after == new, "{fault:?}: {after:?}");
                    // Killed (the fault's step was reached) after the switch.
                    kills_after_switch += usize::from(after == new && steps > k);
                }
            }
            // A failed run undoes what it made (a killed one leaves that to the next run).
            if after == old && matches!(fault, Fault::Fail(_)) {
                assert_eq!(folders(&root), ["ellipsoid", "none"], "{fault:?}");
            }
            // The next run removes what this one left and commits whole.
            assert!(run(&root, LATER, Faults::default()).0.is_ok(), "{fault:?}");
            let mut later = expected(LATER);
            later.insert(user.0.clone(), user.1.clone());
            assert_eq!(shown(&root), later, "{fault:?}");
            assert_eq!(folders(&root), ["none"], "{fault:?}: empty folders left");
            assert_eq!(
                listing(&root),
                [
                    ".slc-result",
                    ".slc-result-N",
                    ".slc.lock",
                    "none",
                    "notes.txt",
                    "report.json"
                ],
                "{fault:?}"
            );
            fs::remove_dir_all(&root).unwrap();
        }
        if done {
            break;
        }
        k += 1;
    }
    // Writes, syncs, links and folders, the switch, and the removal of the previous result.
    assert!(k > 15, "{k} steps");
    assert!(kills_after_switch > 0, "no kill after the switch was tried");
}

#[test]
fn a_file_in_the_way_of_a_result_folder_replaces_nothing() {
    // The case: a plain file where compare puts a strategy folder.
    let root = temp("inway");
    assert!(run(&root, OLD, Faults::default()).0.is_ok());
    fs::remove_file(root.join("ellipsoid/report.json")).unwrap();
    fs::remove_dir(root.join("ellipsoid")).unwrap();
    fs::write(root.join("ellipsoid"), b"user").unwrap();
    let before = shown(&root);
    let out = OutDir::open(&root).unwrap();
    let e = out
        .expect(["none/total.exr", "ellipsoid/report.json"])
        .unwrap_err();
    assert!(
        e.contains("ellipsoid") && e.contains("a file slc did not write"),
        "{e}"
    );
    drop(out);
    let (result, _) = run(&root, OLD, Faults::default());
    let e = result.unwrap_err();
    assert!(
        e.contains("ellipsoid") && e.contains("nothing was replaced"),
        "{e}"
    );
    assert_eq!(shown(&root), before);
    // A folder where a file goes.
    fs::remove_file(root.join("ellipsoid")).unwrap();
    fs::create_dir(root.join("total.exr")).unwrap();
    let e = run(&root, NEW, Faults::default()).0.unwrap_err();
    assert!(e.contains("total.exr") && e.contains("a folder"), "{e}");
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn a_full_disk_names_the_final_file_and_changes_nothing() {
    let root = temp("full");
    assert!(run(&root, OLD, Faults::default()).0.is_ok());
    let (result, _) = run(&root, NEW, Faults::planned(Fault::Fail(1)));
    let e = result.unwrap_err();
    let want = root.join("none/total.exr").display().to_string();
    assert!(
        e.contains(&want) && e.contains("No space left") && e.contains("keeps its previous result"),
        "{e}"
    );
    assert_eq!(shown(&root), expected(OLD));
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn a_second_run_is_refused_while_the_first_holds_the_folder() {
    let root = temp("lock");
    let first = OutDir::open(&root).unwrap();
    let e = OutDir::open(&root).err().unwrap();
    let pid = format!("pid {}", std::process::id());
    assert!(
        e.contains("in use by another slc run") && e.contains(&pid),
        "{e}"
    );
    drop(first);
    let again = OutDir::open(&root).unwrap();
    assert!(root.join(".slc.lock").is_file());
    drop(again);
}

/// A run that ends without a result (dropped, or its commit failing) in a folder it created
/// leaves no folder behind, nor the folders it made above it; in a folder that was there,
/// what was there stays.
#[test]
fn a_run_without_a_result_removes_the_folders_it_created() {
    let above = temp("created");
    let root = above.join("deeper/out");
    let mut out = OutDir::open(&root).unwrap();
    out.write("report.json", b"new").unwrap();
    drop(out);
    assert!(!above.exists(), "{}", above.display());
    // A failed write (steps 0-4: NEW's five files) or sync (5-7) of a first run.
    for k in 0..8 {
        let (result, _) = run(&root, NEW, Faults::planned(Fault::Fail(k)));
        assert!(result.is_err(), "fault at {k}");
        assert!(!above.exists(), "fault at {k}");
    }
    // An empty folder a user made stays, with slc's lock in it.
    fs::create_dir_all(&root).unwrap();
    drop(OutDir::open(&root).unwrap());
    assert_eq!(listing(&root), [".slc.lock"]);
    // A run refused by the lock of another removes nothing, also where the other made the
    // folder.
    let first = OutDir::open(&root).unwrap();
    assert!(OutDir::open(&root).is_err());
    drop(first);
    assert!(root.is_dir());
    fs::remove_dir_all(&above).unwrap();
    let first = OutDir::open(&root).unwrap();
    assert!(OutDir::open(&root).is_err());
    assert!(root.join(".slc.lock").is_file() && first.staging.is_dir());
    drop(first);
    assert!(!above.exists());
}

/// Only the folders this run's own `mkdir` made count as its: a folder that was there, or
/// that a `..` in the path names, is not.
#[test]
fn the_folders_made_are_those_the_run_made() {
    let above = temp("made");
    assert_eq!(
        make_folders(&above.join("a/b")).unwrap(),
        Some(above.clone())
    );
    assert!(above.join("a/b").is_dir());
    assert_eq!(make_folders(&above.join("a/b")).unwrap(), None);
    assert_eq!(
        make_folders(&above.join("a/c")).unwrap(),
        Some(above.join("a/c"))
    );
    // `new` is made, `new/..` (the folder above) is there, and so is `a`.
    assert_eq!(make_folders(&above.join("new/../a")).unwrap(), None);
    assert_eq!(
        make_folders(&above.join("new2/../d")).unwrap(),
        Some(above.join("new2/../d"))
    );
    fs::write(above.join("file"), b"x").unwrap();
    assert!(make_folders(&above.join("file/x")).is_err());
    // A name too long for a folder below two new ones: both are removed again.
    let long = "x".repeat(300);
    assert!(make_folders(&above.join("e/f").join(&long)).is_err());
    assert!(!above.join("e").exists());
    fs::remove_dir_all(&above).unwrap();
}

#[test]
fn a_dropped_run_leaves_the_previous_result() {
    let root = temp("drop");
    assert!(run(&root, OLD, Faults::default()).0.is_ok());
    let mut out = OutDir::open(&root).unwrap();
    out.write("report.json", b"new").unwrap();
    drop(out);
    assert_eq!(shown(&root), expected(OLD));
    assert_eq!(
        listing(&root),
        [
            ".slc-result",
            ".slc-result-N",
            ".slc.lock",
            "compare.json",
            "ellipsoid",
            "none",
            "report.json"
        ]
    );
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn leftovers_at_slc_names_never_block_a_run_and_a_file_is_not_a_folder() {
    let root = temp("stale");
    fs::create_dir_all(root.join(".slc-staging-1/x")).unwrap();
    fs::write(root.join(".slc-staging-2"), "").unwrap();
    fs::write(root.join(".slc-result-7"), "").unwrap();
    fs::write(root.join(".slc-result.next"), "").unwrap();
    assert!(run(&root, LATER, Faults::default()).0.is_ok());
    assert_eq!(
        listing(&root),
        [
            ".slc-result",
            ".slc-result-N",
            ".slc.lock",
            "none",
            "report.json"
        ]
    );
    // Something else at the name of slc's link is refused, not removed.
    let root2 = temp("stale2");
    fs::create_dir_all(root2.join(".slc-result")).unwrap();
    let e = OutDir::open(&root2).err().unwrap();
    assert!(
        e.contains(".slc-result") && e.contains("move it away"),
        "{e}"
    );
    let file = root.join("report.json");
    assert!(OutDir::open(&root.join("none/total.exr"))
        .err()
        .unwrap()
        .contains("not a folder"));
    assert!(file.exists());
    fs::remove_dir_all(&root).unwrap();
    fs::remove_dir_all(&root2).unwrap();
}

#[test]
fn a_result_of_the_earlier_layout_becomes_a_version_with_the_same_bytes() {
    let root = temp("legacy");
    fs::create_dir_all(root.join("none")).unwrap();
    fs::write(root.join("report.json"), "old").unwrap();
    fs::write(root.join("none/total.exr"), "old none").unwrap();
    fs::write(root.join("none/mine.txt"), "user").unwrap();
    fs::write(
        root.join(".slc-manifest"),
        "none/total.exr\nreport.json\n../escape\n",
    )
    .unwrap();
    let before = shown(&root);
    let out = OutDir::open(&root).unwrap();
    assert_eq!(shown(&root), before);
    assert!(!root.join(".slc-manifest").exists());
    assert!(fs::symlink_metadata(root.join("report.json"))
        .unwrap()
        .is_symlink());
    drop(out);
    assert!(run(&root, LATER, Faults::default()).0.is_ok());
    let mut later = expected(LATER);
    later.insert("none/mine.txt".into(), b"user".to_vec());
    assert_eq!(shown(&root), later);
    fs::remove_dir_all(&root).unwrap();
}
