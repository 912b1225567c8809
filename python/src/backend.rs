//! The backends a [`crate::scene::PyScene`] keeps between calls: the CPU's BVH, and the GPU
//! device with the uploaded scene (and a BVH for the CPU passes of its frames), each made on
//! first use. Work is written once as a [`Job`] over the renderer API and run on the backend
//! the options name (`slc_app::backends`, which the `slc` command shares).
use crate::options::Options;
use slc_app::backends::{self, Backend};
use slc_app::cpu_frames::{CpuFrames, SceneBvh};
use slc_core::frame::RenderSettings;
use slc_core::{Progress, RenderError, Renderer, Scene};
use slc_cpu_ref::CpuRenderer;

/// A backend with a scene loaded there: what a [`Job`] runs on.
pub struct On<'a, R: CpuFrames> {
    pub r: &'a R,
    pub scene: &'a Scene,
    pub loaded: &'a R::Scene,
    /// The scene's BVH, for what only the CPU computes (`CpuFrames::cpu_frame`).
    pub bvh: &'a SceneBvh,
    pub progress: Progress<'a>,
}

impl<'a, R: CpuFrames> On<'a, R> {
    /// `r` with `scene` loaded there (`loaded`), the scene's BVH and the call's progress.
    fn new(
        r: &'a R,
        (scene, loaded): (&'a Scene, &'a R::Scene),
        bvh: &'a SceneBvh,
        progress: Progress<'a>,
    ) -> Self {
        Self {
            r,
            scene,
            loaded,
            bvh,
            progress,
        }
    }

    /// A frame up to its VPLs and direct light, at pixel and texel centres.
    pub fn prepare(&self, settings: &RenderSettings) -> Result<R::Prepared, String> {
        self.r
            .prepare(self.scene, self.loaded, settings, None, self.progress)
            .map_err(message)
    }
}

/// Work on one backend, written once for every backend. It reports its pixel-passes to
/// `on.progress` and stops when it is cancelled.
pub trait Job {
    type Output;
    fn run<R: CpuFrames>(self, on: On<'_, R>) -> Result<Self::Output, String>;
}

/// A library error as Python reports it: what a backend lacks points to the one that has it
/// (`backend='NAME'`).
pub fn message(e: RenderError) -> String {
    backends::message(&e, |b| format!("backend='{}'", b.name()))
}

/// What each backend keeps of a scene.
#[derive(Default)]
pub struct Loaded {
    cpu: Option<<CpuRenderer as Renderer>::Scene>,
    /// The CPU renderer, kept from job to job (it reuses its frames' images).
    cpu_renderer: CpuRenderer,
    /// The scene's BVH for the CPU passes of the GPU's frames, built on first use.
    bvh: SceneBvh,
    #[cfg(feature = "gpu")]
    gpu: Option<(
        slc_gpu_wgpu::GpuRenderer,
        <slc_gpu_wgpu::GpuRenderer as Renderer>::Scene,
    )>,
}

impl Loaded {
    /// Backends that built their state of the scene.
    pub fn loads(&self) -> usize {
        #[cfg(feature = "gpu")]
        let gpu = usize::from(self.gpu.is_some());
        #[cfg(not(feature = "gpu"))]
        let gpu = 0;
        usize::from(self.cpu.is_some()) + gpu
    }

    /// Runs `job` on the options' backend (after checking it can render the options'
    /// settings), loading `scene` there first if it is not yet.
    pub fn run<J: Job>(
        &mut self,
        options: &Options,
        scene: &Scene,
        job: J,
        progress: Progress,
    ) -> Result<J::Output, String> {
        match options.backend {
            Backend::Cpu => {
                let r = &self.cpu_renderer;
                r.check(&options.settings).map_err(message)?;
                let loaded = match &mut self.cpu {
                    Some(l) => l,
                    slot => slot.insert(r.load(scene).map_err(message)?),
                };
                job.run(On::new(r, (scene, loaded), &self.bvh, progress))
            }
            Backend::Gpu => self.run_gpu(options, scene, job, progress),
        }
    }

    #[cfg(feature = "gpu")]
    fn run_gpu<J: Job>(
        &mut self,
        options: &Options,
        scene: &Scene,
        job: J,
        progress: Progress,
    ) -> Result<J::Output, String> {
        let (gpu, loaded) = match &mut self.gpu {
            Some(g) => g,
            slot => {
                let gpu = backends::open_gpu()?;
                let loaded = gpu.load(scene).map_err(message)?;
                slot.insert((gpu, loaded))
            }
        };
        gpu.check(&options.settings).map_err(message)?;
        gpu.set_one_pass(options.one_pass);
        job.run(On::new(&*gpu, (scene, loaded), &self.bvh, progress))
    }

    #[cfg(not(feature = "gpu"))]
    fn run_gpu<J: Job>(
        &mut self,
        _options: &Options,
        _scene: &Scene,
        _job: J,
        _progress: Progress,
    ) -> Result<J::Output, String> {
        Err(backends::gpu_not_built("backend='cpu'"))
    }
}
