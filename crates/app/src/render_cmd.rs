//! `slc render`.
use crate::args::{culling_name, Backend, FrameArgs, ImportanceArgs, PipelineArgs, Shader};
use crate::gpu_frame::{check_visibility, gpu_strategy, vsgl_gpu_note, GpuFrame};
use crate::output::write_frame;
use crate::progress::bar;
use crate::report::{Device, FrameFacts, Report};
use clap::{Args, ValueEnum};
use slc_core::Scene;
use slc_cpu_ref::{render, Frame, Method, RenderSettings};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Reference {
    /// Every VPL with p = 1 (no Russian roulette, no culling, no interleaving).
    Vpl,
    /// Path-traced one-bounce reference.
    Path,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[command(flatten)]
    pub importance: ImportanceArgs,
    /// With --shader vsgl: the number of VSGLs sampled from the RSMs.
    #[arg(long, default_value_t = 1024)]
    pub vsgls: u32,
    /// Output folder.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Culling strategy: none, sphere, enclosing-sphere, ellipsoid, clustered (ellipsoids in 3-D
    /// clusters), clustered-sphere, clustered-enclosing-sphere.
    #[arg(long, default_value = "ellipsoid")]
    pub culling: String,
    /// δ of eq. (2), in the units of I / l² (W sr⁻¹ m⁻²): larger culls more and adds variance.
    #[arg(long, default_value_t = 1e-3)]
    pub delta: f32,
    /// Measure culling metrics (true/false positives, misses) by brute force.
    #[arg(long)]
    pub metrics: bool,
    /// Render a reference instead of the stochastic estimate.
    #[arg(long, value_enum)]
    pub reference: Option<Reference>,
    /// Passes (path samples per pixel, or jittered VPL passes) averaged.
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
}

pub fn run(args: &RenderArgs) -> Result<(), String> {
    let scene = args.frame.load()?;
    let method = match (args.reference, args.frame.shader) {
        (Some(_), Shader::Vsgl) => {
            return Err("--reference renders every VPL or paths, not VSGLs: \
                        leave out --shader vsgl or --reference"
                .into())
        }
        (Some(Reference::Path), _) => Method::Path,
        (Some(Reference::Vpl), _) => Method::VplReference,
        (None, Shader::Vsgl) => Method::Vsgl(args.importance.sampling(args.vsgls)),
        (None, Shader::Vpl) => Method::Stochastic(args.pipeline.stochastic(
            args.delta,
            culling_name(&args.culling)?,
            args.metrics,
        )),
    };
    let settings = args.frame.settings(method, args.spp);
    let f = &args.frame;
    let (frame, gpu_timings, device) = match f.backend {
        Backend::Cpu => (render_cpu(&scene, &settings)?, None, Device::cpu()),
        Backend::Gpu => {
            if args.reference.is_some() {
                return Err("references are rendered on the CPU only; use --backend cpu".into());
            }
            check_visibility(f.visibility, f.shader == Shader::Vsgl)?;
            if f.shader == Shader::Vpl {
                gpu_strategy(&args.culling)?;
            }
            let gpu = GpuFrame::new()?;
            eprintln!("rendering {} on the GPU", scene.name);
            let (frame, gpu_timings) = gpu.render(&scene, &settings)?;
            let mut device = gpu.device(args.metrics);
            if f.shader == Shader::Vsgl {
                device.notes.push(vsgl_gpu_note(f.visibility));
            }
            (frame, gpu_timings, device)
        }
    };

    let total = frame.direct.add(&frame.indirect);
    let images = write_frame(&args.out, &frame.direct, &frame.indirect, &total)?;
    let timings = &frame.timings;
    let facts = FrameFacts {
        device: &device,
        scene: &scene,
        args: f,
        method,
        spp: args.spp,
        vpl_count: frame.vpl_count,
        timings,
        gpu_timings: gpu_timings.as_ref(),
        metrics: frame.metrics.as_ref(),
        sampled_lights: frame.sampled_lights,
        images: &images,
    };
    Report::new(&facts).write(&args.out.join("report.json"))?;
    let m = total.mean();
    let lights = match frame.sampled_lights {
        Some(n) if f.shader == Shader::Vsgl => format!("{n} VSGLs of {} samples", args.vsgls),
        _ => format!("{} VPLs", frame.vpl_count),
    };
    println!(
        "{} ({}): {}x{}, {lights}, {:.0} ms; mean total radiance ({:.4}, {:.4}, {:.4}); wrote {}",
        scene.name,
        device.adapter,
        f.width,
        f.height,
        timings.total(),
        m.x,
        m.y,
        m.z,
        args.out.display()
    );
    Ok(())
}

/// Renders on the CPU with a progress bar.
fn render_cpu(scene: &Scene, settings: &RenderSettings) -> Result<Frame, String> {
    let progress = bar(
        settings.width as u64 * settings.height as u64 * settings.spp as u64,
        format!("rendering {}", scene.name),
    );
    let frame = render(scene, settings, &|n| progress.inc(n)).map_err(|e| e.to_string())?;
    progress.finish_and_clear();
    Ok(frame)
}
