//! `slc compare`: every culling strategy on the same G-buffer, VPLs and ξ, side by side.
//!
//! Writes one folder per strategy (images, heat map, report.json), `reference_vpl/` (every VPL
//! with p = 1, the same VPLs), `report.md` with the table, the same table for scripts as
//! `compare.json` / `compare.csv` (every setting a column), `side_by_side.svg` and
//! `index.html` ([`crate::compare_summary`]). With
//! `--shader vsgl` also `vsgl/` and `vpl_sampled/`: `--vsgls N` VSGLs and N VPLs sampled by the
//! same importance, with their own table in `report.md`.
use crate::args::{count, positive, strategies, FrameArgs, ImportanceArgs, PipelineArgs, Shader};
use crate::backend::{message, run_on, OnBackend};
use crate::compare_summary::{side_by_side, table, write_page, CompareRow, Row};
use crate::flip::flip;
use crate::heatmap::{heat_map, HeatScale};
use crate::layers_exr::write_layers;
use crate::output::{frame_files, write_frame, write_rgb8};
use crate::pdf::write_figure;
use crate::print::PrintWidth;
use crate::sampled::{shade_sampled, PASSES};
use crate::table::{write_table, SettingsColumns};
use clap::Args;
use slc_app::cpu_frames::{CpuFrames, SceneBvh};
use slc_app::limits::check_frames;
use slc_app::out_dir::OutDir;
use slc_app::progress::bar;
use slc_app::provenance::Provenance;
use slc_app::reference::{all_vpl_reference_with_bar, cpu_input};
use slc_app::repeat::repeated;
use slc_app::report::{FrameFacts, Report};
use slc_core::frame::counts::{HEAT_MAX, REPEAT, SAMPLED_LIGHTS};
use slc_core::frame::{Method, RenderSettings, Stochastic, Timings};
use slc_core::render::readback_since;
use slc_core::shader::{frame_timings, SampledLights, ShadeInput, Shader as _};
use slc_core::{Image, PreparedFrame, Renderer, Scene, Strategy};
use slc_cpu_ref::{CpuPrepared, CpuRenderer};
use std::fmt::Write;
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct CompareArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[command(flatten)]
    pub importance: ImportanceArgs,
    #[arg(long, default_value_t = 1024, value_parser = count(SAMPLED_LIGHTS),
          help = SAMPLED_LIGHTS.help("With --shader vsgl: the number of VSGLs, and of VPLs sampled at equal count"))]
    pub vsgls: u32,
    /// Output folder.
    #[arg(long, default_value = "compare")]
    pub out: PathBuf,
    // The help names every strategy (`culling_help`).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "none,sphere,enclosing-sphere,ellipsoid,clustered",
        help = crate::args::culling_help("Strategies to compare, comma separated, of")
    )]
    pub culling: Vec<String>,
    /// δ of eq. (2) (a finite number above 0).
    #[arg(long, default_value_t = 1e-3, value_parser = positive)]
    pub delta: f32,
    #[arg(long, value_parser = count(HEAT_MAX),
          help = HEAT_MAX.help("Heat-map brightness saturates at this many VPLs per pixel in every heat map (256 in the paper's figures); default: at each heat map's own maximum, which its caption gives"))]
    pub heat_max: Option<u32>,
    /// Size the figures for print: 3.5in (one column) or 7in (a page) wide, text of 8 pt or
    /// more; screen: for a browser.
    #[arg(long, value_enum, default_value_t = PrintWidth::Screen)]
    pub print_width: PrintWidth,
    /// Skip the all-VPL reference (it costs every VPL at every pixel).
    #[arg(long)]
    pub no_reference: bool,
    #[arg(long, default_value_t = 1, value_parser = count(REPEAT),
          help = REPEAT.help("Time each strategy's culling and shading this many times (after the run that measures the metrics, which is then the warm-up): the tables give median, min and max"))]
    pub repeat: u32,
}

