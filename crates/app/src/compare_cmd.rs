//! `slc compare`: every culling strategy on the same G-buffer, VPLs and ξ, side by side.
//!
//! Writes one folder per strategy (images, heat map, report.json), `reference_vpl/` (every VPL
//! with p = 1, the same VPLs), `report.md` with the table, and `side_by_side.png`. With
//! `--shader vsgl` also `vsgl/` and `vpl_sampled/`: `--vsgls N` VSGLs and N VPLs sampled by the
//! same importance, with their own table in `report.md`.
use crate::args::{culling_names, Backend, FrameArgs, ImportanceArgs, PipelineArgs, Shader};
use crate::gpu_frame::{check_visibility, gpu_strategy, GpuFrame, GpuPrepared};
use crate::heatmap::heat_map;
use crate::output::write_frame;
use crate::progress::bar;
use crate::reference::{all_vpl_reference, prepare_on};
use crate::report::{Device, FrameFacts, Report};
use crate::sampled::{pass_ms, Estimator, ESTIMATORS, PASSES};
use clap::Args;
use image::RgbImage;
use slc_core::Image;
use slc_cpu_ref::{shade_stochastic, Method, Stochastic, Timings, Tracer};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct CompareArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[command(flatten)]
    pub importance: ImportanceArgs,
    /// With --shader vsgl: the number of VSGLs, and of VPLs sampled at equal count.
    #[arg(long, default_value_t = 1024)]
    pub vsgls: u32,
    /// Output folder.
    #[arg(long, default_value = "compare")]
    pub out: PathBuf,
    /// Strategies to compare, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "none,sphere,enclosing-sphere,ellipsoid,clustered"
    )]
    pub culling: Vec<String>,
    #[arg(long, default_value_t = 1e-3)]
    pub delta: f32,
    /// Heat-map brightness saturates at this many VPLs per pixel (256 in the paper's figures).
    #[arg(long, default_value_t = 256)]
    pub heat_max: u32,
    /// Skip the all-VPL reference (it costs every VPL at every pixel).
    #[arg(long)]
    pub no_reference: bool,
}

/// One strategy's row of the table.
struct Row {
    name: &'static str,
    timings: Timings,
    lights_per_pixel: f64,
    tp: u64,
    fp: u64,
    missed: u64,
    fdr: f64,
    rmse_unculled: Option<f32>,
    rmse_reference: Option<f32>,
    total: Image,
    heat: RgbImage,
}

