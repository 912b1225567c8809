//! The pages of `slc compare` and `slc sweep` (`index.html`) as a person sees them: every file
//! a page shows or links is in the folder, and headless Chromium loads the page with every
//! image (the page's own script counts the images that did not load into `data-broken-images`).
//! At 1400 pixels no table is wider than the window. A screenshot of each page is left in the
//! output folder to look at. `.ci/run` installs
//! Chromium; elsewhere, without it, the browser half prints a notice and is skipped (with `CI`
//! set it fails instead).
use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{out_dir, run_ok};

/// The values of every `attribute="…"` in `html`.
fn attribute_values<'a>(html: &'a str, attribute: &str) -> Vec<&'a str> {
    let key = format!(" {attribute}=\"");
    html.match_indices(&key)
        .map(|(i, _)| {
            let rest = &html[i + key.len()..];
            &rest[..rest.find('"').unwrap()]
        })
        .collect()
}

/// The Chromium binary, if one is installed.
fn chromium() -> Option<PathBuf> {
    let found = ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find_map(|name| {
            let o = Command::new("sh")
                .args(["-c", &format!("command -v {name}")])
                .output()
                .ok()?;
            o.status
                .success()
                .then(|| PathBuf::from(String::from_utf8_lossy(&o.stdout).trim()))
        });
    if found.is_none() {
        if std::env::var_os("CI").is_some() {
            panic!("CI is set but Chromium is not installed (.ci/run installs it)");
        }
        eprintln!("notice: Chromium not found; the pages were checked without a browser");
    }
    found
}

/// Runs headless Chromium on `page` with `extra` arguments; returns its stdout.
fn headless(browser: &Path, page: &Path, extra: &[String]) -> String {
    let profile = page.with_file_name(".chromium-profile");
    let o = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--allow-file-access-from-files",
            "--virtual-time-budget=20000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("Chromium runs");
    let _ = std::fs::remove_dir_all(&profile);
    assert!(
        o.status.success(),
        "Chromium failed on {}: {}",
        page.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Checks the page of the folder `out`: every referenced file exists, and Chromium loads at
/// least `images` images with none broken. Leaves `page.png` (a screenshot) in `out`.
fn check_page(out: &Path, images: usize) {
    let page = out.join("index.html");
    let html = std::fs::read_to_string(&page).unwrap();
    let sources = attribute_values(&html, "src");
    assert!(
        sources.len() >= images,
        "{} images: {sources:?}",
        sources.len()
    );
    for file in sources.iter().chain(&attribute_values(&html, "href")) {
        assert!(
            out.join(file).is_file(),
            "index.html shows {file}, which is missing"
        );
    }
    let Some(browser) = chromium() else { return };
    let dom = headless(
        &browser,
        &page,
        &["--dump-dom".to_string(), "--window-size=1400,900".into()],
    );
    let loaded: Vec<&str> = attribute_values(&dom, "data-images");
    let broken: Vec<&str> = attribute_values(&dom, "data-broken-images");
    assert_eq!(
        loaded,
        [sources.len().to_string()],
        "the page's script did not run or counted differently: {dom}"
    );
    assert_eq!(broken, ["0"], "images that did not load: {dom}");
    // At 1400 pixels every column of every table is in view (the headers wrap).
    assert_eq!(
        attribute_values(&dom, "data-wide-tables"),
        ["0"],
        "a table is wider than a 1400-pixel window: {dom}"
    );
    let shot = out.join("page.png");
    headless(
        &browser,
        &page,
        &[
            format!("--screenshot={}", shot.display()),
            "--window-size=1280,1600".into(),
        ],
    );
    let png = image::open(&shot)
        .expect("Chromium wrote a screenshot")
        .to_rgb8();
    let distinct: std::collections::HashSet<_> = png.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 50, "the screenshot is nearly blank");
}

#[test]
fn the_compare_page_loads_every_image() {
    let out = out_dir("compare");
    run_ok(
        "compare --width 48 --height 32 --rsm 4 --interleave 2 --culling none,ellipsoid,clustered",
        &out,
    );
    // The figure, and per strategy total, indirect, heat map and FLIP map; the reference's
    // total and indirect.
    check_page(&out, 1 + 3 * 4 + 2);
}

#[test]
fn the_sweep_pages_load_every_image() {
    let out = out_dir("sweep");
    run_ok(
        "sweep --width 32 --height 24 --rsm 4 --interleave 2 --delta 1e-3,1e-2 --culling ellipsoid,sphere",
        &out,
    );
    check_page(&out, 2);
    let out = out_dir("vsgl-sweep");
    run_ok(
        "sweep --shader vsgl --vsgls 8,32 --width 16 --height 12 --rsm 4",
        &out,
    );
    check_page(&out, 1);
}
