//! The `slc` command as a user runs it: outputs, report fields and errors.
use std::path::Path;

mod common;
use common::{gpu_available, out_dir, read_exr, run, run_ok, slc};

#[test]
fn render_writes_images_and_report() {
    let out = out_dir("render");
    run_ok("render --width 24 --height 16 --rsm 4 --seed 3", &out);
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
        "\"notes\": []",
        "\"width\": 24",
        "\"height\": 16",
        "\"seed\": 3",
        "\"delta\": 0.001",
        "\"culling\": \"ellipsoid\"",
        "\"interleave\": 8",
        "\"denoise\": true",
        "\"shader\": \"vpl\"",
        "\"total\":",
        "\"false_discovery_rate\": null",
        "\"schema_version\": 5",
        "\"rustc\": \"rustc ",
        "\"build_profile\": \"release",
        "\"scene_sha256\":",
        "\"slc_version\":",
        "\"git_commit\":",
        "\"started_at\":",
        "\"cpu_threads\":",
        "\"scene_files\": []",
    ] {
        assert!(report.contains(key), "report.json lacks {key}:\n{report}");
    }
    let png = image::open(out.join("total.png")).unwrap();
    assert_eq!((png.width(), png.height()), (24, 16));
}

#[test]
fn references_are_named_in_the_report() {
    let out = out_dir("reference");
    run_ok("render --width 8 --height 8 --reference path --spp 2", &out);
    let report = std::fs::read_to_string(out.join("report.json")).unwrap();
    assert!(
        report.contains("\"reference\": \"path\"") && report.contains("\"delta\": null"),
        "{report}"
    );
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

#[test]
fn compare_writes_a_folder_per_strategy_a_table_and_heat_maps() {
    let out = out_dir("compare");
    run_ok("compare --width 32 --height 24 --rsm 4 --interleave 2 --culling none,sphere,ellipsoid,clustered --repeat 2", &out);
    for s in ["none", "sphere", "ellipsoid", "clustered"] {
        for f in [
            "total.exr",
            "total.png",
            "heatmap.png",
            "flip.png",
            "layers.exr",
            "report.json",
        ] {
            assert!(out.join(s).join(f).is_file(), "{s}/{f} missing");
        }
    }
    assert!(out.join("reference_vpl/total.exr").is_file());
    // The labelled figure: every strategy's total, heat map and FLIP map, and the legend.
    let svg = std::fs::read_to_string(out.join("side_by_side.svg")).unwrap();
    assert_eq!(
        svg.matches("<image ").count(),
        3 * 4,
        "three rows of four panels"
    );
    // Each heat map at its own frame's maximum, given under its column, and the legend says so.
    assert!(svg.contains(">ellipsoid<") && svg.contains("maximum (under its column)"));
    assert_eq!(svg.matches(">heat full at ").count(), 4);
    // The PDF beside the SVG, linked from the page.
    let pdf = std::fs::read(out.join("side_by_side.pdf")).unwrap();
    assert!(pdf.starts_with(b"%PDF-"));
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(
        html.contains("src=\"side_by_side.svg\"") && html.contains("src=\"clustered/heatmap.png\"")
    );
    assert!(html.contains("href=\"side_by_side.pdf\""));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("full at each frame's own maximum"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("compare.json")).unwrap()).unwrap();
    let table_rows = json["rows"].as_array().unwrap();
    assert_eq!(table_rows.len(), 4);
    assert!(table_rows
        .iter()
        .all(|r| r["missed"] == 0 && r["runs"] == 2));
    // FLIP against the reference: a number in [0, 1] for every strategy.
    assert!(table_rows
        .iter()
        .all(|r| (0.0..=1.0).contains(&r["flip_vs_reference"].as_f64().unwrap())));
    assert_eq!(json["settings"]["width"], 32);
    let csv = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    assert_eq!(csv.lines().count(), 5, "{csv}");
    assert!(csv
        .lines()
        .next()
        .unwrap()
        .contains(",strategy,delta,runs,culling_ms,"));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let rows: Vec<&str> = md
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| strategy"))
        .collect();
    assert_eq!(rows.len(), 4, "{md}");
    for row in rows {
        // Column 9 is "missed": a strategy that culls a contributing light is a bug.
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells[9], "0", "{row}");
    }
}

