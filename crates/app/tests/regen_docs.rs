//! `tools/regen-docs`, the one script that writes the figures of README.md and docs/*.md:
//! `--check` reruns the recipes whose figures are deterministic (counts, VPLs, false
//! positives and their ratios, the tables rendered from the GPU report) at the sizes the
//! documents state and fails when a document says something else than the code produces
//! now; `--quick` runs every recipe at tiny sizes into copies of the documents, so the script
//! cannot rot, and this test checks (independently of the script's own assertions) that the
//! copies differ from the originals only between the `<!-- regen:NAME -->` markers and that
//! every measured block names its command, commit, machine and date.
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn regen(args: &[&str]) -> (bool, String) {
    let out = Command::new("python3")
        .arg(root().join("tools/regen-docs"))
        .args(args)
        .arg("--slc")
        .arg(env!("CARGO_BIN_EXE_slc"))
        .output()
        .expect("python3 runs tools/regen-docs");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// The documents the script may write into.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![PathBuf::from("README.md")];
    let mut more: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .map(|p| Path::new("docs").join(p.file_name().unwrap()))
        .collect();
    more.sort();
    docs.extend(more);
    docs
}

/// The text with every block's content removed (the markers kept), and the blocks by name.
fn split_blocks(text: &str) -> (String, Vec<(String, String)>) {
    let mut outside = String::new();
    let mut blocks = Vec::new();
    let mut rest = text;
    while let Some(start) = rest.find("<!-- regen:") {
        let after = &rest[start + "<!-- regen:".len()..];
        let name_end = after.find(" -->").expect("an opening marker ends with -->");
        let name = &after[..name_end];
        let body_start = start + "<!-- regen:".len() + name_end + " -->".len();
        let close = format!("<!-- /regen:{name} -->");
        let body_len = rest[body_start..]
            .find(&close)
            .unwrap_or_else(|| panic!("regen:{name} is never closed"));
        outside.push_str(&rest[..body_start]);
        outside.push_str(&close);
        blocks.push((
            name.to_string(),
            rest[body_start..body_start + body_len].to_string(),
        ));
        rest = &rest[body_start + body_len + close.len()..];
    }
    outside.push_str(rest);
    (outside, blocks)
}

#[test]
fn deterministic_figures_match_the_code() {
    let (ok, text) = regen(&["--check"]);
    assert!(ok, "tools/regen-docs --check failed:\n{text}");
    for block in [
        "default-render",
        "tight-sponza-640",
        "gpu-table2",
        "headline",
    ] {
        assert!(text.contains(block), "{block} was not checked:\n{text}");
    }
}

#[test]
fn quick_regeneration_rewrites_only_its_blocks() {
    let out = common::out_dir("regen-docs");
    let (ok, text) = regen(&["--quick", "--out", out.to_str().unwrap()]);
    assert!(ok, "tools/regen-docs --quick failed:\n{text}");
    let mut rewritten = 0;
    let mut measured = 0;
    for doc in documents() {
        let original = std::fs::read_to_string(root().join(&doc)).unwrap();
        let (outside, blocks) = split_blocks(&original);
        let copy = out.join(&doc);
        if blocks.is_empty() {
            assert!(
                !copy.exists(),
                "{} has no block but was written",
                doc.display()
            );
            continue;
        }
        let new =
            std::fs::read_to_string(&copy).unwrap_or_else(|e| panic!("{}: {e}", copy.display()));
        let (new_outside, new_blocks) = split_blocks(&new);
        assert_eq!(
            new_outside,
            outside,
            "{}: text outside the blocks changed",
            doc.display()
        );
        let names = |b: &[(String, String)]| b.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
        assert_eq!(names(&new_blocks), names(&blocks), "{}", doc.display());
        for (name, body) in &new_blocks {
            rewritten += 1;
            // The quick runs render the built-in scene at 48x32 (compare, bench) or 32x32
            // (render) and the memory grid's small cases: a block that names a command it
            // ran must name the one that ran.
            if body.contains("`slc ") || body.contains("`python3 tools/") {
                measured += 1;
                assert!(
                    body.contains("--width 48")
                        || body.contains("--width 32")
                        || body.contains("--resolutions 48x32")
                        || body.contains("grid.py --quick"),
                    "regen:{name} does not name the quick command:\n{body}"
                );
                let date = regex_lite_date(body);
                assert!(date, "regen:{name} has no date:\n{body}");
                assert!(
                    body.contains("threads)"),
                    "regen:{name} has no machine:\n{body}"
                );
            }
        }
    }
    assert!(
        rewritten >= 10 && measured >= 5,
        "{rewritten} blocks, {measured} measured"
    );
}

/// Whether `s` holds a date written YYYY-MM-DD.
fn regex_lite_date(s: &str) -> bool {
    let b = s.as_bytes();
    b.windows(10).any(|w| {
        w.iter().enumerate().all(|(i, c)| {
            if i == 4 || i == 7 {
                *c == b'-'
            } else {
                c.is_ascii_digit()
            }
        })
    })
}
