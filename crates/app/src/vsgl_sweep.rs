//! `slc sweep --shader vsgl`: error against light count for VSGLs and for VPLs sampled at equal
//! count (the VSGL paper's Fig. 9), and the per-frame cost of each pass (its Table 1).
//!
//! For each N of `--vsgls`, shades one prepared frame (same G-buffer and RSMs) with N VSGLs
//! and with the VPLs of N texels sampled by the same importance and points, and records the
//! RMSE of the indirect image against every VPL with p = 1 (root of the mean squared error over
//! `--seeds` point sets) and the pass times of the median run of `--repeat` × `--seeds` (with the
//! min and max of its total). Writes `vsgl_sweep.json` / `vsgl_sweep.csv`, `vsgl_sweep.md`
//! (both tables), `vsgl_sweep.svg` (RMSE against N) and `index.html`.
//! With `--backend gpu` the frame is prepared on the GPU and the VSGLs are shaded there (with
//! imperfect shadow maps for `--visibility`); the reference and the sampled VPLs are shaded on
//! the CPU from the read-back frame.
use crate::args::PipelineArgs;
use crate::backend::{message, run_on, OnBackend};
use crate::page::{Block, Page};
use crate::pdf::write_figure;
use crate::plot::{log_log_plot_svg, PlotPoint, Series};
use crate::sampled::{shade_sampled, PASSES};
use crate::sweep_cmd::SweepArgs;
use crate::table::{write_table, SettingsColumns};
use serde::Serialize;
use slc_app::cpu_frames::{CpuFrames, SceneBvh};
use slc_app::limits::check_frames;
use slc_app::out_dir::OutDir;
use slc_app::progress::bar;
use slc_app::provenance::Provenance;
use slc_app::reference::{all_vpl_reference_with_bar, cpu_input};
use slc_app::repeat::{repeated, Spread};
use slc_core::frame::{Importance, LightSampling, Method, Timings};
use slc_core::shader::{SampledLights, ShadeInput};
use slc_core::{PreparedFrame, Scene};
use std::fmt::Write;
use std::time::Instant;

struct Point {
    count: u32,
    estimator: SampledLights,
    lights: usize,
    /// The pass times of the run with the median total.
    timings: Timings,
    /// The total over the runs.
    total: Spread,
    runs: usize,
    rmse: f32,
}

pub fn run(args: &SweepArgs, out: OutDir) -> Result<(), String> {
    let f = &args.frame;
    if args.vsgls.is_empty() || args.repeat == 0 || args.seeds == 0 {
        return Err(
            "sweep --shader vsgl needs at least one --vsgls count, one repetition and one seed"
                .into(),
        );
    }
    let scene = f.load_renderable()?;
    let frames: Vec<_> = args
        .vsgls
        .iter()
        .map(|&n| f.settings(Method::Vsgl(args.importance.sampling(n)), 1))
        .collect();
    check_frames(&scene, &frames)?;
    run_on(f.backend_choice()?, VsglSweep { args, scene, out })
}

struct VsglSweep<'a> {
    args: &'a SweepArgs,
    scene: Scene,
    out: OutDir,
}

