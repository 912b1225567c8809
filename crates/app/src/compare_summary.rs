//! What a compare run writes to be read: `report.md` (the settings and the table),
//! `side_by_side.svg` (labelled panels of every strategy) and `index.html` (the page of the
//! whole folder).
use crate::compare_cmd::CompareArgs;
use crate::figure::{Figure, FigureRow};
use crate::heatmap::HeatScale;
use crate::output::to_srgb8;
use crate::page::{Block, Page};
use crate::table::TextTable;
use image::RgbImage;
use serde::Serialize;
use slc_app::out_dir::OutDir;
use slc_app::provenance::Provenance;
use slc_app::repeat::Spread;
use slc_core::frame::Timings;
use slc_core::shader::SampledLights;
use slc_core::{BackendInfo, Image, Strategy};
use std::fmt::Write;

/// One strategy's row of the table.
pub struct Row {
    pub strategy: Strategy,
    /// The timings of each measured run.
    pub runs: Vec<Timings>,
    pub lights_per_pixel: f64,
    pub tp: u64,
    pub fp: u64,
    pub missed: u64,
    pub fdr: f64,
    pub rmse_unculled: Option<f32>,
    pub rmse_reference: Option<f32>,
    /// Mean ꟻLIP of the total image against the reference's.
    pub flip_reference: Option<f32>,
    pub total: Image,
    pub heat: RgbImage,
    /// The lights per pixel at which `heat` is at full brightness.
    pub heat_full: u32,
    /// The ꟻLIP error map of the total against the reference's.
    pub flip_map: Option<RgbImage>,
}

/// `report.md`: the settings, the table and what the pictures show.
pub fn table(
    args: &CompareArgs,
    device: &BackendInfo,
    scene: &str,
    vpls: usize,
    rows: &[Row],
    sampled: &str,
) -> String {
    let f = &args.frame;
    let mut md = String::new();
    let _ = writeln!(md, "# slc compare: {scene}\n");
    let _ = writeln!(
        md,
        "Backend {}, adapter {}. {}x{}, {vpls} VPLs (RSM {}² per face, lobes {:?}), δ = {}, K = {}, denoise {}, seed {}, {} rayon threads.\n",
        device.backend,
        device.adapter,
        f.width,
        f.height,
        f.rsm,
        f.lobes,
        args.delta,
        args.pipeline.interleave,
        !args.pipeline.no_denoise,
        f.seed,
        rayon::current_num_threads()
    );
    let _ = writeln!(md, "Every strategy shades the same G-buffer, VPLs and ξ. \"vs unculled\" is the RMSE of the indirect image against the estimate with no culling (same K, δ, ξ and filter): 0 up to float rounding when nothing contributing was culled. \"vs reference\" is against every VPL with p = 1 (`reference_vpl/`).\n");
    for note in &device.notes {
        let _ = writeln!(md, "- {note}");
    }
    if !device.notes.is_empty() {
        let _ = writeln!(
            md,
            "- the unculled estimate and `reference_vpl/` were shaded on the CPU\n"
        );
    }
    if args.repeat > 1 {
        let _ = writeln!(
            md,
            "Times are the median (min–max) of {} runs after a warm-up.\n",
            args.repeat
        );
    }
    let _ = writeln!(md, "| strategy | culling ms | shading ms | denoise ms | culling + shading ms | lights/pixel | true positives | false positives | missed | FDR | RMSE vs unculled | RMSE vs reference | FLIP vs reference |");
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let fmt_opt = |v: Option<f32>| v.map_or("n/a".to_string(), |v| format!("{v:.3e}"));
    for r in rows {
        let time = |passes: &[&str]| Spread::of_passes(&r.runs, passes).text(r.runs.len());
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {:.1} | {} | {} | {} | {:.3} | {} | {} | {} |",
            r.strategy,
            time(&["culling"]),
            time(&["shading"]),
            time(&["denoise"]),
            time(&["culling", "shading"]),
            r.lights_per_pixel,
            r.tp,
            r.fp,
            r.missed,
            r.fdr,
            fmt_opt(r.rmse_unculled),
            fmt_opt(r.rmse_reference),
            r.flip_reference
                .map_or("n/a".to_string(), |v| format!("{v:.4}"))
        );
    }
    let order: Vec<&str> = rows.iter().map(|r| r.strategy.name()).collect();
    let _ = writeln!(
        md,
        "\n`side_by_side.svg`, left to right: {}; totals on top, heat maps below (with their legend), then the ꟻLIP maps against the reference. `index.html` shows it all.",
        order.join(", ")
    );
    let full: Vec<String> = rows
        .iter()
        .map(|r| format!("{} {}", r.strategy, r.heat_full))
        .collect();
    let _ = writeln!(md, "\nHeat maps (`*/heatmap.png`; the lights and FDR per pixel as data in `*/layers.exr`): brightness = VPLs per pixel, {} ({}), colour = false discovery rate from blue (0) to red (1).", HeatScale::of(args.heat_max).describe(), full.join(", "));
    md.push_str(sampled);
    md
}

