//! `slc render`.
use crate::args::{count, EstimateArgs, FrameArgs, ImportanceArgs, PipelineArgs, Shader};
use crate::backend::{message, run_on, OnBackend};
use crate::layers_exr::write_layers;
use crate::output::{frame_files, write_frame};
use clap::{Args, ValueEnum};
use slc_app::cpu_frames::CpuFrames;
use slc_app::limits::check_frames;
use slc_app::out_dir::OutDir;
use slc_app::progress::bar;
use slc_app::provenance::Provenance;
use slc_app::repeat::{repeated, Spread};
use slc_app::report::{FrameFacts, Report};
use slc_core::frame::counts::{REPEAT, SPP};
use slc_core::frame::{Method, RenderSettings};
use slc_core::Scene;
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
    #[command(flatten)]
    pub estimate: EstimateArgs,
    /// Output folder.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Measure culling metrics (true/false positives, misses) by brute force.
    #[arg(long)]
    pub metrics: bool,
    /// Render a reference instead of the stochastic estimate.
    #[arg(long, value_enum)]
    pub reference: Option<Reference>,
    #[arg(long, default_value_t = 1, value_parser = count(SPP),
          help = SPP.help("Passes (path samples per pixel, or jittered VPL passes) averaged"))]
    pub spp: u32,
    #[arg(long, default_value_t = 1, value_parser = count(REPEAT),
          help = REPEAT.help("Render this many times after a warm-up (when more than one): report.json gives each pass's median, min and max (`timings_spread_ms`); the images are the last run's"))]
    pub repeat: u32,
}

pub fn run(args: &RenderArgs) -> Result<(), String> {
    let out = OutDir::open(&args.out)?;
    out.expect(frame_files(""))?;
    let scene = args.frame.load()?;
    let method = match (args.reference, args.frame.shader) {
        (Some(_), Shader::Vsgl) => {
            return Err("--reference renders every VPL or paths, not VSGLs: \
                        leave out --shader vsgl or --reference"
                .into())
        }
        (Some(Reference::Path), _) => Method::Path,
        (Some(Reference::Vpl), _) => Method::VplReference,
        (None, shader) => {
            args.estimate
                .method(shader, &args.pipeline, &args.importance, args.metrics)?
        }
    };
    let settings = args.frame.settings(method, args.spp);
    check_frames(&scene, std::slice::from_ref(&settings))?;
    run_on(
        args.frame.backend_choice()?,
        Render {
            args,
            scene,
            settings,
            out,
        },
    )
}

/// The warning for a stochastic estimate whose indirect image is black because δ culled every
/// pair: a frame with VPLs whose indirect image is zero everywhere, while a small probe of it
/// (at most 64 x 64 pixels and an RSM of 32², one pass) with every pair kept (δ at the least
/// positive f32, so p = 1) is not black. (A scene whose VPLs light nothing the camera sees is
/// black either way, and gets no warning.)
fn culled_everything<R: CpuFrames>(
    r: &R,
    scene: &Scene,
    settings: &RenderSettings,
    frame: &slc_core::frame::RenderedFrame,
) -> Result<Option<String>, String> {
    let Method::Stochastic(s) = settings.method else {
        return Ok(None);
    };
    let black = |image: &slc_core::Image| image.pixels.iter().all(|p| *p == glam::Vec3::ZERO);
    if frame.vpl_count == 0 || !black(&frame.indirect) {
        return Ok(None);
    }
    let probe = RenderSettings {
        width: settings.width.min(64),
        height: settings.height.min(64),
        rsm_resolution: settings.rsm_resolution.min(32),
        method: Method::Stochastic(slc_core::frame::Stochastic {
            delta: f32::MIN_POSITIVE,
            metrics: false,
            ..s
        }),
        spp: 1,
        ..settings.clone()
    };
    let probe = slc_core::render(r, scene, &probe, &|_| {}).map_err(message)?;
    Ok((!black(&probe.indirect)).then(|| {
        format!(
            "the indirect image is black: δ = {:e} culls every pair (no pair's p = I/(δ l²) of eq. 2 reaches its ξ), while the same frame with every pair kept is lit; lower --delta (the default is 1e-3)",
            s.delta
        )
    }))
}

struct Render<'a> {
    args: &'a RenderArgs,
    scene: Scene,
    settings: RenderSettings,
    out: OutDir,
}

impl OnBackend for Render<'_> {
    fn run<R: CpuFrames>(self, r: &R) -> Result<(), String> {
        let Render {
            args,
            scene,
            settings,
            mut out,
        } = self;
        let f = &args.frame;
        let runs = args.repeat.max(1) + u32::from(args.repeat > 1);
        let progress = bar(
            settings.width as u64 * settings.height as u64 * settings.spp as u64 * runs as u64,
            format!("rendering {} on the {}", scene.name, r.name()),
        );
        // Only the last frame is kept (earlier runs give their timings).
        let mut last = None;
        let runs = repeated(args.repeat, || {
            let frame =
                slc_core::render(r, &scene, &settings, &|n| progress.inc(n)).map_err(message)?;
            let timings = frame.timings.clone();
            last = Some(frame);
            Ok(timings)
        })?;
        progress.finish_and_clear();
        let frame = last.expect("at least one run");
        let device = r.info(&settings);
        let total = frame.total();
        let images = write_frame(
            &mut out,
            "",
            f.exposure,
            &frame.direct,
            &frame.indirect,
            &total,
        )?;
        let provenance = Provenance::new(&scene);
        write_layers(&mut out, "", &images, frame.metrics.as_ref(), &provenance)?;
        let facts = FrameFacts {
            device: &device,
            scene: &scene,
            settings: &settings,
            method: settings.method,
            spp: args.spp,
            vpl_count: frame.vpl_count,
            timings: &runs,
            gpu_timings: frame.gpu_timings.as_ref(),
            metrics: frame.metrics.as_ref(),
            sampled_lights: frame.sampled_lights,
            images: &images,
            readback_bytes: frame.readback_bytes.as_ref(),
        };
        let mut report = Report::new(&facts);
        if let Some(w) = culled_everything(r, &scene, &settings, &frame)? {
            eprintln!("warning: {w}");
            report.warnings.push(w);
        }
        report.write(&mut out, "")?;
        out.commit()?;
        let m = total.mean();
        let lights = match frame.sampled_lights {
            Some(n) if f.shader == Shader::Vsgl => {
                format!("{n} VSGLs of {} samples", args.estimate.vsgls)
            }
            _ => format!("{} VPLs", frame.vpl_count),
        };
        println!(
            "{} ({}): {}x{}, {lights}, {:.0} ms; mean total radiance ({:.4}, {:.4}, {:.4}); wrote {}",
            scene.name,
            device.adapter,
            f.width,
            f.height,
            Spread::of_totals(&runs).median,
            m.x,
            m.y,
            m.z,
            args.out.display()
        );
        Ok(())
    }
}