impl OnBackend for VsglSweep<'_> {
    fn run<R: CpuFrames>(self, r: &R) -> Result<(), String> {
        let VsglSweep {
            args,
            scene,
            mut out,
        } = self;
        let f = &args.frame;
        for &n in &args.vsgls {
            r.check(&f.settings(Method::Vsgl(args.importance.sampling(n)), 1))
                .map_err(message)?;
        }
        let loaded = r.load(&scene).map_err(message)?;
        let p = r
            .prepare(
                &scene,
                &loaded,
                &f.settings(Method::VplReference, 1),
                None,
                &|_| {},
            )
            .map_err(message)?;
        let cpu_p = r
            .cpu_frame(&scene, &SceneBvh::default(), &p)
            .map_err(message)?;
        let texels: usize = cpu_p
            .maps
            .iter()
            .map(|m| m.texels.iter().flatten().count())
            .sum();
        let start = Instant::now();
        let reference =
            all_vpl_reference_with_bar(cpu_input(&scene, &cpu_p, f.seed, f.visibility))?;
        let reference_ms = start.elapsed().as_secs_f64() * 1e3;
        // With a warm-up run before each point's measured ones when `--repeat` > 1.
        let per_point = args.seeds * (args.repeat + u32::from(args.repeat > 1));
        let runs = args.vsgls.len() * SampledLights::ALL.len() * per_point as usize;
        let progress = bar(runs as u64, "sweep".into());
        let mut points = Vec::new();
        for &count in &args.vsgls {
            let sampling = args.importance.sampling(count);
            for estimator in SampledLights::ALL {
                let (mut squared, mut runs, mut lights) = (0.0f64, Vec::new(), 0);
                for seed in f.seed..f.seed + args.seeds {
                    let on_r = ShadeInput {
                        scene: &scene,
                        loaded: &loaded,
                        prepared: &p,
                        seed,
                        visibility: f.visibility,
                    };
                    let cpu = cpu_input(&scene, &cpu_p, seed, f.visibility);
                    let outs = repeated(args.repeat, || {
                        let (out, _) = shade_sampled(estimator, r, on_r, cpu, sampling)?;
                        progress.inc(1);
                        Ok(out)
                    })?;
                    let first = &outs[0];
                    squared += f64::from(first.indirect.rmse(&reference)).powi(2);
                    lights = first.sampled_lights.unwrap_or(0);
                    runs.extend(outs.into_iter().map(|o| o.timings));
                }
                let total = Spread::of_totals(&runs);
                // The run whose total is nearest the median (of an even count: the lower of
                // the two middle runs when they are equally near).
                runs.sort_by(|a, b| a.total().total_cmp(&b.total()));
                let median_run = (runs.len() - 1) / 2;
                points.push(Point {
                    count,
                    estimator,
                    lights,
                    total,
                    runs: runs.len(),
                    timings: runs.swap_remove(median_run),
                    rmse: (squared / f64::from(args.seeds)).sqrt() as f32,
                });
            }
        }
        progress.finish_and_clear();
        let provenance = Provenance::new(&scene);
        let settings = f.settings(Method::VplReference, 1);
        let vpl_count = p.vpl_count().map_err(message)?;
        let columns = SettingsColumns::new(
            &provenance,
            &scene,
            &r.info(&settings),
            f,
            // Sampled lights are shaded without interleaving or the filter.
            &PipelineArgs {
                interleave: 1,
                no_denoise: true,
            },
            vpl_count,
        );
        let facts = SweepFacts {
            scene: &scene.name,
            texels,
            vpls: vpl_count,
            reference_ms,
            vsgl_backend: r.name(),
        };
        let sampling = args.importance.sampling(0);
        let rows: Vec<VsglSweepRow> = points
            .iter()
            .map(|p| VsglSweepRow::of(p, sampling))
            .collect();
        let tables = write_table(&mut out, "vsgl_sweep", &provenance, &columns, &rows)?;
        write_outputs(args, &mut out, &facts, &points)?;
        // Stages `index.html`: the plot and the tables.
        Page::of_table(
            format!("slc sweep --shader vsgl: {}", scene.name),
            &provenance,
            vec![Block::figure(
                &out,
                "vsgl_sweep",
                "RMSE of the indirect image against every VPL with p = 1, against the \
                light count N: N VSGLs and N VPLs sampled by the same importance.",
            )],
            ("vsgl_sweep", "vsgl_sweep.md"),
            tables,
            Vec::new(),
        )
        .write(&mut out)?;
        out.commit()?;
        println!("wrote {}", args.out.display());
        Ok(())
    }
}

/// What the tables say about the swept frame.
struct SweepFacts<'a> {
    scene: &'a str,
    /// Lit RSM texels.
    texels: usize,
    vpls: usize,
    /// Time of the all-VPL reference.
    reference_ms: f64,
    /// Where the VSGLs were shaded.
    vsgl_backend: &'static str,
}

/// `vsgl_sweep.md` and `.svg`.
fn write_outputs(
    args: &SweepArgs,
    out: &mut OutDir,
    facts: &SweepFacts,
    points: &[Point],
) -> Result<(), String> {
    out.write("vsgl_sweep.md", tables(args, facts, points).as_bytes())?;
    let series: Vec<Series> = SampledLights::ALL
        .iter()
        .map(|&e| Series {
            name: e.name().to_string(),
            points: points
                .iter()
                .filter(|p| p.estimator == e)
                .map(|p| PlotPoint::at(f64::from(p.count), f64::from(p.rmse)))
                .collect(),
        })
        .collect();
    let title = format!(
        "{}: RMSE vs light count ({} importance)",
        facts.scene,
        args.importance.sampling(0).importance.name()
    );
    let svg = log_log_plot_svg(
        &title,
        "lights N",
        "RMSE of indirect vs all VPLs",
        &series,
        &args.print_width.style(),
    )?;
    write_figure(out, "vsgl_sweep", &svg).map(drop)
}

