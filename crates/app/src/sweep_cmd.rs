//! `slc sweep`: the speed-versus-accuracy trade of δ for each culling strategy.
//!
//! For each strategy and δ, shades the same prepared frame (same G-buffer, VPLs and ξ) and
//! records culling + shading time and the RMSE of the indirect image against every VPL with
//! p = 1. Writes `sweep.json` / `sweep.csv`, `sweep.svg` (RMSE against time, one curve per
//! strategy), an equal-time comparison (`equal_time.md`, `equal_time.svg`) in the spirit of the
//! supplemental's Fig. 2: each strategy at the δ whose time is closest to the reference
//! strategy's median run, and `index.html` showing it all.
//! Culling and shading run on the command's backend, the reference on the CPU (from the frame
//! read back). With `--shader vsgl` it sweeps light counts instead ([`crate::vsgl_sweep`]).
use crate::args::{count, positive, strategies, FrameArgs, ImportanceArgs, PipelineArgs, Shader};
use crate::backend::{message, run_on, OnBackend};
use crate::figure::{Figure, FigureRow};
use crate::output::to_srgb8;
use crate::page::{Block, Page};
use crate::pdf::write_figure;
use crate::plot::{log_log_plot_svg, tick_label, PlotPoint, Series};
use crate::print::PrintWidth;
use crate::table::{write_table, SettingsColumns};
use clap::Args;
use serde::Serialize;
use slc_app::cpu_frames::{CpuFrames, SceneBvh};
use slc_app::limits::check_frames;
use slc_app::out_dir::OutDir;
use slc_app::progress::bar;
use slc_app::provenance::Provenance;
use slc_app::reference::{all_vpl_reference_with_bar, cpu_input};
use slc_app::repeat::{repeated, Spread};
use slc_core::frame::counts::{REPEAT, SAMPLED_LIGHTS, SEEDS};
use slc_core::frame::{Method, Stochastic};
use slc_core::shader::{ShadeInput, Shader as _};
use slc_core::{Image, PreparedFrame, Renderer, Scene, Strategy};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct SweepArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[arg(long, default_value = "sweep")]
    pub out: PathBuf,
    /// Values of δ, comma separated (each a finite number above 0).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1e-4,3e-4,1e-3,3e-3,1e-2",
        value_parser = positive
    )]
    pub delta: Vec<f32>,
    // The help names every strategy (`culling_help`).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "ellipsoid,sphere,enclosing-sphere,clustered",
        help = crate::args::culling_help(
            "Strategies, comma separated (the first is the equal-time reference), of"
        )
    )]
    pub culling: Vec<String>,
    #[arg(long, default_value_t = 1, value_parser = count(REPEAT),
          help = REPEAT.help("Timing repetitions per point, after one warm-up when more than one: the tables give the median, min and max of culling + shading (VSGL sweep: the median run's passes and the min and max of its total, over the repetitions of every seed)"))]
    pub repeat: u32,
    #[command(flatten)]
    pub importance: ImportanceArgs,
    #[arg(long, value_delimiter = ',', default_value = "256,1024,4096,16384",
          value_parser = count(SAMPLED_LIGHTS),
          help = SAMPLED_LIGHTS.help("With --shader vsgl: light counts N, comma separated (N VSGLs against N sampled VPLs)"))]
    pub vsgls: Vec<u32>,
    #[arg(long, default_value_t = 1, value_parser = count(SEEDS),
          help = SEEDS.help("With --shader vsgl: point sets (seeds seed, seed + 1, ...) whose squared errors are averaged per N"))]
    pub seeds: u32,
    /// Size the figures for print: 3.5in (one column) or 7in (a page) wide, text of 8 pt or
    /// more; screen: for a browser.
    #[arg(long, value_enum, default_value_t = PrintWidth::Screen)]
    pub print_width: PrintWidth,
}

struct Point {
    strategy: Strategy,
    delta: f32,
    /// Medians over the runs.
    culling_ms: f64,
    shading_ms: f64,
    /// Culling + shading over the runs.
    time: Spread,
    runs: usize,
    rmse: f32,
    total: Image,
}

impl Point {
    /// The median culling + shading time.
    fn time_ms(&self) -> f64 {
        self.time.median
    }
}

