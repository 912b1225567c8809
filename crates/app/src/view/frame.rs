//! One frame of the view on the GPU renderer: the scene is uploaded once; every frame
//! prepares (G-buffer, RSMs, VPLs, direct light) and shades with the panel's method, so a
//! moved camera or light recomputes everything from the RSMs to the filter.
use crate::backend::message;
use slc_core::frame::RenderSettings;
use slc_core::{CullMetrics, Image, Renderer, Scene, Timings};
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

    /// Renders `scene` (its camera and lights as the view has them) with `settings`: the
    /// library's frame loop on the scene uploaded once ([`slc_core::render_loaded`]).
    pub fn render(&self, scene: &Scene, settings: &RenderSettings) -> Result<ViewFrame, String> {
        let start = Instant::now();
        let frame = slc_core::render_loaded(&self.gpu, scene, &self.loaded, settings, &|_| {})
            .map_err(message)?;
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
}