/// One strategy's row of `compare.json` / `compare.csv`.
#[derive(Serialize)]
pub struct CompareRow {
    strategy: &'static str,
    delta: f32,
    /// Measured runs of culling and shading (`--repeat`).
    runs: usize,
    /// Medians over the runs.
    culling_ms: f64,
    shading_ms: f64,
    denoise_ms: f64,
    culling_plus_shading_ms: f64,
    culling_plus_shading_ms_min: f64,
    culling_plus_shading_ms_max: f64,
    lights_per_pixel: f64,
    true_positives: u64,
    false_positives: u64,
    missed: u64,
    false_discovery_rate: f64,
    rmse_vs_unculled: Option<f32>,
    rmse_vs_reference: Option<f32>,
    /// Mean ꟻLIP (LDR, of the sRGB previews at `--exposure`) of the total image against the
    /// reference's.
    flip_vs_reference: Option<f32>,
}

impl Row {
    pub fn columns(&self, delta: f32) -> CompareRow {
        let median = |passes: &[&str]| Spread::of_passes(&self.runs, passes).median;
        let both = Spread::of_passes(&self.runs, &["culling", "shading"]);
        CompareRow {
            strategy: self.strategy.name(),
            delta,
            runs: self.runs.len(),
            culling_ms: median(&["culling"]),
            shading_ms: median(&["shading"]),
            denoise_ms: median(&["denoise"]),
            culling_plus_shading_ms: both.median,
            culling_plus_shading_ms_min: both.min,
            culling_plus_shading_ms_max: both.max,
            lights_per_pixel: self.lights_per_pixel,
            true_positives: self.tp,
            false_positives: self.fp,
            missed: self.missed,
            false_discovery_rate: self.fdr,
            rmse_vs_unculled: self.rmse_unculled,
            rmse_vs_reference: self.rmse_reference,
            flip_vs_reference: self.flip_reference,
        }
    }
}

/// Every strategy's total, heat map and (with a reference) ꟻLIP map as labelled panels, one
/// column per strategy, with the heat-map legend.
pub fn side_by_side(args: &CompareArgs, scene: &str, rows: &[Row]) -> Result<String, String> {
    let totals: Vec<RgbImage> = rows
        .iter()
        .map(|r| to_srgb8(&r.total, args.frame.exposure))
        .collect();
    let mut figure_rows = vec![
        FigureRow {
            label: "total".into(),
            images: totals.iter().collect(),
        },
        FigureRow {
            label: "heat map".into(),
            images: rows.iter().map(|r| &r.heat).collect(),
        },
    ];
    let flips: Option<Vec<&RgbImage>> = rows.iter().map(|r| r.flip_map.as_ref()).collect();
    if let Some(images) = flips.filter(|f| !f.is_empty()) {
        figure_rows.push(FigureRow {
            label: "FLIP vs reference".into(),
            images,
        });
    }
    Figure {
        title: format!(
            "{scene}: culling strategies at δ = {}, K = {}",
            args.delta, args.pipeline.interleave
        ),
        columns: rows
            .iter()
            .map(|r| {
                format!(
                    "{}\n{:.1} lights/px, FDR {:.2}\nheat full at {}",
                    r.strategy, r.lights_per_pixel, r.fdr, r.heat_full
                )
            })
            .collect(),
        rows: figure_rows,
        heat_legend: Some(HeatScale::of(args.heat_max)),
        style: args.print_width.style(),
    }
    .svg()
}

/// Stages `index.html`: the figure, the table, each strategy's images and the data files.
pub fn write_page(
    out: &mut OutDir,
    scene: &str,
    provenance: &Provenance,
    rows: &[Row],
    tables: (TextTable, TextTable),
) -> Result<(), String> {
    let figure = Block::figure(
        out,
        "side_by_side",
        "Every strategy on the same G-buffer, VPLs and ξ: totals, heat maps \
        (brightness = VPLs per pixel, hue = false discovery rate) and ꟻLIP maps.",
    );
    let mut galleries = Vec::new();
    // Every folder compare may write; those this run did not write show nothing.
    let dirs = rows
        .iter()
        .map(|r| r.strategy.name())
        .chain(["reference_vpl"])
        .chain(SampledLights::ALL.map(|e| e.name()));
    for dir in dirs {
        let shown: Vec<(String, String)> = [
            ("total.png", "total"),
            ("indirect.png", "indirect"),
            ("heatmap.png", "lights per pixel × FDR"),
            ("flip.png", "ꟻLIP vs reference"),
        ]
        .into_iter()
        .map(|(file, caption)| (format!("{dir}/{file}"), format!("{dir}: {caption}")))
        .filter(|(file, _)| out.has(file))
        .collect();
        if shown.is_empty() {
            continue;
        }
        galleries.push(Block::Heading(dir.to_string()));
        galleries.push(Block::Gallery(shown));
        let data = ["layers.exr", "total.exr", "report.json"]
            .into_iter()
            .map(|f| format!("{dir}/{f}"))
            .filter(|f| out.has(f))
            .collect();
        galleries.push(Block::Links(data));
    }
    Page::of_table(
        format!("slc compare: {scene}"),
        provenance,
        vec![figure],
        ("compare", "report.md"),
        tables,
        galleries,
    )
    .write(out)
}