pub fn run(args: &SweepArgs) -> Result<(), String> {
    let out = OutDir::open(&args.out)?;
    let files: &[&str] = match args.frame.shader {
        Shader::Vsgl => &[
            "vsgl_sweep.json",
            "vsgl_sweep.csv",
            "vsgl_sweep.md",
            "vsgl_sweep.svg",
            "index.html",
        ],
        Shader::Vpl => &[
            "sweep.json",
            "sweep.csv",
            "sweep.svg",
            "equal_time.md",
            "equal_time.svg",
            "index.html",
        ],
    };
    out.expect(files)?;
    if args.frame.shader == Shader::Vsgl {
        return crate::vsgl_sweep::run(args, out);
    }
    let scene = args.frame.load_renderable()?;
    let strategies = strategies(&args.culling)?;
    if strategies.is_empty() || args.delta.is_empty() || args.repeat == 0 {
        return Err("sweep needs at least one strategy, one δ and one repetition".into());
    }
    run_on(
        args.frame.backend_choice()?,
        Sweep {
            args,
            scene,
            strategies,
            out,
        },
    )
}

struct Sweep<'a> {
    args: &'a SweepArgs,
    scene: Scene,
    strategies: Vec<Strategy>,
    out: OutDir,
}

impl OnBackend for Sweep<'_> {
    fn run<R: CpuFrames>(self, r: &R) -> Result<(), String> {
        let Sweep {
            args,
            scene,
            strategies,
            mut out,
        } = self;
        let f = &args.frame;
        let base = args
            .pipeline
            .stochastic(args.delta[0], strategies[0], false);
        let frames: Vec<_> = args
            .delta
            .iter()
            .map(|&delta| f.settings(Method::Stochastic(Stochastic { delta, ..base }), 1))
            .collect();
        check_frames(&scene, &frames)?;
        for settings in &frames {
            r.check(settings).map_err(message)?;
        }
        let settings = f.settings(Method::Stochastic(base), 1);
        let loaded = r.load(&scene).map_err(message)?;
        let p = r
            .prepare(&scene, &loaded, &settings, None, &|_| {})
            .map_err(message)?;
        let cpu_p = r
            .cpu_frame(&scene, &SceneBvh::default(), &p)
            .map_err(message)?;
        let reference =
            all_vpl_reference_with_bar(cpu_input(&scene, &cpu_p, f.seed, f.visibility))?;
        let input = f.input(&scene, &loaded, &p);
        let points = sweep(args, r, input, &strategies, base, &reference)?;
        let provenance = Provenance::new(&scene);
        let device = r.info(&settings);
        let columns = SettingsColumns::new(
            &provenance,
            &scene,
            &device,
            f,
            &args.pipeline,
            p.vpl_count().map_err(message)?,
        );
        let table = (provenance, columns);
        write_outputs(args, &mut out, &table, &scene, &strategies, &points)?;
        out.commit()?;
        println!("wrote {}", args.out.display());
        Ok(())
    }
}

/// Each strategy at each δ over `--repeat` runs (the estimate is the same in every run).
fn sweep<R: Renderer>(
    args: &SweepArgs,
    r: &R,
    input: ShadeInput<'_, R>,
    strategies: &[Strategy],
    base: Stochastic,
    reference: &Image,
) -> Result<Vec<Point>, String> {
    let mut points = Vec::new();
    // With a warm-up run before each point's measured ones when `--repeat` > 1.
    let per_point = args.repeat + u32::from(args.repeat > 1);
    let progress = bar(
        (strategies.len() * args.delta.len() * per_point as usize) as u64,
        "sweep".into(),
    );
    for &strategy in strategies {
        for &delta in &args.delta {
            let s = Stochastic {
                delta,
                strategy,
                ..base
            };
            let outs = repeated(args.repeat, || {
                let out = s.shade(r, input, &|_| {}).map_err(message)?;
                progress.inc(1);
                Ok(out)
            })?;
            let runs: Vec<_> = outs.iter().map(|o| o.timings.clone()).collect();
            let last = outs.last().expect("at least one run");
            points.push(Point {
                strategy,
                delta,
                culling_ms: Spread::of_passes(&runs, &["culling"]).median,
                shading_ms: Spread::of_passes(&runs, &["shading"]).median,
                time: Spread::of_passes(&runs, &["culling", "shading"]),
                runs: runs.len(),
                rmse: last.indirect.rmse(reference),
                total: input.prepared.direct().add(&last.indirect),
            });
        }
    }
    progress.finish_and_clear();
    Ok(points)
}

/// One point of `sweep.json` / `sweep.csv`: medians over `--repeat` runs, with the min and
/// max of culling + shading.
#[derive(Serialize)]
struct SweepRow {
    strategy: &'static str,
    delta: f32,
    runs: usize,
    culling_ms: f64,
    shading_ms: f64,
    culling_plus_shading_ms: f64,
    culling_plus_shading_ms_min: f64,
    culling_plus_shading_ms_max: f64,
    rmse_vs_all_vpl: f32,
}

