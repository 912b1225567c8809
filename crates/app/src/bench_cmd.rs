//! `slc bench`: per-pass times of the stochastic pipeline over resolutions and VPL counts, for
//! each culling strategy, in one run (so ratios are measured on the same machine state).
//! Writes `bench.csv` and `bench.md`.
use crate::args::{culling_names, Backend, FrameArgs, PipelineArgs, Shader};
use crate::gpu_frame::{check_visibility, gpu_strategy, GpuFrame, GpuPrepared};
use crate::report::Device;
use clap::Args;
use slc_cpu_ref::{prepare, shade_stochastic, Method, Stochastic, Tracer};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[arg(long, default_value = "bench")]
    pub out: PathBuf,
    /// Resolutions WxH, comma separated (overrides --width/--height).
    #[arg(long, value_delimiter = ',', default_value = "1280x720,1920x1080")]
    pub resolutions: Vec<String>,
    /// RSM resolutions per face, comma separated (overrides --rsm).
    #[arg(long, value_delimiter = ',', default_value = "128,256")]
    pub rsms: Vec<u32>,
    #[arg(long, value_delimiter = ',', default_value = "ellipsoid,sphere")]
    pub culling: Vec<String>,
    #[arg(long, default_value_t = 1e-3)]
    pub delta: f32,
    /// Timing repetitions of culling + shading; the fastest is kept.
    #[arg(long, default_value_t = 1)]
    pub repeat: u32,
}

fn parse_resolution(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("resolution '{s}' is not WxH"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|e| format!("resolution '{s}': {e}"))
    };
    Ok((p(w)?, p(h)?))
}

const PASSES: [&str; 7] = [
    "gbuffer",
    "rsm",
    "vpl_generation",
    "direct",
    "culling",
    "shading",
    "denoise",
];

