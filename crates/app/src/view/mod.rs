//! `slc view`: an interactive window on the GPU renderer, or with `--backend cpu` on the CPU
//! reference renderer (for machines without a GPU). A fly camera, movable lights and
//! a side panel (egui) with the render controls, overlays (heat map of lights per pixel and
//! FDR, tile grid), per-pass times and lights per pixel; screenshots (PNG) and the current
//! settings as a `.toml` scene that `slc render` accepts. The window is drawn with wgpu on
//! either backend (on a machine without a GPU, Mesa's software adapters draw it).
//!
//! For tests and scripts, `--frames N` renders N frames (with `--camera-script`, one scripted
//! input per frame), writes `--screenshot` and `--save-settings`, prints the per-pass times
//! and exits.
//!
//! Files: [`window`] runs the event loop with [`input`] and [`ui`], [`session`] holds what the
//! view shows and renders, [`camera`] and [`script`] move the view, [`controls`], [`panel`] and [`light_edit`] are the
//! side panel, [`frame`] renders on the chosen backend, [`overlay`] makes the picture, [`display`] puts it
//! in the window, [`screenshot`] and [`scene_toml`] save it.
mod camera;
mod controls;
mod display;
mod frame;
mod input;
mod light_edit;
mod overlay;
mod panel;
mod scene_toml;
mod screenshot;
mod script;
mod session;
mod ui;
mod window;

use crate::args::{
    count, stops, EstimateArgs, ImportanceArgs, Lobes, PipelineArgs, SceneSpec, Shader,
};
use clap::Args;
use controls::{Controls, Layer, Overlay};
use session::Session;
use slc_app::backends::Backend;
use slc_core::frame::counts::{Count, HEAT_MAX, HEIGHT, MAX_IMAGE_SIDE, RSM};
use std::path::PathBuf;

/// Everything that stops the view.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    #[error(
        "no display to open a window on ({0}): slc view opens X11 windows (XWayland on \
         Wayland); set DISPLAY, or run under xvfb-run (apt-get install xvfb) for --frames"
    )]
    NoDisplay(String),
    #[error(
        "no GPU adapter can draw into the window ({0}); install a Vulkan driver (on Debian: \
         apt-get install mesa-vulkan-drivers libvulkan1, whose lavapipe draws on the CPU); \
         slc view draws its window with wgpu also with --backend cpu, slc render --backend \
         cpu needs no adapter"
    )]
    NoAdapter(String),
    #[error("cannot open a window: {0}")]
    Window(String),
    #[error(transparent)]
    Gpu(#[from] slc_gpu_wgpu::GpuError),
    #[error("the window's GPU surface: {0}")]
    Surface(String),
    #[error("{0}")]
    Input(String),
    #[error("{0}")]
    Render(String),
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
}

/// The view's width: the window adds the side panel ([`window::PANEL_WIDTH`]) beside it, and
/// the window's surface is at most [`MAX_IMAGE_SIDE`] wide.
pub const VIEW_WIDTH: Count = Count::up_to(
    "the view's width (the window adds the side panel)",
    MAX_IMAGE_SIDE - window::PANEL_WIDTH,
);

/// `slc view`'s options.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// A .gltf/.glb/.obj file, a .toml scene-settings file, or a built-in scene name; none
    /// opens the built-in default (settings can be saved for scene files only).
    #[arg(value_parser = SceneSpec::parser())]
    pub scene: Option<SceneSpec>,
    #[arg(long, default_value_t = 640, value_parser = count(VIEW_WIDTH),
          help = VIEW_WIDTH.help("Width of the rendered view in pixels (the window adds the side panel)"))]
    pub width: u32,
    #[arg(long, default_value_t = 480, value_parser = count(HEIGHT),
          help = HEIGHT.help("Height of the rendered view in pixels"))]
    pub height: u32,
    /// Who renders the frames: the GPU (wgpu), or the CPU reference renderer (rayon) for
    /// machines without a GPU; the window is drawn with wgpu either way.
    #[arg(long, value_enum, default_value_t = Backend::Gpu)]
    pub backend: Backend,
    #[arg(long, value_enum, default_value_t = Shader::Vpl)]
    pub shader: Shader,
    #[arg(long, default_value_t = 64, value_parser = count(RSM),
          help = RSM.help("Reflective-shadow-map resolution per face"))]
    pub rsm: u32,
    /// Seed of ξ, interleaving and sampling.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Exposure of the picture in stops.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = stops)]
    pub exposure: f32,
    /// Which VPL lobes to generate.
    #[arg(long, value_enum, default_value_t = Lobes::Both)]
    pub lobes: Lobes,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[command(flatten)]
    pub importance: ImportanceArgs,
    #[command(flatten)]
    pub estimate: EstimateArgs,
    /// The layer shown.
    #[arg(long, value_enum, default_value_t = Layer::Total)]
    pub show: Layer,
    /// What is drawn over the picture.
    #[arg(long, value_enum, default_value_t = Overlay::None)]
    pub overlay: Overlay,
    #[arg(long, default_value_t = 256, value_parser = count(HEAT_MAX),
          help = HEAT_MAX.help("Heat-map brightness saturates at this many lights per pixel"))]
    pub heat_max: u32,
    /// Measure lights per pixel and FDR every frame (brute force on the CPU), also without
    /// the heat map.
    #[arg(long)]
    pub measure: bool,
    /// Render this many frames, save what --screenshot and --save-settings ask for, print
    /// the per-pass times and exit (for tests and scripts; works under xvfb-run).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// With --frames: save the view as the window shows it (PNG, --width x --height).
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// With --screenshot: the whole window, side panel included.
    #[arg(long, requires = "screenshot")]
    pub screenshot_window: bool,
    /// With --frames: save the final settings as a .toml scene for `slc render`.
    #[arg(long, requires = "frames")]
    pub save_settings: Option<PathBuf>,
    /// Camera input, one step per frame: w a s d q e, look:DX:DY, wheel:N, reset, - (none),
    /// each with an optional *N repeat; e.g. "w*5,look:80:0*3".
    #[arg(long)]
    pub camera_script: Option<String>,
    /// Folder of the screenshots (P) and settings (K) saved from the window.
    #[arg(long, default_value = ".")]
    pub out: PathBuf,
}

/// Runs `slc view`.
pub fn run(args: &ViewArgs) -> Result<(), String> {
    view(args).map_err(|e| e.to_string())
}

fn view(args: &ViewArgs) -> Result<(), ViewError> {
    let script = match &args.camera_script {
        Some(s) => {
            script::parse(s).map_err(|m| ViewError::Input(format!("--camera-script: {m}")))?
        }
        None => Vec::new(),
    };
    if let Some(frames) = args.frames {
        if script.len() > frames as usize {
            return Err(ViewError::Input(format!(
                "--camera-script has {} steps, more than --frames {frames}",
                script.len()
            )));
        }
    }
    let controls = Controls::from_args(args);
    controls
        .settings(args.width, args.height)
        .and_then(|s| s.validate().map_err(crate::backend::message))
        .map_err(ViewError::Input)?;
    let spec = args.scene.as_deref().unwrap_or("default");
    let scene = SceneSpec::load(args.scene.as_ref()).map_err(ViewError::Input)?;
    scene
        .validate_for_render()
        .map_err(|e| ViewError::Input(e.to_string()))?;
    let session = Session::new(args, spec, scene, controls);
    window::run(args, session, script)
}
