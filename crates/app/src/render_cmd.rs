//! `slc render`.
use crate::output::{write_exr, write_png};
use crate::report::{Metrics, Report};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use slc_core::{load_scene, Image};
use slc_cpu_ref::{render, LobeSelection, Method, RenderSettings, VplEstimator};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    Cpu,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Culling {
    /// Every VPL at every pixel (the unculled stochastic estimate, eq. 3).
    None,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Shader {
    Vpl,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Reference {
    /// Every VPL with p = 1 (no Russian roulette).
    Vpl,
    /// Path-traced one-bounce reference.
    Path,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Lobes {
    Both,
    Diffuse,
    Glossy,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A .gltf/.glb/.obj file or a built-in scene name; none renders the built-in default.
    pub scene: Option<String>,
    /// Output folder.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    #[arg(long, default_value_t = 512)]
    pub width: u32,
    #[arg(long, default_value_t = 512)]
    pub height: u32,
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
    #[arg(long, value_enum, default_value_t = Culling::None)]
    pub culling: Culling,
    #[arg(long, value_enum, default_value_t = Shader::Vpl)]
    pub shader: Shader,
    /// δ of eq. (2), in the units of I / l² (W sr⁻¹ m⁻²): larger culls more and adds variance.
    #[arg(long, default_value_t = 1e-3)]
    pub delta: f32,
    /// Reflective-shadow-map resolution per face (a point light has six faces).
    #[arg(long, default_value_t = 32)]
    pub rsm: u32,
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Shadow rays between every VPL and pixel.
    #[arg(long)]
    pub visibility: bool,
    /// Render a reference instead of the stochastic estimate.
    #[arg(long, value_enum)]
    pub reference: Option<Reference>,
    /// Passes (path samples per pixel, or jittered VPL passes) averaged.
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
    /// Which VPL lobes to generate.
    #[arg(long, value_enum, default_value_t = Lobes::Both)]
    pub lobes: Lobes,
}

pub fn run(args: &RenderArgs) -> Result<(), String> {
    let spec = args.scene.as_deref().unwrap_or("default");
    let scene = load_scene(spec).map_err(|e| e.to_string())?;
    for w in &scene.report.warnings {
        eprintln!("warning: {w}");
    }
    let method = match args.reference {
        Some(Reference::Path) => Method::Path,
        Some(Reference::Vpl) => Method::Vpl(VplEstimator::Exact),
        None => Method::Vpl(VplEstimator::Stochastic { delta: args.delta }),
    };
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        rsm_resolution: args.rsm,
        seed: args.seed,
        method,
        visibility: args.visibility,
        spp: args.spp,
        lobes: match args.lobes {
            Lobes::Both => LobeSelection::Both,
            Lobes::Diffuse => LobeSelection::Diffuse,
            Lobes::Glossy => LobeSelection::Glossy,
        },
    };
    let bar = ProgressBar::new(args.width as u64 * args.height as u64 * args.spp as u64);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent}% ({eta} left)")
            .map_err(|e| e.to_string())?
            .progress_chars("=> "),
    );
    bar.set_message(format!("rendering {}", scene.name));
    let frame = render(&scene, &settings, &|n| bar.inc(n)).map_err(|e| e.to_string())?;
    bar.finish_and_clear();

    let total = frame.direct.add(&frame.indirect);
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("{}: cannot create folder: {e}", args.out.display()))?;
    let images: [(&'static str, &Image); 3] = [
        ("direct", &frame.direct),
        ("indirect", &frame.indirect),
        ("total", &total),
    ];
    for (name, img) in images {
        write_exr(&args.out.join(format!("{name}.exr")), img)?;
    }
    write_png(&args.out.join("total.png"), &total)?;

    let report = Report {
        scene: scene.name.clone(),
        backend: "cpu",
        adapter: format!("CPU ({} rayon threads)", rayon::current_num_threads()),
        width: args.width,
        height: args.height,
        vpl_count: frame.vpl_count,
        delta: match method {
            Method::Vpl(VplEstimator::Stochastic { delta }) => Some(delta),
            _ => None,
        },
        seed: args.seed,
        culling: "none",
        shader: "vpl",
        reference: args.reference.map(|r| match r {
            Reference::Vpl => "vpl",
            Reference::Path => "path",
        }),
        visibility: args.visibility || method == Method::Path,
        spp: args.spp,
        rsm: args.rsm,
        timings_ms: frame
            .timings_ms
            .iter()
            .map(|(k, v)| (k.to_string(), *v))
            .collect(),
        metrics: Metrics::default(),
        image_means: images
            .iter()
            .map(|(n, i)| (*n, i.mean().to_array()))
            .collect::<BTreeMap<_, _>>(),
        skipped_triangles: scene.report.skipped.total(),
        warnings: scene.report.warnings.clone(),
    };
    write_report(&args.out.join("report.json"), &report)?;
    let m = total.mean();
    let t = frame.timings_ms.last().map_or(0.0, |(_, t)| *t);
    println!(
        "{}: {}x{}, {} VPLs, {:.0} ms; mean total radiance ({:.4}, {:.4}, {:.4}); wrote {}",
        scene.name,
        args.width,
        args.height,
        frame.vpl_count,
        t,
        m.x,
        m.y,
        m.z,
        args.out.display()
    );
    Ok(())
}

fn write_report(path: &Path, report: &Report) -> Result<(), String> {
    let json = serde_json::to_string_pretty(report).map_err(|e| e.to_string())?;
    std::fs::write(path, json + "\n")
        .map_err(|e| format!("{}: cannot write report: {e}", path.display()))
}