/// `sweep.json`, `sweep.csv`, `sweep.svg` and the equal-time comparison.
fn write_outputs(
    args: &SweepArgs,
    out: &mut OutDir,
    table: &(Provenance, SettingsColumns),
    scene: &Scene,
    names: &[Strategy],
    points: &[Point],
) -> Result<(), String> {
    let rows: Vec<SweepRow> = points
        .iter()
        .map(|pt| SweepRow {
            strategy: pt.strategy.name(),
            delta: pt.delta,
            culling_ms: pt.culling_ms,
            shading_ms: pt.shading_ms,
            runs: pt.runs,
            culling_plus_shading_ms: pt.time.median,
            culling_plus_shading_ms_min: pt.time.min,
            culling_plus_shading_ms_max: pt.time.max,
            rmse_vs_all_vpl: pt.rmse,
        })
        .collect();
    let tables = write_table(out, "sweep", &table.0, &table.1, &rows)?;
    let series: Vec<Series> = names
        .iter()
        .map(|&n| Series {
            name: n.to_string(),
            points: points
                .iter()
                .filter(|p| p.strategy == n)
                .map(|p| PlotPoint {
                    x: p.time_ms(),
                    y: f64::from(p.rmse),
                    label: Some(format!("δ={}", tick_label(f64::from(p.delta)))),
                    x_range: (p.runs > 1).then_some((p.time.min, p.time.max)),
                })
                .collect(),
        })
        .collect();
    let spread = if args.repeat > 1 {
        format!(", bars: min–max of {} runs", args.repeat)
    } else {
        String::new()
    };
    let title = format!("{}: RMSE vs time, each point a δ{spread}", scene.name);
    let svg = log_log_plot_svg(
        &title,
        "culling + shading (ms, median)",
        "RMSE of indirect vs all VPLs",
        &series,
        &args.print_width.style(),
    )?;
    write_figure(out, "sweep", &svg)?;
    equal_time(args, out, &scene.name, names, points)?;
    // Stages `index.html`: the plot, the equal-time figure and the tables.
    Page::of_table(
        format!("slc sweep: {}", scene.name),
        &table.0,
        vec![
            Block::figure(
                out,
                "sweep",
                "RMSE of the indirect image against every VPL with p = 1, against \
                the median culling + shading time, one point per δ (labelled), \
                bars from the fastest to the slowest of --repeat runs.",
            ),
            Block::figure(
                out,
                "equal_time",
                "Each strategy at the δ whose time is closest to the first \
                strategy's median run.",
            ),
        ],
        ("sweep", "equal_time.md"),
        tables,
        Vec::new(),
    )
    .write(out)
}

/// Each strategy's run closest in time to the median run of the first strategy.
fn equal_time(
    args: &SweepArgs,
    out: &mut OutDir,
    scene: &str,
    names: &[Strategy],
    points: &[Point],
) -> Result<(), String> {
    let mut first: Vec<&Point> = points.iter().filter(|p| p.strategy == names[0]).collect();
    first.sort_by(|a, b| a.time_ms().total_cmp(&b.time_ms()));
    let target = first[first.len() / 2].time_ms();
    let picks: Vec<&Point> = names
        .iter()
        .filter_map(|&n| {
            points.iter().filter(|p| p.strategy == n).min_by(|a, b| {
                (a.time_ms() - target)
                    .abs()
                    .total_cmp(&(b.time_ms() - target).abs())
            })
        })
        .collect();
    let mut md = format!("# Equal-time comparison\n\nTarget: {target:.1} ms of culling + shading (the median run of `{}`).\n\n| strategy | δ | culling + shading ms | RMSE vs all VPLs |\n|---|---|---|---|\n", names[0]);
    for p in &picks {
        let _ = writeln!(
            md,
            "| {} | {} | {:.1} | {:.4e} |",
            p.strategy,
            p.delta,
            p.time_ms(),
            p.rmse
        );
    }
    md.push_str("\n`equal_time.svg`: the total images in this order, left to right.\n");
    out.write("equal_time.md", md.as_bytes())?;
    let totals: Vec<_> = picks
        .iter()
        .map(|p| to_srgb8(&p.total, args.frame.exposure))
        .collect();
    let figure = Figure {
        title: format!("{scene}: equal time, {target:.1} ms of culling + shading"),
        columns: picks
            .iter()
            .map(|p| {
                format!(
                    "{} at δ = {}\n{:.1} ms, RMSE {:.2e}",
                    p.strategy,
                    p.delta,
                    p.time_ms(),
                    p.rmse
                )
            })
            .collect(),
        rows: vec![FigureRow {
            label: "total".into(),
            images: totals.iter().collect(),
        }],
        heat_legend: None,
        style: args.print_width.style(),
    };
    write_figure(out, "equal_time", &figure.svg()?).map(drop)
}