#[test]
fn sweep_writes_csv_plot_and_equal_time_comparison() {
    let out = out_dir("sweep");
    run_ok("sweep --width 32 --height 24 --rsm 4 --interleave 2 --delta 1e-3,1e-2 --culling ellipsoid,sphere --repeat 3", &out);
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 2, "{csv}");
    let header = csv.lines().next().unwrap();
    assert!(header.starts_with("scene,scene_sha256,backend,adapter,width,height,rsm,lobes,vpls,seed,interleave,denoise,visibility,threads,"), "{header}");
    assert!(
        header.ends_with(
            ",strategy,delta,runs,culling_ms,shading_ms,culling_plus_shading_ms,culling_plus_shading_ms_min,culling_plus_shading_ms_max,rmse_vs_all_vpl"
        ),
        "{header}"
    );
    let columns = header.split(',').count();
    assert!(csv
        .lines()
        .skip(1)
        .all(|l| l.split(',').count() == columns && l.contains(",32,24,4,") && !l.contains("NaN")));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["rows"].as_array().unwrap().len(), 4);
    assert_eq!(json["settings"]["interleave"], 2);
    for row in json["rows"].as_array().unwrap() {
        assert_eq!(row["runs"], 3);
        let (min, med, max) = (
            row["culling_plus_shading_ms_min"].as_f64().unwrap(),
            row["culling_plus_shading_ms"].as_f64().unwrap(),
            row["culling_plus_shading_ms_max"].as_f64().unwrap(),
        );
        assert!(min <= med && med <= max, "{row}");
    }
    let svg = std::fs::read_to_string(out.join("sweep.svg")).unwrap();
    assert!(svg.contains("ellipsoid") && svg.contains("sphere"));
    assert!(
        svg.contains("\nculling + shading (ms, median)\n")
            && svg.contains("\nRMSE of indirect vs all VPLs\n")
    );
    let figure = std::fs::read_to_string(out.join("equal_time.svg")).unwrap();
    assert_eq!(figure.matches("<image ").count(), 2);
    assert!(out.join("equal_time.md").is_file() && out.join("index.html").is_file());
}

#[test]
fn render_with_vsgls_reports_the_sampled_lights() {
    let out = out_dir("render-vsgl");
    run_ok(
        "render --shader vsgl --vsgls 32 --width 16 --height 12 --rsm 4 --seed 2",
        &out,
    );
    let report: serde_json::Value = read_report(&out);
    assert_eq!(report["shader"], "vsgl", "{report}");
    assert_eq!(report["light_samples"], 32, "{report}");
    assert_eq!(report["importance"], "flux", "{report}");
    assert_eq!(report["vsgl_diffuse"], "clamped", "{report}");
    assert!(report["camera_vsgls"].is_null() && report["delta"].is_null());
    assert!(report["culling"].is_null() && report["interleave"].is_null());
    let lights = report["sampled_lights"].as_u64().unwrap();
    assert!(lights > 0 && lights <= 32, "{report}");
    for pass in [
        "vsgl_mip",
        "importance_map",
        "light_sampling",
        "light_shading",
    ] {
        assert!(report["timings_ms"][pass].is_number(), "{pass}: {report}");
    }
    assert!(report["image_means"]["indirect"][1].as_f64().unwrap() > 0.0);
    let out2 = out_dir("render-vsgl-bidirectional");
    run_ok(
        "render --shader vsgl --vsgls 32 --vsgl-importance bidirectional --camera-vsgls 16 --vsgl-diffuse sg --width 16 --height 12 --rsm 4",
        &out2,
    );
    let report = std::fs::read_to_string(out2.join("report.json")).unwrap();
    assert!(
        report.contains("\"importance\": \"bidirectional\"")
            && report.contains("\"camera_vsgls\": 16")
            && report.contains("\"vsgl_diffuse\": \"sg\""),
        "{report}"
    );
}

#[test]
fn compare_with_vsgls_adds_vsgl_and_equal_count_vpl_folders() {
    let out = out_dir("compare-vsgl");
    run_ok("compare --shader vsgl --vsgls 24 --width 24 --height 16 --rsm 4 --interleave 2 --culling ellipsoid", &out);
    for dir in ["vsgl", "vpl_sampled"] {
        for f in ["total.exr", "total.png", "report.json"] {
            assert!(out.join(dir).join(f).is_file(), "{dir}/{f} missing");
        }
    }
    let report = std::fs::read_to_string(out.join("vsgl/report.json")).unwrap();
    assert!(report.contains("\"shader\": \"vsgl\""), "{report}");
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let section = md
        .split("## Sampled lights")
        .nth(1)
        .expect("no sampled-lights section");
    let rows: Vec<&str> = section
        .lines()
        .filter(|l| l.starts_with("| vsgl") || l.starts_with("| vpl_sampled"))
        .collect();
    assert_eq!(rows.len(), 2, "{md}");
    for row in rows {
        // The last column is the RMSE against every VPL: a number.
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let rmse: f64 = cells[cells.len() - 2].parse().unwrap_or(f64::NAN);
        assert!(rmse.is_finite() && rmse > 0.0, "{row}");
    }
}

