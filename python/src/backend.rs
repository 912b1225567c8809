//! The backends a [`crate::scene::PyScene`] keeps between calls: the CPU's BVH, and the GPU
//! device with the uploaded scene (and a BVH for the CPU passes of its frames), each made on
//! first use. Work is written once as a [`Job`]
//! over the renderer API and run on the backend the options name.
use crate::options::{Backend, Options};
use slc_app::cpu_frames::{CpuFrames, SceneBvh};
use slc_core::{Progress, Renderer, Scene};
use slc_cpu_ref::CpuRenderer;

/// Work on one backend, written once for every backend. It reports its pixel-passes to
/// `progress` and stops when it is cancelled.
pub trait Job {
    type Output;
    fn run<R: CpuFrames>(
        self,
        r: &R,
        scene: &Scene,
        loaded: &R::Scene,
        bvh: &SceneBvh,
        progress: Progress,
    ) -> Result<Self::Output, String>;
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
                self.cpu_renderer
                    .check(&options.settings)
                    .map_err(|e| e.to_string())?;
                let loaded = match &mut self.cpu {
                    Some(l) => l,
                    slot => slot.insert(self.cpu_renderer.load(scene).map_err(|e| e.to_string())?),
                };
                job.run(&self.cpu_renderer, scene, loaded, &self.bvh, progress)
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
                let gpu = slc_gpu_wgpu::GpuRenderer::new().map_err(|e| e.to_string())?;
                if let Some(warning) = gpu.context().software_warning() {
                    eprintln!("warning: {warning}");
                }
                let loaded = gpu.load(scene).map_err(|e| e.to_string())?;
                slot.insert((gpu, loaded))
            }
        };
        gpu.check(&options.settings).map_err(|e| e.to_string())?;
        gpu.set_one_pass(options.one_pass);
        job.run(&*gpu, scene, loaded, &self.bvh, progress)
    }

    #[cfg(not(feature = "gpu"))]
    fn run_gpu<J: Job>(
        &mut self,
        _options: &Options,
        _scene: &Scene,
        _job: J,
        _progress: Progress,
    ) -> Result<J::Output, String> {
        Err("this slc was built without the `gpu` feature: use backend='cpu'".into())
    }
}
