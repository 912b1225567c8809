//! `slc sweep --shader vsgl`: error against light count for VSGLs and for VPLs sampled at equal
//! count (the VSGL paper's Fig. 9), and the per-frame cost of each pass (its Table 1).
//!
//! For each N of `--vsgls`, shades one prepared frame (same G-buffer and RSMs) with N VSGLs
//! and with the VPLs of N texels sampled by the same importance and points, and records the
//! RMSE of the indirect image against every VPL with p = 1 (root of the mean squared error over
//! `--seeds` point sets) and the fastest of `--repeat` × `--seeds` runs' pass times. Writes
//! `vsgl_sweep.csv`, `vsgl_sweep.md` (both tables) and `vsgl_sweep.svg` (RMSE against N).
//! With `--backend gpu` the frame is prepared on the GPU and the VSGLs are shaded there (with
//! imperfect shadow maps for `--visibility`); the reference and the sampled VPLs are shaded on
//! the CPU from the read-back frame.
use crate::backend::{message, run_on, OnBackend};
use crate::limits::check_memory;
use crate::out_dir::OutDir;
use crate::plot::{line_plot_svg, Series};
use crate::progress::bar;
use crate::reference::{all_vpl_reference, cpu_input};
use crate::sampled::{shade_sampled, PASSES};
use crate::sweep_cmd::SweepArgs;
use slc_core::frame::{Importance, Method, Timings};
use slc_core::shader::{SampledLights, ShadeInput};
use slc_core::{PreparedFrame, Scene};
use slc_cpu_ref::CpuFrames;
use std::fmt::Write;
use std::time::Instant;

struct Point {
    count: u32,
    estimator: SampledLights,
    lights: usize,
    /// The fastest run's pass times.
    timings: Timings,
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
    for &n in &args.vsgls {
        let settings = f.settings(Method::Vsgl(args.importance.sampling(n)), 1);
        settings.validate().map_err(|e| e.to_string())?;
        check_memory(&settings, &scene)?;
    }
    run_on(f.backend, VsglSweep { args, scene, out })
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
            .prepare(&scene, &loaded, &f.settings(Method::VplReference, 1), None)
            .map_err(message)?;
        let cpu_p = r.cpu_frame(&scene, &loaded, &p).map_err(message)?;
        let texels: usize = cpu_p
            .maps
            .iter()
            .map(|m| m.texels.iter().flatten().count())
            .sum();
        let start = Instant::now();
        let reference = all_vpl_reference(cpu_input(&scene, &cpu_p, f.seed, f.visibility))?;
        let reference_ms = start.elapsed().as_secs_f64() * 1e3;
        let runs =
            args.vsgls.len() * SampledLights::ALL.len() * (args.seeds * args.repeat) as usize;
        let progress = bar(runs as u64, "sweep".into());
        let mut points = Vec::new();
        for &count in &args.vsgls {
            let sampling = args.importance.sampling(count);
            for estimator in SampledLights::ALL {
                let (mut squared, mut best, mut lights) = (0.0f64, None::<Timings>, 0);
                for seed in f.seed..f.seed + args.seeds {
                    let on_r = ShadeInput {
                        scene: &scene,
                        loaded: &loaded,
                        prepared: &p,
                        seed,
                        visibility: f.visibility,
                    };
                    let cpu = cpu_input(&scene, &cpu_p, seed, f.visibility);
                    for repetition in 0..args.repeat {
                        let (out, _) = shade_sampled(estimator, r, on_r, cpu, sampling)?;
                        if repetition == 0 {
                            squared += f64::from(out.indirect.rmse(&reference)).powi(2);
                            lights = out.sampled_lights.unwrap_or(0);
                        }
                        if best
                            .as_ref()
                            .is_none_or(|b| out.timings.total() < b.total())
                        {
                            best = Some(out.timings);
                        }
                        progress.inc(1);
                    }
                }
                points.push(Point {
                    count,
                    estimator,
                    lights,
                    timings: best.unwrap_or_default(),
                    rmse: (squared / f64::from(args.seeds)).sqrt() as f32,
                });
            }
        }
        progress.finish_and_clear();
        let facts = SweepFacts {
            scene: &scene.name,
            texels,
            vpls: p.vpls().len(),
            reference_ms,
            vsgl_backend: r.name(),
        };
        write_outputs(args, &mut out, &facts, &points)?;
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

/// `vsgl_sweep.csv`, `.md` and `.svg`.
fn write_outputs(
    args: &SweepArgs,
    out: &mut OutDir,
    facts: &SweepFacts,
    points: &[Point],
) -> Result<(), String> {
    out.write("vsgl_sweep.csv", csv(points).as_bytes())?;
    out.write("vsgl_sweep.md", tables(args, facts, points).as_bytes())?;
    let series: Vec<Series> = SampledLights::ALL
        .iter()
        .map(|&e| Series {
            name: e.name().to_string(),
            points: points
                .iter()
                .filter(|p| p.estimator == e)
                .map(|p| (f64::from(p.count), f64::from(p.rmse)))
                .collect(),
        })
        .collect();
    let title = format!(
        "{}: RMSE vs light count ({} importance)",
        facts.scene,
        args.importance.sampling(0).importance.name()
    );
    let svg = line_plot_svg(
        &title,
        "lights N",
        "RMSE of indirect vs all VPLs",
        &series,
        true,
        true,
    );
    out.write("vsgl_sweep.svg", svg.as_bytes())
}

/// `vsgl_sweep.csv`.
fn csv(points: &[Point]) -> String {
    let mut csv = String::from("n,estimator,distinct_lights");
    for (pass, _) in PASSES {
        let _ = write!(csv, ",{pass}_ms");
    }
    csv.push_str(",total_ms,rmse_vs_all_vpl\n");
    for p in points {
        let _ = write!(csv, "{},{},{}", p.count, p.estimator.name(), p.lights);
        for (pass, _) in PASSES {
            let _ = write!(csv, ",{:.3}", p.timings.get(pass));
        }
        let _ = writeln!(csv, ",{:.3},{:.6e}", p.timings.total(), p.rmse);
    }
    csv
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
        "\n## Milliseconds per frame (fastest of {} runs), as the paper's Table 1\n",
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