#[test]
fn sweep_with_vsgls_writes_error_against_light_count() {
    let out = out_dir("sweep-vsgl");
    run_ok(
        "sweep --shader vsgl --vsgls 8,32 --seeds 2 --repeat 2 --width 16 --height 12 --rsm 4",
        &out,
    );
    let csv = std::fs::read_to_string(out.join("vsgl_sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 2, "{csv}");
    assert!(csv.starts_with("scene,scene_sha256,backend,"), "{csv}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("vsgl_sweep.json")).unwrap())
            .unwrap();
    for row in json["rows"].as_array().unwrap() {
        assert!(["vsgl", "vpl_sampled"].contains(&row["estimator"].as_str().unwrap()));
        let rmse = row["rmse_vs_all_vpl"].as_f64().unwrap();
        assert!(rmse.is_finite() && rmse > 0.0, "{row}");
        assert_eq!(row["runs"], 2 * 2, "two repetitions of two seeds");
        let (min, total, max) = (
            row["total_ms_min"].as_f64().unwrap(),
            row["total_ms"].as_f64().unwrap(),
            row["total_ms_max"].as_f64().unwrap(),
        );
        assert!(min <= total && total <= max, "{row}");
    }
    assert!(out.join("index.html").is_file());
    let md = std::fs::read_to_string(out.join("vsgl_sweep.md")).unwrap();
    assert!(
        md.contains("| 32 | ") && md.contains("VSGL overhead"),
        "{md}"
    );
    let svg = std::fs::read_to_string(out.join("vsgl_sweep.svg")).unwrap();
    assert!(svg.contains("vsgl") && svg.contains("vpl_sampled"));
}

#[test]
fn vsgl_options_that_do_not_fit_are_clear_errors() {
    for (args, says) in [
        ("render --shader vsgl --reference vpl", "--reference"),
        ("render --shader vsgl --lobes diffuse", "lobes"),
        (
            "render --shader vsgl --vsgl-importance bidirectional --camera-vsgls 0",
            "camera VSGLs",
        ),
        ("bench --shader vsgl", "sweep --shader vsgl"),
        (
            "render --shader vsgl --vsgls 0",
            "must be in 1..=16777216 (got 0)",
        ),
    ] {
        let o = slc()
            .args(args.split(' '))
            .args(["--width", "8", "--height", "8", "--rsm", "2", "--out"])
            .arg(out_dir("vsgl-refused"))
            .output()
            .unwrap();
        assert!(!o.status.success(), "{args}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{args}: {err}");
    }
}

#[test]
fn bench_writes_a_row_per_resolution_vpl_count_and_strategy() {
    let out = out_dir("bench");
    run_ok(
        "bench --resolutions 16x16,24x16 --rsms 2,4 --culling ellipsoid,none --interleave 2 --repeat 3",
        &out,
    );
    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 2 * 2, "{csv}");
    assert!(
        csv.lines().skip(1).any(|l| l.contains(",24,16,4,")),
        "{csv}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    assert!(json["provenance"]["command_line"].is_array());
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 8);
    for row in rows {
        let t = &row["times"];
        assert_eq!(t["runs"], 3, "{row}");
        let (min, med, max) = (
            t["culling_plus_shading_ms_min"].as_f64().unwrap(),
            t["culling_plus_shading_ms"].as_f64().unwrap(),
            t["culling_plus_shading_ms_max"].as_f64().unwrap(),
        );
        assert!(min <= med && med <= max, "{row}");
    }
    assert_eq!(rows[7]["settings"]["width"], 24);
    // The CPU counts the pairs its lists hold: the unculled lists hold the most.
    let pairs = |i: usize| rows[i]["times"]["listed_pairs"].as_u64().unwrap();
    assert!(
        pairs(7) >= pairs(6) && pairs(6) > 0,
        "none lists at least the ellipsoid's"
    );
    assert!(rows
        .iter()
        .all(|r| r["times"]["shading_mpairs_per_s"].as_f64().unwrap() > 0.0));
    // A ceiling measured before every run (each row's the median of its runs') and a share
    // of it (the median of each run's own share; checked in bench_cmd's unit test).
    for r in rows {
        let t = &r["times"];
        let ceiling = t["ceiling_mpairs_per_s"].as_f64().unwrap();
        assert!(ceiling > 0.0, "{r}");
        let share = t["ceiling_share"].as_f64().unwrap();
        assert!(share > 0.0 && share.is_finite(), "{r}");
    }
    let md = std::fs::read_to_string(out.join("bench.md")).unwrap();
    assert!(md.contains("| 24x16 |") && md.contains("measured right before every run"));
    assert!(
        md.contains("| M pairs/s | ceiling M pairs/s | of ceiling |"),
        "{md}"
    );
    // Against the VPL count: a curve per (resolution, strategy), each over both RSM sizes,
    // in the table, bench.json and both plots.
    let slopes = json["slopes"].as_array().unwrap();
    assert_eq!(slopes.len(), 4, "{slopes:?}");
    for s in slopes {
        assert_eq!(s["points"], 2, "{s}");
        assert!(s["vpls_min"].as_u64() < s["vpls_max"].as_u64(), "{s}");
        assert!(
            s["culling_plus_shading"].as_f64().unwrap().is_finite(),
            "{s}"
        );
        // Every strategy ran at both counts: the fastest at the fewest is one of their own
        // first points, so each ratio is at least its own growth, and one equals it.
        let over_fastest = s["over_fastest_at_fewest"].as_f64().unwrap();
        let growth = s["growth"].as_f64().unwrap();
        assert!(over_fastest.is_finite() && over_fastest > 0.0, "{s}");
        assert!(over_fastest >= growth * (1.0 - 1e-12), "{s}");
    }
    for resolution in ["16x16", "24x16"] {
        assert!(
            slopes.iter().any(
                |s| s["resolution"] == resolution && s["over_fastest_at_fewest"] == s["growth"]
            ),
            "{slopes:?}"
        );
    }
    assert!(md.contains("## Against the VPL count") && md.contains("| 24x16 | ellipsoid | "));
    assert!(md.contains("| over the fastest at the fewest |"), "{md}");
    for plot in ["scaling_culling.svg", "scaling_shading.svg"] {
        let svg = std::fs::read_to_string(out.join(plot)).unwrap();
        assert!(
            svg.contains("ellipsoid 16x16 (") && svg.contains("none 24x16"),
            "{plot}"
        );
        assert_eq!(svg.matches("<circle").count(), 8, "{plot}");
    }
}

/// Every strategy is checked against the backend before the first is timed: a raster
/// baseline named last on the CPU stops the bench before it runs and writes nothing.
#[test]
fn bench_refuses_a_strategy_the_backend_lacks_before_timing_any() {
    let out = out_dir("bench-refused");
    let o = run(
        "bench --resolutions 16x16 --rsms 2 --culling ellipsoid,splatting",
        &out,
    );
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--backend gpu"), "{err}");
    assert!(
        !err.contains("culling + shading"),
        "nothing was timed: {err}"
    );
    assert!(!out.join("bench.md").exists());
}

/// The `report.json` of an output folder.
fn read_report(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap()
}

/// The mean of each channel of an EXR image.
fn exr_mean(p: &std::path::Path) -> [f64; 3] {
    let px = read_exr(p);
    let n = px.len() as f64;
    px.iter().fold([0f64; 3], |m, v| {
        [0, 1, 2].map(|c| m[c] + f64::from(v[c]) / n)
    })
}

/// The channel means of `image` in the CPU's and the GPU's output folders, whose relative
/// difference is printed and held to `tolerance`.
fn assert_means_agree(
    image: &str,
    (cpu, gpu): (&Path, &Path),
    tolerance: f64,
) -> ([f64; 3], [f64; 3]) {
    let (c, g) = (exr_mean(&cpu.join(image)), exr_mean(&gpu.join(image)));
    for ch in 0..3 {
        let rel = (c[ch] - g[ch]).abs() / c[ch];
        eprintln!(
            "{image} channel {ch}: cpu {} gpu {} ({rel:.2e})",
            c[ch], g[ch]
        );
        assert!(
            rel <= tolerance,
            "{image} channel {ch}: cpu {} gpu {}",
            c[ch],
            g[ch]
        );
    }
    (c, g)
}

/// The VSGL frame the GPU and the CPU render in the VSGL agreement tests.
const VSGL_FRAME: &str =
    "render --shader vsgl --vsgls 256 --width 48 --height 32 --rsm 16 --seed 3";

#[test]
fn gpu_vsgl_render_agrees_with_the_cpu_vsgl_render() {
    /// Relative difference of the indirect images' means allowed between the GPU frame
    /// (rasterized G-buffer and RSM, VSGLs built from the RSM and shaded on the GPU) and the
    /// CPU's (ray traced, shaded on the CPU). The shading itself agrees to 1e-5 per pixel
    /// (crates/gpu-wgpu/tests/gpu/vsgl.rs); the rest is rasterization against ray tracing
    /// at 48 x 32 pixels and RSM 16² (edge texels and pixels change the importance, so the
    /// 256 samples pick partly different clusters). Measured on lavapipe, worst channel: 4.4e-3
    /// (flux) and 4.8e-3 (bidirectional, whose importance also depends on the G-buffer); with
    /// 64 samples at RSM 8² these were up to 3e-2.
    const TOLERANCE_OF_MEAN: f64 = 0.015;
    if !gpu_available() {
        return;
    }
    for importance in ["flux", "bidirectional"] {
        let (cpu, gpu) = (
            out_dir(&format!("render-vsgl-cpu-{importance}")),
            out_dir(&format!("render-vsgl-gpu-{importance}")),
        );
        for (backend, out) in [("cpu", &cpu), ("gpu", &gpu)] {
            let args = format!("{VSGL_FRAME} --vsgl-importance {importance} --backend {backend}");
            run_ok(&args, out);
        }
        let report: serde_json::Value = read_report(&gpu);
        assert_eq!(report["backend"], "gpu", "{report}");
        assert_eq!(report["shader"], "vsgl", "{report}");
        assert!(report["sampled_lights"].as_u64().unwrap() > 0, "{report}");
        assert!(
            report["notes"].to_string().contains("no visibility term"),
            "{report}"
        );
        // The VSGLs are built on the GPU: no RSM comes back.
        let by_label = &report["gpu_readback"]["by_label"];
        for label in ["rsm texels", "shadow map"] {
            assert!(by_label.get(label).is_none(), "{label}: {report}");
        }
        assert!(by_label["vsgl status"].as_u64().unwrap() > 0, "{report}");
        for pass in [
            "vsgl_mip",
            "importance_map",
            "light_sampling",
            "light_shading",
            "total",
        ] {
            assert!(report["timings_ms"][pass].is_number(), "{pass}: {report}");
        }
        eprintln!("importance {importance}:");
        assert_means_agree("indirect.exr", (&cpu, &gpu), TOLERANCE_OF_MEAN);
    }
}

#[test]
fn gpu_vsgl_render_with_visibility_uses_imperfect_shadow_maps() {
    /// Relative difference of the indirect images' means allowed between the GPU frame with
    /// visibility from imperfect shadow maps (8192 points, 64² per VSGL) and the CPU's with
    /// shadow rays, on top of rasterization against ray tracing (see
    /// `gpu_vsgl_render_agrees_with_the_cpu_vsgl_render`). Measured on lavapipe (48 x 32,
    /// RSM 8², 64 VSGLs): 1.6e-2 worst channel (the GPU 1.3-1.6 % darker); the GPU frame
    /// without visibility is 9-11 % brighter than the CPU's with it, so dropping the
    /// visibility fails.
    const TOLERANCE_OF_MEAN: f64 = 0.04;
    if !gpu_available() {
        return;
    }
    let runs = [
        ("cpu", true, out_dir("render-vsgl-vis-cpu")),
        ("gpu", true, out_dir("render-vsgl-vis-gpu")),
        ("gpu", false, out_dir("render-vsgl-novis-gpu")),
    ];
    for (backend, visibility, out) in &runs {
        let with = if *visibility { " --visibility" } else { "" };
        run_ok(&format!("{VSGL_FRAME} --backend {backend}{with}"), out);
    }
    let report: serde_json::Value = read_report(&runs[1].2);
    assert_eq!(report["backend"], "gpu", "{report}");
    assert!(
        report["notes"]
            .to_string()
            .contains("imperfect shadow maps"),
        "{report}"
    );
    assert!(report["timings_ms"]["shadow_maps"].is_number(), "{report}");
    let (_, gpu) = assert_means_agree("indirect.exr", (&runs[0].2, &runs[1].2), TOLERANCE_OF_MEAN);
    let open = exr_mean(&runs[2].2.join("indirect.exr"));
    for ch in 0..3 {
        assert!(
            gpu[ch] < open[ch],
            "channel {ch}: {} >= {}",
            gpu[ch],
            open[ch]
        );
    }
}

#[test]
fn gpu_render_agrees_with_the_cpu_render_and_names_its_adapter() {
    /// Relative difference of image means allowed between the rasterized and the ray-traced
    /// frame (48 x 32 pixels, RSM 4²: edge pixels and texels weigh heavily; measured on
    /// lavapipe: 1.4e-2 at most).
    const TOLERANCE_OF_MEAN: f64 = 0.03;
    if !gpu_available() {
        return;
    }
    let frame = [
        "render",
        "--width",
        "48",
        "--height",
        "32",
        "--rsm",
        "4",
        "--interleave",
        "2",
        "--seed",
        "5",
        "--metrics",
    ];
    let (cpu, gpu) = (out_dir("render-cpu"), out_dir("render-gpu"));
    for (backend, out) in [("cpu", &cpu), ("gpu", &gpu)] {
        let o = slc()
            .args(frame)
            .args(["--backend", backend, "--out"])
            .arg(out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    for f in [
        "direct.exr",
        "indirect.exr",
        "total.exr",
        "total.png",
        "report.json",
    ] {
        assert!(gpu.join(f).is_file(), "{f} missing");
    }
    let report: serde_json::Value = read_report(&gpu);
    assert_eq!(report["backend"], "gpu", "{report}");
    assert!(
        report["adapter"].as_str().is_some_and(|a| !a.is_empty()),
        "{report}"
    );
    assert!(
        report["notes"].as_array().is_some_and(|n| !n.is_empty()),
        "{report}"
    );
    for pass in ["culling", "shading", "denoise", "total"] {
        assert!(report["timings_ms"][pass].is_number(), "{pass}: {report}");
    }
    // Timestamp times where the adapter has them (lavapipe does), `null` and a note otherwise.
    let gpu_timings = &report["gpu_timings_ms"];
    if gpu_timings.is_null() {
        assert!(report["notes"].to_string().contains("timestamp queries"));
    } else {
        for pass in ["culling", "shading", "total"] {
            let ms = gpu_timings[pass].as_f64().unwrap_or(-1.0);
            assert!(ms > 0.0, "{pass}: {report}");
        }
    }
    // What the frame read back from the GPU, by what was read: at least the VPLs (the
    // culler's bounds pass takes them from the CPU) and both images, adding up.
    let readback = &report["gpu_readback"];
    let by_label = readback["by_label"]
        .as_object()
        .expect("gpu_readback.by_label");
    for label in ["vpls", "direct image", "indirect image"] {
        assert!(
            by_label
                .get(label)
                .and_then(|b| b.as_u64())
                .is_some_and(|b| b > 0),
            "{label}: {readback}"
        );
    }
    let sum: u64 = by_label.values().filter_map(|b| b.as_u64()).sum();
    assert_eq!(readback["total_bytes"].as_u64(), Some(sum), "{readback}");
    let cpu_report: serde_json::Value = read_report(&cpu);
    assert_eq!(cpu_report["notes"], serde_json::json!([]));
    assert!(cpu_report["gpu_timings_ms"].is_null());
    assert!(cpu_report["gpu_readback"].is_null());
    // The GPU rasterizes its own G-buffer and RSM (the per-pixel conformance of those passes
    // is in crates/gpu-wgpu/tests/gpu/raster_*.rs): here the frames must agree on average
    // and the GPU's culling must miss nothing.
    assert_eq!(report["metrics"]["missed_pairs"], 0, "{report}");
    assert!(report["metrics"]["true_positive_pairs"].as_u64().unwrap() > 0);
    for image in ["direct.exr", "indirect.exr"] {
        assert_means_agree(image, (&cpu, &gpu), TOLERANCE_OF_MEAN);
    }
}

#[test]
fn gpu_backend_refuses_what_it_lacks_and_suggests_the_cpu() {
    // `--shader vsgl --visibility` renders on the GPU (imperfect shadow maps); `compare`
    // also shades culled VPLs on the GPU, which have no visibility there.
    for (command, extra) in [
        ("render", &["--visibility"][..]),
        ("render", &["--reference", "path"]),
        ("compare", &["--shader", "vsgl", "--visibility"]),
    ] {
        let o = slc()
            .args([command, "--width", "8", "--height", "8", "--backend", "gpu"])
            .args(extra)
            .arg("--out")
            .arg(out_dir("gpu-refused"))
            .output()
            .unwrap();
        assert!(!o.status.success(), "{command} {extra:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--backend cpu"), "{command} {extra:?}: {err}");
    }
}

/// Mesa's llvmpipe (CI's adapter) ends a shader's loops after 65,535 iterations in all: there
/// a frame whose subregion holds more VPLs than a pixel's list can walk is refused by name
/// (the built-in scene's 69,213 VPLs at RSM 80 with K = 1, unculled), and one whose buffer's
/// capacity alone would be refused but whose count fits (RSM 72: 56,026 VPLs in 62,208
/// places) renders after the count is read back. An adapter without the limit renders both.
#[test]
fn gpu_frames_beyond_the_adapters_loop_limit_are_refused_by_name() {
    if !gpu_available() {
        return;
    }
    let budget = slc_gpu_wgpu::GpuContext::new().unwrap().loop_budget;
    let render = |rsm: &str| {
        let args = "render --width 8 --height 8 --backend gpu --culling none --interleave 1 \
                    --no-denoise --rsm";
        run(
            &format!("{args} {rsm}"),
            &out_dir(&format!("loop-budget-{rsm}")),
        )
    };
    let o = render("80");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.success(), budget.is_none(), "{err}");
    if budget.is_some() {
        assert!(
            err.contains("VPLs in one of the 1x1 subregions")
                && err.contains("--interleave")
                && err.contains("--backend cpu"),
            "{err}"
        );
    }
    let o = render("72");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `--gpu-tiled lists` (cull into light lists, shade in a second pass) renders the same
/// indirect image as the default one-pass frame; without `--backend gpu` it is an error.
#[test]
fn gpu_tiled_lists_render_what_one_pass_renders() {
    let o = slc()
        .args([
            "render",
            "--width",
            "8",
            "--height",
            "8",
            "--gpu-tiled",
            "lists",
        ])
        .arg("--out")
        .arg(out_dir("gpu-tiled-cpu"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--backend gpu"),
        "{err}"
    );
    if !gpu_available() {
        return;
    }
    let render = |mode: &str| {
        let out = out_dir(&format!("gpu-tiled-{mode}"));
        let o = slc()
            .args(["render", "--backend", "gpu", "--gpu-tiled", mode])
            .args([
                "--width",
                "40",
                "--height",
                "30",
                "--rsm",
                "8",
                "--culling",
                "sphere",
            ])
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(out.join("indirect.exr")).unwrap()
    };
    assert_eq!(render("one-pass"), render("lists"));
}

/// The raster baselines are the GPU's: on the CPU backend a clear error, before any work.
#[test]
fn raster_baselines_on_the_cpu_are_refused() {
    for culling in ["splatting", "clustered-raster"] {
        let o = slc()
            .args(["render", "--width", "16", "--height", "12", "--rsm", "4"])
            .args(["--culling", culling])
            .arg("--out")
            .arg(out_dir(&format!("raster-cpu-{culling}")))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{culling}: {err}");
        assert!(err.contains("rasterization baselines"), "{culling}: {err}");
    }
}

/// `binned` renders on both backends (its GPU twin: `slc_gpu_wgpu::cull::binned`).
#[test]
fn binned_renders_on_both_backends() {
    let render = |backend: &str| {
        let out = out_dir(&format!("binned-{backend}"));
        run(
            &format!("render --width 16 --height 12 --rsm 4 --backend {backend} --culling binned"),
            &out,
        )
    };
    let o = render("cpu");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    if !gpu_available() {
        return;
    }
    let o = render("gpu");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn gpu_compare_names_backend_and_adapter_and_misses_nothing() {
    if !gpu_available() {
        return;
    }
    let out = out_dir("compare-gpu");
    // Every strategy, the tight ones, binned and the raster baselines included.
    let on_gpu: Vec<_> = slc_core::Strategy::every().map(|s| s.name()).collect();
    let gpu_compare = |(width, height): (&str, &str), rsm: &str, culling: &str| {
        slc()
            .args([
                "compare",
                "--backend",
                "gpu",
                "--width",
                width,
                "--height",
                height,
            ])
            .args(["--rsm", rsm, "--interleave", "2", "--culling", culling])
            .arg("--no-reference")
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap()
    };
    let o = gpu_compare(("32", "24"), "4", &on_gpu.join(","));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("Backend gpu, adapter "), "{md}");
    let rows: Vec<&str> = md
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| strategy"))
        .collect();
    assert_eq!(rows.len(), on_gpu.len(), "{md}");
    for row in rows {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells[9], "0", "{row}");
    }
    let report = std::fs::read_to_string(out.join("ellipsoid/report.json")).unwrap();
    assert!(report.contains("\"backend\": \"gpu\""), "{report}");
}

#[test]
fn gpu_compare_shades_vsgls_on_the_gpu() {
    if !gpu_available() {
        return;
    }
    let out = out_dir("compare-gpu-vsgl");
    let o = slc()
        .args([
            "compare",
            "--backend",
            "gpu",
            "--shader",
            "vsgl",
            "--vsgls",
            "32",
            "--width",
            "32",
            "--height",
            "24",
            "--rsm",
            "8",
            "--culling",
            "ellipsoid",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("| vsgl (gpu) |"), "{md}");
    assert!(md.contains("| vpl_sampled (cpu) |"), "{md}");
    let report: serde_json::Value = read_report(&out.join("vsgl"));
    assert_eq!(report["backend"], "gpu", "{report}");
    assert!(
        report["notes"].to_string().contains("no visibility term"),
        "{report}"
    );
    let mean = report["image_means"]["indirect"].as_array().unwrap();
    assert!(mean.iter().all(|v| v.as_f64().unwrap() > 0.0), "{report}");
}

#[test]
fn gpu_sweep_shades_vsgls_on_the_gpu_with_shadow_maps() {
    if !gpu_available() {
        return;
    }
    let out = out_dir("sweep-vsgl-gpu");
    run_ok(
        "sweep --backend gpu --shader vsgl --visibility --vsgls 8,32 --seeds 1 --width 16 --height 12 --rsm 4",
        &out,
    );
    let md = std::fs::read_to_string(out.join("vsgl_sweep.md")).unwrap();
    assert!(md.contains("VSGLs shaded on the gpu"), "{md}");
    assert!(md.contains("visibility true"), "{md}");
    let csv = std::fs::read_to_string(out.join("vsgl_sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 2, "{csv}");
    for line in csv.lines().skip(1) {
        let rmse: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
        assert!(rmse.is_finite() && rmse > 0.0, "{line}");
    }
}

#[test]
fn gpu_sweep_of_the_vpl_pipeline_culls_and_shades_on_the_gpu() {
    if !gpu_available() {
        return;
    }
    // The commands are written once over the renderer API: the VPL sweep runs on the GPU too
    // (the reference on the CPU from the read-back frame).
    let out = out_dir("sweep-vpl-gpu");
    run_ok(
        "sweep --backend gpu --width 16 --height 12 --rsm 4 --interleave 2 --delta 1e-3,1e-2 --culling ellipsoid,none",
        &out,
    );
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 2, "{csv}");
    for line in csv.lines().skip(1) {
        let rmse: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
        assert!(rmse.is_finite() && rmse > 0.0, "{line}");
    }
}

#[test]
fn a_software_gpu_adapter_is_named_in_a_warning() {
    if !gpu_available() {
        return;
    }
    let software = slc_gpu_wgpu::GpuContext::new().unwrap().software;
    let out = out_dir("gpu-software");
    let o = slc()
        .args(["render", "--width", "8", "--height", "8", "--rsm", "2"])
        .args(["--backend", "gpu", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.contains("is a software rasterizer"), software, "{err}");
}

#[test]
fn exposure_brightens_the_png_previews_only() {
    let plain = out_dir("exposure-0");
    let bright = out_dir("exposure-2");
    run_ok("render --width 16 --height 12 --rsm 2", &plain);
    run_ok(
        "render --width 16 --height 12 --rsm 2 --exposure 2",
        &bright,
    );
    let mean = |d: &Path| {
        let png = image::open(d.join("total.png")).unwrap().to_rgb8();
        png.pixels().map(|p| u64::from(p.0[1])).sum::<u64>()
    };
    assert!(mean(&bright) > mean(&plain));
    assert_eq!(
        std::fs::read(plain.join("total.exr")).unwrap(),
        std::fs::read(bright.join("total.exr")).unwrap()
    );
    let o = slc()
        .args(["render", "--exposure", "nan"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("not in [-64, 64] stops"));
}

#[test]
fn render_repeat_reports_the_spread_of_each_pass() {
    let out = out_dir("render-repeat");
    run_ok("render --width 16 --height 12 --rsm 2 --repeat 3", &out);
    let r = read_report(&out);
    assert_eq!(r["timing_runs"], 3);
    let spread = &r["timings_spread_ms"];
    for pass in ["culling", "shading", "total"] {
        let s = &spread[pass];
        let (min, med, max) = (
            s["min"].as_f64().unwrap(),
            s["median"].as_f64().unwrap(),
            s["max"].as_f64().unwrap(),
        );
        assert!(min <= med && med <= max, "{pass}: {s}");
        assert_eq!(r["timings_ms"][pass].as_f64().unwrap(), med);
    }
    run_ok("render --width 16 --height 12 --rsm 2", &out);
    let r = read_report(&out);
    assert_eq!(r["timing_runs"], 1);
    assert!(r["timings_spread_ms"].is_null());
}
