//! What only the CPU computes (the all-VPL reference, the unculled estimate of a comparison,
//! the brute-force metrics of a sweep, sampled VPLs) on a frame any backend prepared: the
//! CPU's own frame borrowed, another backend's read back as `slc_core`'s
//! [`slc_core::frame::PreparedData`] and traced with a BVH of the scene built on first use.
//! The backends stay siblings: neither depends on the other, this front end joins them.
use slc_core::{RenderError, Renderer, Scene};
use slc_cpu_ref::{CpuPrepared, CpuRenderer, Tracer};
use std::borrow::Cow;
use std::sync::{Arc, OnceLock};

/// A scene's BVH for the CPU passes of another backend's frames, built when first needed.
#[derive(Default)]
pub struct SceneBvh(OnceLock<Arc<Tracer>>);

impl SceneBvh {
    /// The BVH of `scene` (built on the first call; later calls must pass the same scene).
    pub fn of(&self, scene: &Scene) -> Arc<Tracer> {
        Arc::clone(self.0.get_or_init(|| Arc::new(Tracer::new(scene))))
    }
}

/// A backend whose prepared frames the CPU can read.
pub trait CpuFrames: Renderer {
    /// `p` as the CPU's frame: borrowed on the CPU; elsewhere read back, with `bvh`'s BVH
    /// of `scene`.
    fn cpu_frame<'a>(
        &self,
        scene: &Scene,
        bvh: &SceneBvh,
        p: &'a Self::Prepared,
    ) -> Result<Cow<'a, CpuPrepared>, RenderError>;

    /// Makes the next frame start as the first does: on the CPU, in fresh memory rather than
    /// in what the last frame left (`CpuRenderer::release_frame_memory`).
    fn start_cold(&self) {}
}

impl CpuFrames for CpuRenderer {
    fn cpu_frame<'a>(
        &self,
        _scene: &Scene,
        _bvh: &SceneBvh,
        p: &'a CpuPrepared,
    ) -> Result<Cow<'a, CpuPrepared>, RenderError> {
        Ok(Cow::Borrowed(p))
    }

    fn start_cold(&self) {
        self.release_frame_memory();
    }
}

#[cfg(feature = "gpu")]
impl CpuFrames for slc_gpu_wgpu::GpuRenderer {
    fn cpu_frame<'a>(
        &self,
        scene: &Scene,
        bvh: &SceneBvh,
        p: &'a slc_gpu_wgpu::GpuPrepared,
    ) -> Result<Cow<'a, CpuPrepared>, RenderError> {
        let data = self.read_frame(p)?;
        Ok(Cow::Owned(CpuPrepared::from_data(data, bvh.of(scene))))
    }
}