pub fn run(args: &CompareArgs) -> Result<(), String> {
    let scene = args.frame.load_renderable()?;
    let names = culling_names(&args.culling)?;
    let f = &args.frame;
    let gpu = match f.backend {
        Backend::Cpu => None,
        Backend::Gpu => {
            check_visibility(f.visibility, false)?;
            for name in &names {
                gpu_strategy(name)?;
            }
            Some(GpuFrame::new()?)
        }
    };
    let device = gpu.as_ref().map_or_else(Device::cpu, |g| g.device(true));
    let cpu = Device::cpu();
    let base = args.pipeline.stochastic(args.delta, "none", true);
    let settings = f.settings(Method::Stochastic(base), 1);
    settings.validate().map_err(|e| e.to_string())?;
    let pixels = f.width as u64 * f.height as u64;
    eprintln!(
        "preparing {} ({}x{}, RSM {}²)",
        scene.name, f.width, f.height, f.rsm
    );
    // The GPU prepares its own frame (rasterized G-buffer, its RSMs and VPLs); the CPU's
    // reference and unculled estimate read that frame back.
    let (p, on_gpu) = prepare_on(gpu.as_ref(), &scene, &settings)?;
    eprintln!("{} VPLs", p.vpls.len());

    let reference = (!args.no_reference)
        .then(|| all_vpl_reference(&p, f.visibility))
        .transpose()?;
    if let Some(r) = &reference {
        let total = p.direct.add(r);
        let dir = args.out.join("reference_vpl");
        let images = write_frame(&dir, &p.direct, r, &total)?;
        let facts = FrameFacts {
            device: &cpu,
            scene: &scene,
            args: f,
            method: Method::VplReference,
            spp: 1,
            vpl_count: p.vpls.len(),
            timings: &p.timings,
            gpu_timings: None,
            metrics: None,
            sampled_lights: None,
            images: &images,
        };
        Report::new(&facts).write(&dir.join("report.json"))?;
    }

    // The unculled estimate with the same K, δ, ξ and filter: a strategy that misses nothing
    // equals it.
    let unculled = shade_stochastic(
        &p,
        &Stochastic {
            metrics: false,
            ..base
        },
        f.seed,
        f.visibility,
        &|_| {},
    )
    .map_err(|e| e.to_string())?
    .indirect;
    let mut rows = Vec::new();
    for name in names {
        let s = Stochastic {
            culling: name,
            ..base
        };
        let out = match &gpu {
            None => {
                let bar = bar(pixels, name.to_string());
                let out = shade_stochastic(&p, &s, f.seed, f.visibility, &|n| bar.inc(n))
                    .map_err(|e| e.to_string())?;
                bar.finish_and_clear();
                (out, None)
            }
            Some(g) => {
                let gp = on_gpu.as_ref().expect("prepared on the GPU");
                g.shade(gp, &s, f.seed)?
            }
        };
        let (out, shade_gpu_timings) = out;
        // The GPU's times of this strategy's frame: the shared preparation and its own passes.
        let gpu_timings = shade_gpu_timings.map(|t| {
            let mut all = on_gpu
                .as_ref()
                .and_then(|gp| gp.gpu_timings.clone())
                .unwrap_or_default();
            all.merge(&t);
            all
        });
        let m = out.metrics.as_ref().expect("metrics were asked for");
        let total = p.direct.add(&out.indirect);
        let dir = args.out.join(name);
        let images = write_frame(&dir, &p.direct, &out.indirect, &total)?;
        let heat = heat_map(
            f.width,
            f.height,
            &m.lights_per_pixel,
            &m.fdr_per_pixel,
            args.heat_max,
        );
        heat.save(dir.join("heatmap.png"))
            .map_err(|e| format!("{}: {e}", dir.display()))?;
        let mut timings = p.timings.clone();
        timings.merge(&out.timings);
        let facts = FrameFacts {
            device: &device,
            scene: &scene,
            args: f,
            method: Method::Stochastic(s),
            spp: 1,
            vpl_count: p.vpls.len(),
            timings: &timings,
            gpu_timings: gpu_timings.as_ref(),
            metrics: Some(m),
            sampled_lights: None,
            images: &images,
        };
        Report::new(&facts).write(&dir.join("report.json"))?;
        rows.push(Row {
            name,
            timings: out.timings,
            lights_per_pixel: m.lights_per_pixel_mean,
            tp: m.true_positive_pairs,
            fp: m.false_positive_pairs,
            missed: m.missed_pairs,
            fdr: m.false_discovery_rate,
            rmse_unculled: Some(out.indirect.rmse(&unculled)),
            rmse_reference: reference.as_ref().map(|r| out.indirect.rmse(r)),
            total,
            heat,
        });
        eprintln!("{name}: done");
    }
    let sampled = if f.shader == Shader::Vsgl {
        let on_gpu = gpu.as_ref().zip(on_gpu.as_ref());
        sampled_lights(args, &scene, &p, on_gpu, reference.as_ref())?
    } else {
        String::new()
    };
    write_table(args, &device, &scene.name, p.vpls.len(), &rows, &sampled)?;
    side_by_side(&rows)
        .save(args.out.join("side_by_side.png"))
        .map_err(|e| e.to_string())?;
    println!("wrote {}", args.out.display());
    Ok(())
}