pub fn run(args: &CompareArgs) -> Result<(), String> {
    let out = OutDir::open(&args.out)?;
    let strategies = strategies(&args.culling)?;
    out.expect(result_files(args, &strategies))?;
    let scene = args.frame.load_renderable()?;
    let base = args.pipeline.stochastic(args.delta, Strategy::None, true);
    let settings = args.frame.settings(Method::Stochastic(base), 1);
    check_frames(&scene, &planned(args, &settings))?;
    run_on(
        args.frame.backend_choice()?,
        Compare {
            args,
            scene,
            strategies,
            base,
            settings,
            out,
        },
    )
}

/// Every frame compare renders: the strategies' (and the reference's, on the same prepared
/// frame) and, with `--shader vsgl`, the sampled lights'.
fn planned(args: &CompareArgs, settings: &RenderSettings) -> Vec<RenderSettings> {
    let mut frames = vec![settings.clone()];
    if args.frame.shader == Shader::Vsgl {
        let sampling = args.importance.sampling(args.vsgls);
        frames.extend(
            SampledLights::ALL
                .iter()
                .map(|e| args.frame.settings(e.method(sampling), 1)),
        );
    }
    frames
}

/// Every file compare writes with these arguments.
fn result_files(args: &CompareArgs, strategies: &[Strategy]) -> Vec<PathBuf> {
    let mut folders: Vec<&str> = strategies.iter().map(|s| s.name()).collect();
    if !args.no_reference {
        folders.push("reference_vpl");
    }
    if args.frame.shader == Shader::Vsgl {
        folders.extend(SampledLights::ALL.iter().map(|e| e.name()));
    }
    let mut files: Vec<PathBuf> = folders.iter().flat_map(|d| frame_files(d)).collect();
    for s in strategies {
        files.extend(["heatmap.png", "flip.png"].map(|f| Path::new(s.name()).join(f)));
    }
    files.extend(
        [
            "report.md",
            "compare.json",
            "compare.csv",
            "side_by_side.svg",
            "index.html",
        ]
        .map(PathBuf::from),
    );
    files
}

struct Compare<'a> {
    args: &'a CompareArgs,
    scene: Scene,
    strategies: Vec<Strategy>,
    base: Stochastic,
    settings: RenderSettings,
    out: OutDir,
}

