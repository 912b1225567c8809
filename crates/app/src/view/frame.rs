//! One frame of the view on the backend `--backend` chose: the scene is loaded once (uploaded
//! to the GPU, or its BVH built for the CPU); every frame prepares (G-buffer, RSMs, VPLs,
//! direct light) and shades with the panel's method, so a moved camera or light recomputes
//! everything from the RSMs to the filter. The window is drawn with wgpu either way: on the
//! GPU renderer's own device, or for the CPU backend on a device of its own (any adapter that
//! can present, Mesa's software ones included).
use crate::backend::message;
use slc_app::backends::Backend;
use slc_core::frame::RenderSettings;
use slc_core::{Capabilities, CullMetrics, Image, Renderer, Scene, Timings};
use slc_cpu_ref::{CpuRenderer, Tracer};
use slc_gpu_wgpu::{GpuContext, GpuLoadedScene, GpuRenderer};
use std::sync::Arc;
use std::time::Instant;

/// How a frame's pass times were measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// The GPU's timestamp queries (adapters whose timestamps are trusted).
    Timestamp,
    /// Wall clock around each pass (on the GPU with its uploads, readbacks and the wait).
    WallClock,
}

impl Clock {
    /// The label the panel and the table print.
    pub fn label(self) -> &'static str {
        match self {
            Clock::Timestamp => "timestamp",
            Clock::WallClock => "wall clock",
        }
    }
}

/// A rendered frame: its layers and what it cost.
pub struct ViewFrame {
    pub direct: Image,
    pub indirect: Image,
    /// Milliseconds per pass, measured by `clock`.
    pub timings: Timings,
    pub clock: Clock,
    /// Lights per pixel and FDR, where measured.
    pub metrics: Option<CullMetrics>,
    /// VPLs made from the RSMs.
    pub vpl_count: usize,
    /// Distinct VSGLs shaded (VSGL shader).
    pub sampled_lights: Option<usize>,
    /// Wall-clock milliseconds of the whole frame: the passes, the readbacks between them and
    /// the brute-force metrics (which the pass times leave out).
    pub render_ms: f64,
}

/// The view's renderer with the scene loaded on it, and the device the window is drawn with.
pub struct FrameRenderer {
    backend: ViewBackend,
}

enum ViewBackend {
    /// Both boxed: the GPU renderer's passes are some 900 bytes, a device's limits 300.
    Gpu {
        gpu: Box<GpuRenderer>,
        loaded: GpuLoadedScene,
    },
    Cpu {
        cpu: CpuRenderer,
        loaded: Arc<Tracer>,
        /// The display's device (the CPU renderer has none).
        display: Box<GpuContext>,
    },
}

impl FrameRenderer {
    /// Loads `scene` on `backend`; `ctx` is the display's device, which the GPU renderer
    /// renders on too.
    pub fn new(backend: Backend, ctx: GpuContext, scene: &Scene) -> Result<Self, String> {
        let backend = match backend {
            Backend::Gpu => {
                let gpu = GpuRenderer::from_context(ctx).map_err(|e| e.to_string())?;
                let loaded = gpu.load(scene).map_err(message)?;
                ViewBackend::Gpu {
                    gpu: Box::new(gpu),
                    loaded,
                }
            }
            Backend::Cpu => {
                let cpu = CpuRenderer::default();
                let loaded = cpu.load(scene).map_err(message)?;
                ViewBackend::Cpu {
                    cpu,
                    loaded,
                    display: Box::new(ctx),
                }
            }
        };
        Ok(Self { backend })
    }

    /// The device the window is drawn with (the GPU renderer's own on the GPU backend).
    pub fn context(&self) -> &GpuContext {
        match &self.backend {
            ViewBackend::Gpu { gpu, .. } => gpu.context(),
            ViewBackend::Cpu { display, .. } => display,
        }
    }

    /// Who renders, for the panel and the timing table: the renderer's adapter.
    pub fn renderer_label(&self) -> String {
        match &self.backend {
            ViewBackend::Gpu { gpu, .. } => gpu.context().adapter_name.clone(),
            ViewBackend::Cpu { .. } => {
                format!("CPU ({} rayon threads)", rayon::current_num_threads())
            }
        }
    }

    /// Whether the renderer's times are a software GPU's (they say nothing about a GPU).
    pub fn software_gpu(&self) -> bool {
        matches!(&self.backend, ViewBackend::Gpu { gpu, .. } if gpu.context().software)
    }

    /// What the renderer runs (the panel offers the strategies it has).
    pub fn capabilities(&self) -> Capabilities {
        match &self.backend {
            ViewBackend::Gpu { gpu, .. } => gpu.capabilities(),
            ViewBackend::Cpu { cpu, .. } => cpu.capabilities(),
        }
    }

    /// Renders `scene` (its camera and lights as the view has them) with `settings`: the
    /// library's frame loop on the scene loaded once ([`slc_core::render_loaded`]).
    pub fn render(&self, scene: &Scene, settings: &RenderSettings) -> Result<ViewFrame, String> {
        match &self.backend {
            ViewBackend::Gpu { gpu, loaded } => render_on(gpu.as_ref(), loaded, scene, settings),
            ViewBackend::Cpu { cpu, loaded, .. } => render_on(cpu, loaded, scene, settings),
        }
    }
}

/// One frame on `r`, timed by its timestamps where it has trusted ones, else by wall clock.
fn render_on<R: Renderer>(
    r: &R,
    loaded: &R::Scene,
    scene: &Scene,
    settings: &RenderSettings,
) -> Result<ViewFrame, String> {
    let start = Instant::now();
    let frame = slc_core::render_loaded(r, scene, loaded, settings, &|_| {}).map_err(message)?;
    let (timings, clock) = match frame.gpu_timings {
        Some(t) => (t, Clock::Timestamp),
        None => (frame.timings, Clock::WallClock),
    };
    Ok(ViewFrame {
        vpl_count: frame.vpl_count,
        direct: frame.direct,
        indirect: frame.indirect,
        timings,
        clock,
        metrics: frame.metrics,
        sampled_lights: frame.sampled_lights,
        render_ms: start.elapsed().as_secs_f64() * 1e3,
    })
}
