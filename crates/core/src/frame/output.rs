//! What rendering returns: a whole frame, or the indirect light of one shader.
use super::timings::Timings;
use crate::culling::CullMetrics;
use crate::framebuffer::Image;
use std::collections::BTreeMap;

/// The indirect light one shader made from a prepared frame, with what it cost.
#[derive(Clone, Debug)]
pub struct Shaded {
    pub indirect: Image,
    /// Wall-clock milliseconds of the shader's passes.
    pub timings: Timings,
    /// The GPU's timestamp times of the same passes, where the adapter has trustworthy ones.
    pub gpu_timings: Option<Timings>,
    /// Culling metrics, when the stochastic shader was asked for them.
    pub metrics: Option<CullMetrics>,
    /// Distinct sampled lights shaded (VSGL and sampled-VPL shaders).
    pub sampled_lights: Option<usize>,
    /// Pixel-VPL pairs the stochastic shader's lists held, where the backend counts them
    /// without a readback ([`crate::Renderer::listed_pairs`]).
    pub listed_pairs: Option<u64>,
}

impl Shaded {
    /// Indirect light with wall-clock timings and nothing else.
    pub fn new(indirect: Image, timings: Timings) -> Self {
        Self {
            indirect,
            timings,
            gpu_timings: None,
            metrics: None,
            sampled_lights: None,
            listed_pairs: None,
        }
    }
}

/// A rendered frame with what it cost.
#[derive(Clone, Debug)]
pub struct RenderedFrame {
    pub direct: Image,
    pub indirect: Image,
    /// VPLs per pass (0 for the path method).
    pub vpl_count: usize,
    /// Milliseconds per pass, summed over the passes, in the order they ran.
    pub timings: Timings,
    /// The GPU's timestamp times, summed over the passes, where the adapter has them.
    pub gpu_timings: Option<Timings>,
    /// Culling metrics of the last pass, when asked for.
    pub metrics: Option<CullMetrics>,
    /// Distinct sampled lights shaded in the last pass (VSGL and sampled-VPL methods).
    pub sampled_lights: Option<usize>,
    /// Bytes read back from the device while rendering, summed over the passes, by what was
    /// read (metrics included; `None` for a backend without a device).
    pub readback_bytes: Option<BTreeMap<String, u64>>,
}

impl RenderedFrame {
    /// Direct plus indirect light.
    pub fn total(&self) -> Image {
        self.direct.add(&self.indirect)
    }
}
