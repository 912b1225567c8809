//! One frame of the view on the GPU renderer: the scene is uploaded once; every frame
//! prepares (G-buffer, RSMs, VPLs, direct light) and shades with the panel's method, so a
//! moved camera or light recomputes everything from the RSMs to the filter.
use crate::backend::message;
use slc_core::frame::{merge_optional, RenderSettings};
use slc_core::render::shade_method;
use slc_core::{CullMetrics, Image, PreparedFrame, Renderer, Scene, ShadeInput, Timings};
use slc_gpu_wgpu::{GpuLoadedScene, GpuRenderer};
use std::time::Instant;

/// How a frame's pass times were measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// The GPU's timestamp queries (adapters whose timestamps are trusted).
    Timestamp,
    /// Wall clock around each pass, uploads, readbacks and the wait for the GPU included.
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

/// The GPU renderer with the view's scene on it.
pub struct FrameRenderer {
    gpu: GpuRenderer,
    loaded: GpuLoadedScene,
}

impl FrameRenderer {
    /// Uploads `scene` to `gpu`.
    pub fn new(gpu: GpuRenderer, scene: &Scene) -> Result<Self, String> {
        let loaded = gpu.load(scene).map_err(message)?;
        Ok(Self { gpu, loaded })
    }

    /// The renderer (its device and adapter).
    pub fn gpu(&self) -> &GpuRenderer {
        &self.gpu
    }

    /// Renders `scene` (its camera and lights as the view has them) with `settings`.
    pub fn render(&self, scene: &Scene, settings: &RenderSettings) -> Result<ViewFrame, String> {
        let start = Instant::now();
        settings.validate().map_err(message)?;
        self.gpu.check(settings).map_err(message)?;
        let p = self
            .gpu
            .prepare(scene, &self.loaded, settings, None)
            .map_err(message)?;
        let input = ShadeInput {
            scene,
            loaded: &self.loaded,
            prepared: &p,
            seed: settings.seed,
            visibility: settings.visibility,
        };
        let shaded = shade_method(&self.gpu, &settings.method, input, &|_| {}).map_err(message)?;
        let mut wall = p.timings().clone();
        wall.merge(&shaded.timings);
        let mut gpu = p.gpu_timings().cloned();
        merge_optional(&mut gpu, shaded.gpu_timings.as_ref());
        let (timings, clock) = match gpu {
            Some(t) => (t, Clock::Timestamp),
            None => (wall, Clock::WallClock),
        };
        Ok(ViewFrame {
            vpl_count: p.vpls().len(),
            direct: p.direct().clone(),
            indirect: shaded.indirect,
            timings,
            clock,
            metrics: shaded.metrics,
            sampled_lights: shaded.sampled_lights,
            render_ms: start.elapsed().as_secs_f64() * 1e3,
        })
    }
}