impl OnBackend for Compare<'_> {
    fn run<R: CpuFrames>(self, r: &R) -> Result<(), String> {
        let Compare {
            args,
            scene,
            strategies,
            base,
            settings,
            out: mut dir_out,
        } = self;
        let f = &args.frame;
        // Each frame on the backend that renders it: sampled VPLs always on the CPU
        // (`shade_sampled`), everything else on `r`.
        for planned in planned(args, &settings) {
            match planned.method {
                Method::SampledVpls(_) => CpuRenderer::default().check(&planned),
                _ => r.check(&planned),
            }
            .map_err(message)?;
        }
        let device = r.info(&settings);
        let pixels = f.width as u64 * f.height as u64;
        eprintln!(
            "preparing {} on the {} ({}x{}, RSM {}²)",
            scene.name,
            r.name(),
            f.width,
            f.height,
            f.rsm
        );
        let loaded = r.load(&scene).map_err(message)?;
        let before_prepare = r.readback_bytes();
        let p = r
            .prepare(&scene, &loaded, &settings, None, &|_| {})
            .map_err(message)?;
        let prepare_readback = readback_since(r, before_prepare);
        // The CPU's reference and unculled estimate read the backend's frame (back).
        let cpu_p = r
            .cpu_frame(&scene, &SceneBvh::default(), &p)
            .map_err(message)?;
        let cpu = cpu_input(&scene, &cpu_p, f.seed, f.visibility);
        let vpl_count = p.vpl_count().map_err(message)?;
        eprintln!("{vpl_count} VPLs");
        let cpu_device = CpuRenderer::default().info(&settings);

        let reference = (!args.no_reference)
            .then(|| all_vpl_reference_with_bar(cpu))
            .transpose()?;
        let reference_total = reference.as_ref().map(|r| p.direct().add(r));
        if let (Some(r), Some(total)) = (&reference, &reference_total) {
            let dir = "reference_vpl";
            let images = write_frame(&mut dir_out, dir, f.exposure, p.direct(), r, total)?;
            let facts = FrameFacts {
                device: &cpu_device,
                scene: &scene,
                settings: &settings,
                method: Method::VplReference,
                spp: 1,
                vpl_count,
                timings: std::slice::from_ref(p.timings()),
                gpu_timings: None,
                metrics: None,
                sampled_lights: None,
                images: &images,
                readback_bytes: None,
            };
            Report::new(&facts).write(&mut dir_out, dir)?;
        }

        // The unculled estimate with the same K, δ, ξ and filter: a strategy that misses
        // nothing equals it.
        let unculled = Stochastic {
            metrics: false,
            ..base
        }
        .shade(&CpuRenderer::default(), cpu, &|_| {})
        .map_err(message)?
        .indirect;
        let input = f.input(&scene, &loaded, &p);
        let provenance = Provenance::new(&scene);
        let mut rows = Vec::new();
        for strategy in strategies {
            let s = Stochastic { strategy, ..base };
            let bar = bar(pixels, strategy.name().to_string());
            let before_shade = r.readback_bytes();
            let out = s.shade(r, input, &|n| bar.inc(n)).map_err(message)?;
            bar.finish_and_clear();
            // The frame's reads: its preparation's and this strategy's shading's.
            let readback = readback_since(r, before_shade).map(|mut shade| {
                for (k, v) in prepare_readback.iter().flatten() {
                    *shade.entry(k.clone()).or_default() += v;
                }
                shade
            });
            let runs = match args.repeat {
                1 => vec![out.timings.clone()],
                n => {
                    let timed = Stochastic {
                        metrics: false,
                        ..s
                    };
                    repeated(n, || {
                        let run = timed.shade(r, input, &|_| {}).map_err(message)?;
                        Ok(run.timings)
                    })?
                }
            };
            let m = out.metrics.as_ref().expect("metrics were asked for");
            let total = p.direct().add(&out.indirect);
            let dir = strategy.name();
            let images = write_frame(
                &mut dir_out,
                dir,
                f.exposure,
                p.direct(),
                &out.indirect,
                &total,
            )?;
            let heat_full = HeatScale::of(args.heat_max).full_at(&m.lights_per_pixel);
            let heat = heat_map(
                f.width,
                f.height,
                &m.lights_per_pixel,
                &m.fdr_per_pixel,
                heat_full,
            );
            write_rgb8(&mut dir_out, &format!("{dir}/heatmap.png"), &heat)?;
            write_layers(&mut dir_out, dir, &images, Some(m), &provenance)?;
            let (flip_reference, flip_map) = match &reference_total {
                Some(reference) => {
                    let (mean, map) = flip(reference, &total, f.exposure);
                    write_rgb8(&mut dir_out, &format!("{dir}/flip.png"), &map)?;
                    (Some(mean), Some(map))
                }
                None => (None, None),
            };
            let (timings, gpu_timings) = frame_timings(&p, &out);
            // The frame's passes with each measured run's culling and shading.
            let frame_runs: Vec<Timings> = match args.repeat {
                1 => vec![timings],
                _ => runs
                    .iter()
                    .map(|t| {
                        let mut frame = p.timings().clone();
                        frame.merge(t);
                        frame
                    })
                    .collect(),
            };
            let facts = FrameFacts {
                device: &device,
                scene: &scene,
                settings: &settings,
                method: Method::Stochastic(s),
                spp: 1,
                vpl_count,
                timings: &frame_runs,
                gpu_timings: gpu_timings.as_ref(),
                metrics: Some(m),
                sampled_lights: None,
                images: &images,
                readback_bytes: readback.as_ref(),
            };
            Report::new(&facts).write(&mut dir_out, dir)?;
            rows.push(Row {
                strategy,
                lights_per_pixel: m.lights_per_pixel_mean,
                tp: m.true_positive_pairs,
                fp: m.false_positive_pairs,
                missed: m.missed_pairs,
                fdr: m.false_discovery_rate,
                rmse_unculled: Some(out.indirect.rmse(&unculled)),
                rmse_reference: reference.as_ref().map(|r| out.indirect.rmse(r)),
                flip_reference,
                runs,
                total,
                heat,
                heat_full,
                flip_map,
            });
            eprintln!("{strategy}: done");
        }
        let sampled = if f.shader == Shader::Vsgl {
            sampled_lights(args, &mut dir_out, r, input, cpu, reference.as_ref())?
        } else {
            String::new()
        };
        let columns =
            SettingsColumns::new(&provenance, &scene, &device, f, &args.pipeline, vpl_count);
        let table_rows: Vec<CompareRow> = rows.iter().map(|r| r.columns(args.delta)).collect();
        let tables = write_table(&mut dir_out, "compare", &provenance, &columns, &table_rows)?;
        let md = table(args, &device, &scene.name, vpl_count, &rows, &sampled);
        dir_out.write("report.md", md.as_bytes())?;
        let figure = side_by_side(args, &scene.name, &rows)?;
        write_figure(&mut dir_out, "side_by_side", &figure)?;
        write_page(&mut dir_out, &scene.name, &provenance, &rows, tables)?;
        dir_out.commit()?;
        println!("wrote {}", args.out.display());
        Ok(())
    }
}