pub fn run(args: &BenchArgs) -> Result<(), String> {
    if args.frame.shader == Shader::Vsgl {
        return Err(
            "slc bench times the VPL passes; the VSGL passes are timed by \
                    slc sweep --shader vsgl (vsgl_sweep.md)"
                .into(),
        );
    }
    let scene = args.frame.load_renderable()?;
    let names = culling_names(&args.culling)?;
    let resolutions = args
        .resolutions
        .iter()
        .map(|r| parse_resolution(r))
        .collect::<Result<Vec<_>, _>>()?;
    if args.repeat == 0 {
        return Err("--repeat must be at least 1".into());
    }
    let gpu = match args.frame.backend {
        Backend::Cpu => None,
        Backend::Gpu => {
            check_visibility(args.frame.visibility, false)?;
            for name in &names {
                gpu_strategy(name)?;
            }
            Some(GpuFrame::new()?)
        }
    };
    let device = gpu.as_ref().map_or_else(Device::cpu, |g| g.device(false));
    let mut csv = format!(
        "scene,width,height,rsm,vpls,culling,{},culling_plus_shading_ms\n",
        PASSES.map(|p| format!("{p}_ms")).join(",")
    );
    let mut md = format!(
        "# slc bench: {}\n\nBackend {}, adapter {}, {} rayon threads, δ = {}, K = {}, lobes {:?}, best of {} for culling + shading. Milliseconds per pass.\n\n{}| resolution | VPLs | strategy | {} | culling + shading |\n|---|---|---|{}---|\n",
        scene.name,
        device.backend,
        device.adapter,
        rayon::current_num_threads(),
        args.delta,
        args.pipeline.interleave,
        args.frame.lobes,
        args.repeat,
        device
            .notes
            .iter()
            .map(|n| format!("- {n}\n"))
            .chain((!device.notes.is_empty()).then(|| "\n".to_string()))
            .collect::<String>(),
        PASSES.join(" | "),
        "---|".repeat(PASSES.len())
    );
    // The CPU keeps one BVH for every frame; the GPU one scene upload.
    let mut tracer = gpu.is_none().then(|| Tracer::new(&scene));
    let gpu_scene = gpu.as_ref().map(|g| g.upload(&scene)).transpose()?;
    for &(w, h) in &resolutions {
        for &rsm in &args.rsms {
            let frame = FrameArgs {
                width: w,
                height: h,
                rsm,
                ..args.frame.clone()
            };
            let base = args.pipeline.stochastic(args.delta, names[0], false);
            let settings = frame.settings(Method::Stochastic(base), 1);
            settings.validate().map_err(|e| e.to_string())?;
            eprintln!("{w}x{h}, RSM {rsm}²");
            let prepared = match (&gpu, &gpu_scene) {
                (Some(g), Some(gs)) => Prepared::Gpu(g, g.prepare(&scene, gs, &settings, None)?),
                _ => Prepared::Cpu(prepare(
                    &scene,
                    &settings,
                    tracer
                        .take()
                        .expect("the tracer is returned after each frame"),
                    None,
                )),
            };
            let vpl_count = prepared.vpl_count();
            for &name in &names {
                let mut best = None;
                for _ in 0..args.repeat {
                    let s = Stochastic {
                        culling: name,
                        ..base
                    };
                    let (mut t, out, gpu_timings) = match &prepared {
                        Prepared::Gpu(g, p) => {
                            let (out, shade_gpu) = g.shade(p, &s, frame.seed)?;
                            let gpu_timings = shade_gpu.map(|t| {
                                let mut all = p.gpu_timings.clone().unwrap_or_default();
                                all.merge(&t);
                                all
                            });
                            (p.timings.clone(), out, gpu_timings)
                        }
                        Prepared::Cpu(p) => (
                            p.timings.clone(),
                            shade_stochastic(p, &s, frame.seed, frame.visibility, &|_| {})
                                .map_err(|e| e.to_string())?,
                            None,
                        ),
                    };
                    t.merge(&out.timings);
                    // The GPU's own times of its passes replace the wall clock where the
                    // adapter has timestamp queries.
                    if let Some(g) = &gpu_timings {
                        for (name, ms) in &g.0 {
                            t.0.retain(|(n, _)| n != name);
                            t.add(name, *ms);
                        }
                    }
                    let ms = |n: &str| t.0.iter().find(|(k, _)| *k == n).map_or(0.0, |(_, v)| *v);
                    let cs = ms("culling") + ms("shading");
                    if best.as_ref().is_none_or(|(b, _): &(f64, _)| cs < *b) {
                        best = Some((cs, PASSES.map(ms)));
                    }
                }
                let (cs, per_pass) = best.expect("at least one repetition");
                let _ = writeln!(
                    csv,
                    "{},{w},{h},{rsm},{vpl_count},{name},{},{cs:.3}",
                    scene.name,
                    per_pass.map(|v| format!("{v:.3}")).join(",")
                );
                let _ = writeln!(
                    md,
                    "| {w}x{h} | {vpl_count} | {name} | {} | {cs:.1} |",
                    per_pass.map(|v| format!("{v:.1}")).join(" | ")
                );
                eprintln!("  {name}: culling + shading {cs:.1} ms");
            }
            if let Prepared::Cpu(p) = prepared {
                tracer = Some(p.tracer);
            }
        }
    }
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    std::fs::write(args.out.join("bench.csv"), csv).map_err(|e| e.to_string())?;
    std::fs::write(args.out.join("bench.md"), md).map_err(|e| e.to_string())?;
    println!("wrote {}", args.out.display());
    Ok(())
}

/// A frame prepared by the backend that benchmarks it.
enum Prepared<'g> {
    Cpu(slc_cpu_ref::Prepared),
    Gpu(&'g GpuFrame, GpuPrepared),
}

impl Prepared<'_> {
    fn vpl_count(&self) -> usize {
        match self {
            Prepared::Cpu(p) => p.vpls.len(),
            Prepared::Gpu(_, p) => p.vpls.len(),
        }
    }
}