/// Shades the prepared frame with `--vsgls` VSGLs and as many sampled VPLs, writes their
/// folders, and returns their section of `report.md`. With `gpu` (the GPU and the frame it
/// prepared, of which `p` is the read-back) the VSGLs are shaded on the GPU; the sampled VPLs
/// always on the CPU.
fn sampled_lights(
    args: &CompareArgs,
    scene: &slc_core::Scene,
    p: &slc_cpu_ref::Prepared,
    gpu: Option<(&GpuFrame, &GpuPrepared)>,
    reference: Option<&Image>,
) -> Result<String, String> {
    let f = &args.frame;
    let sampling = args.importance.sampling(args.vsgls);
    let cpu = Device::cpu();
    let gpu_device = gpu.map(|(g, _)| g.vsgl_device(false));
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
    for e in ESTIMATORS {
        eprintln!("{}: {} lights", e.name(), args.vsgls);
        let (out, device) = match (e, gpu) {
            (Estimator::Vsgl, Some((g, gp))) => (
                g.shade_vsgl(gp, &sampling, f.seed, Tracer::scene_epsilon(scene), None)?,
                gpu_device.as_ref().unwrap_or(&cpu),
            ),
            _ => (e.shade(p, &sampling, f.seed, f.visibility)?, &cpu),
        };
        let total = p.direct.add(&out.indirect);
        let dir = args.out.join(e.name());
        let images = write_frame(&dir, &p.direct, &out.indirect, &total)?;
        let mut timings = p.timings.clone();
        timings.merge(&out.timings);
        let facts = FrameFacts {
            device,
            scene,
            args: f,
            method: e.method(sampling),
            spp: 1,
            vpl_count: p.vpls.len(),
            timings: &timings,
            gpu_timings: None,
            metrics: None,
            sampled_lights: Some(out.lights),
            images: &images,
        };
        Report::new(&facts).write(&dir.join("report.json"))?;
        let _ = write!(md, "| {} ({}) | {} |", e.name(), device.backend, out.lights);
        for (pass, _) in PASSES {
            let _ = write!(md, " {:.1} |", pass_ms(&out.timings, pass));
        }
        let rmse = reference.map_or("n/a".to_string(), |r| {
            format!("{:.3e}", out.indirect.rmse(r))
        });
        let _ = writeln!(md, " {:.1} | {rmse} |", out.timings.total());
    }
    Ok(md)
}

fn write_table(
    args: &CompareArgs,
    device: &Device,
    scene: &str,
    vpls: usize,
    rows: &[Row],
    sampled: &str,
) -> Result<(), String> {
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
    let _ = writeln!(md, "| strategy | culling ms | shading ms | denoise ms | culling + shading ms | lights/pixel | true positives | false positives | missed | FDR | RMSE vs unculled | RMSE vs reference |");
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|---|---|");
    let fmt_opt = |v: Option<f32>| v.map_or("n/a".to_string(), |v| format!("{v:.3e}"));
    for r in rows {
        let (c, s, d) = (
            pass_ms(&r.timings, "culling"),
            pass_ms(&r.timings, "shading"),
            pass_ms(&r.timings, "denoise"),
        );
        let _ = writeln!(
            md,
            "| {} | {c:.1} | {s:.1} | {d:.1} | {:.1} | {:.1} | {} | {} | {} | {:.3} | {} | {} |",
            r.name,
            c + s,
            r.lights_per_pixel,
            r.tp,
            r.fp,
            r.missed,
            r.fdr,
            fmt_opt(r.rmse_unculled),
            fmt_opt(r.rmse_reference)
        );
    }
    let order: Vec<&str> = rows.iter().map(|r| r.name).collect();
    let _ = writeln!(
        md,
        "\n`side_by_side.png`, left to right: {}; totals on top, heat maps below.",
        order.join(", ")
    );
    let _ = writeln!(md, "\nHeat maps (`*/heatmap.png`): brightness = VPLs per pixel (full at {}), colour = false discovery rate from blue (0) to red (1).", args.heat_max);
    md.push_str(sampled);
    std::fs::write(args.out.join("report.md"), md).map_err(|e| e.to_string())
}

/// Totals in the top row, heat maps below, one column per strategy.
fn side_by_side(rows: &[Row]) -> RgbImage {
    let (w, h) = rows
        .first()
        .map_or((1, 1), |r| (r.total.width, r.total.height));
    let mut out = RgbImage::new(w * rows.len().max(1) as u32, 2 * h);
    for (i, r) in rows.iter().enumerate() {
        let png = crate::output::to_srgb8(&r.total);
        image::imageops::replace(&mut out, &png, (i as u32 * w) as i64, 0);
        image::imageops::replace(&mut out, &r.heat, (i as u32 * w) as i64, h as i64);
    }
    out
}