/// Shades the prepared frame with `--vsgls` VSGLs (on the backend `r`) and as many sampled
/// VPLs (on the CPU, from `cpu`, the same frame), writes their folders, and returns their
/// section of `report.md`.
fn sampled_lights<R: Renderer>(
    args: &CompareArgs,
    dir_out: &mut OutDir,
    r: &R,
    input: ShadeInput<'_, R>,
    cpu: ShadeInput<'_, CpuRenderer>,
    reference: Option<&Image>,
) -> Result<String, String> {
    let f = &args.frame;
    let sampling = args.importance.sampling(args.vsgls);
    let mut md = format!(
        "\n## Sampled lights\n\n{} lights sampled from the RSMs by {} importance (the same \
         points for both): VSGLs at the filtered mip level (diffuse intensity {}), and VPLs of \
         single texels (unbiased). Times in ms; RMSE of the indirect image against every VPL \
         with p = 1.\n\n| estimator | distinct lights |",
        args.vsgls,
        sampling.importance.name(),
        sampling.diffuse.name()
    );
    for (_, row) in PASSES {
        let _ = write!(md, " {row} ms |");
    }
    md.push_str(" total ms | RMSE vs reference |\n|---|---|---|---|---|---|---|---|\n");
    let prepared: &CpuPrepared = cpu.prepared;
    for e in SampledLights::ALL {
        eprintln!("{}: {} lights", e.name(), args.vsgls);
        let (out, backend) = shade_sampled(e, r, input, cpu, sampling)?;
        let method = e.method(sampling);
        let settings = f.settings(method, 1);
        let device = if backend == r.name() {
            r.info(&settings)
        } else {
            CpuRenderer::default().info(&settings)
        };
        let total = prepared.direct.add(&out.indirect);
        let dir = e.name();
        let images = write_frame(
            dir_out,
            dir,
            f.exposure,
            &prepared.direct,
            &out.indirect,
            &total,
        )?;
        let (timings, _) = frame_timings(prepared, &out);
        let facts = FrameFacts {
            device: &device,
            scene: cpu.scene,
            settings: &settings,
            method,
            spp: 1,
            vpl_count: prepared.vpls.len(),
            timings: std::slice::from_ref(&timings),
            gpu_timings: None,
            metrics: None,
            sampled_lights: out.sampled_lights,
            images: &images,
            readback_bytes: None,
        };
        Report::new(&facts).write(dir_out, dir)?;
        let lights = out.sampled_lights.unwrap_or(0);
        let _ = write!(md, "| {} ({backend}) | {lights} |", e.name());
        for (pass, _) in PASSES {
            let _ = write!(md, " {:.1} |", out.timings.get(pass));
        }
        let rmse = reference.map_or("n/a".to_string(), |r| {
            format!("{:.3e}", out.indirect.rmse(r))
        });
        let _ = writeln!(md, " {:.1} | {rmse} |", out.timings.total());
    }
    Ok(md)
}