/// One point of `vsgl_sweep.json` / `vsgl_sweep.csv`: the pass times (ms) of the median run
/// of `--repeat` × `--seeds`, with the min and max of the total.
#[derive(Serialize)]
struct VsglSweepRow {
    n: u32,
    estimator: &'static str,
    importance: &'static str,
    /// VSGLs on the G-buffer for the bidirectional importance; empty for flux.
    camera_vsgls: Option<u32>,
    vsgl_diffuse: &'static str,
    distinct_lights: usize,
    runs: usize,
    vsgl_mip_ms: f64,
    importance_map_ms: f64,
    light_sampling_ms: f64,
    light_shading_ms: f64,
    total_ms: f64,
    total_ms_min: f64,
    total_ms_max: f64,
    rmse_vs_all_vpl: f32,
}

impl VsglSweepRow {
    fn of(p: &Point, sampling: LightSampling) -> Self {
        let [vsgl_mip_ms, importance_map_ms, light_sampling_ms, light_shading_ms] =
            PASSES.map(|(pass, _)| p.timings.get(pass));
        Self {
            n: p.count,
            estimator: p.estimator.name(),
            importance: sampling.importance.name(),
            camera_vsgls: match sampling.importance {
                Importance::Bidirectional { camera_vsgls } => Some(camera_vsgls),
                Importance::Flux => None,
            },
            vsgl_diffuse: sampling.diffuse.name(),
            distinct_lights: p.lights,
            runs: p.runs,
            vsgl_mip_ms,
            importance_map_ms,
            light_sampling_ms,
            light_shading_ms,
            total_ms: p.timings.total(),
            total_ms_min: p.total.min,
            total_ms_max: p.total.max,
            rmse_vs_all_vpl: p.rmse,
        }
    }
}

/// `vsgl_sweep.md`.
fn tables(args: &SweepArgs, facts: &SweepFacts, points: &[Point]) -> String {
    let f = &args.frame;
    let SweepFacts {
        scene,
        texels,
        vpls,
        reference_ms,
        vsgl_backend,
    } = facts;
    let find = |n: u32, e: SampledLights| points.iter().find(|p| p.count == n && p.estimator == e);
    let mut md = format!("# VSGLs against VPLs at equal count: {scene}\n\n");
    let _ = writeln!(
        md,
        "{}x{}, RSM {}² per face ({texels} lit texels, {vpls} VPLs), {} importance{}, VSGL diffuse intensity {}, visibility {}, seeds {}..{}, {} rayon threads. \
         The reference is every VPL with p = 1 ({reference_ms:.0} ms). \"VPLs\" are the VPLs of N texels sampled by the same importance \
         and the same points as the N VSGLs (unbiased, weight 1/(N p)); a sampled texel gives up to two VPLs (diffuse and glossy), \
         a VSGL two lobes. No interleaving, no denoising. VSGLs shaded on the {vsgl_backend}, the reference and sampled VPLs on the CPU.\n",
        f.width,
        f.height,
        f.rsm,
        args.importance.sampling(0).importance.name(),
        match args.importance.sampling(0).importance {
            Importance::Bidirectional { camera_vsgls } =>
                format!(" ({camera_vsgls} camera VSGLs)"),
            Importance::Flux => String::new(),
        },
        args.importance.sampling(0).diffuse.name(),
        f.visibility,
        f.seed,
        f.seed + args.seeds - 1,
        rayon::current_num_threads()
    );
    md.push_str("## RMSE of the indirect image against every VPL\n\n| N | VPLs | VSGLs | VSGL / VPL |\n|---|---|---|---|\n");
    for &n in &args.vsgls {
        if let (Some(v), Some(s)) = (find(n, SampledLights::Vpl), find(n, SampledLights::Vsgl)) {
            let _ = writeln!(
                md,
                "| {n} | {:.4e} | {:.4e} | {:.3} |",
                v.rmse,
                s.rmse,
                s.rmse / v.rmse
            );
        }
    }
    let _ = writeln!(
        md,
        "\n## Milliseconds per frame (the median run of {}), as the paper's Table 1\n",
        args.repeat * args.seeds
    );
    md.push_str("| N | estimator | distinct lights |");
    for (_, row) in PASSES {
        let _ = write!(md, " {row} |");
    }
    md.push_str(" total | VSGL overhead |\n|---|---|---|---|---|---|---|---|---|\n");
    for &n in &args.vsgls {
        let vpl_total = find(n, SampledLights::Vpl).map(|p| p.timings.total());
        for e in SampledLights::ALL {
            let Some(p) = find(n, e) else { continue };
            let _ = write!(md, "| {n} | {} | {} |", e.name(), p.lights);
            for (pass, _) in PASSES {
                let _ = write!(md, " {:.2} |", p.timings.get(pass));
            }
            let overhead = match (e, vpl_total) {
                (SampledLights::Vsgl, Some(v)) => format!("{:+.2}", p.timings.total() - v),
                _ => String::new(),
            };
            let _ = writeln!(md, " {:.2} | {overhead} |", p.timings.total());
        }
    }
    md
}
