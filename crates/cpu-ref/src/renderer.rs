//! The CPU backend of the renderer API: [`CpuRenderer`] runs every step of
//! `slc_core::Renderer` with this crate's ray-traced passes and `slc_cull`'s cullers, and
//! has every method, the references and shadow rays included. Another backend hands a frame
//! to what only the CPU computes as [`slc_core::frame::PreparedData`] ([`CpuPrepared::from_data`]).
use crate::denoise::{BilateralParams, CrossBilateral};
use crate::frame_images::{Spare, SpareImage};
use crate::path::trace_pixel_sample;
use crate::prepare::{prepare_watched, CpuPrepared, FrameSpares};
use crate::sampled_lights::{shade_sampled_vpls, shade_vsgl};
use crate::tracer::Tracer;
use crate::vpl_shading::{shade_lists_into, shade_vpls, VplEstimator};
use rayon::prelude::*;
use slc_core::frame::{LightSampling, RenderError, RenderSettings, RenderedFrame, Shaded};
use slc_core::shader::SampledLights;
use slc_core::{
    BackendInfo, Capabilities, CullMetrics, Image, Interleaving, LightLists, Progress, Renderer,
    Scene, Strategy,
};
use slc_cull::{BoundedCuller, BoundedMemory, ListedReach};
use std::sync::{Arc, Mutex, TryLockError};

/// The CPU reference renderer on rayon's threads. It keeps the last noisy image its filter
/// consumed ([`Renderer::denoise`]) and shades the next frame of the same size into it
/// ([`shade_lists_into`]): in a loop of frames (cull, shade, filter) the shading then
/// allocates and clears no image, and forms its listed VPLs' exits in the last frame's table
/// ([`ListedReach`]); a bound-testing strategy's culling forms its bounds in the last one's
/// memory ([`BoundedMemory`]). Its filter keeps its working set from frame to frame as
/// well ([`CrossBilateral`]), and each prepared frame, once dropped, leaves its G-buffer,
/// VPLs and direct light for the next one to write into ([`FrameSpares`]). A clone keeps
/// none of them.
#[derive(Clone, Debug, Default)]
pub struct CpuRenderer {
    spare: SpareImage,
    /// The bounds of the last bound-testing culling, formed again in their memory.
    bounds: Spare<BoundedMemory>,
    /// The listed VPLs' exits of the last shading, formed again in its memory.
    exits: Spare<ListedReach>,
    frames: FrameSpares,
    filter: KeptFilter,
}

/// The renderer's cross bilateral filter with its working set; a clone starts without.
#[derive(Debug, Default)]
struct KeptFilter(Mutex<CrossBilateral>);

impl Clone for KeptFilter {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl KeptFilter {
    /// Filters with the kept working set, or with a fresh one while another thread holds it.
    fn filter(&self, image: &Image, p: &CpuPrepared) -> Result<Image, RenderError> {
        let params = BilateralParams::default();
        let filtered = match self.0.try_lock() {
            Ok(mut kept) => kept.filter(image, &p.gbuffer, params),
            Err(TryLockError::Poisoned(poisoned)) => {
                poisoned.into_inner().filter(image, &p.gbuffer, params)
            }
            Err(TryLockError::WouldBlock) => {
                CrossBilateral::default().filter(image, &p.gbuffer, params)
            }
        };
        filtered.map_err(RenderError::backend)
    }
}

impl CpuRenderer {
    /// Frees the memory the last frame dropped left ([`FrameSpares`]) and the memory of its
    /// culling and shading ([`BoundedMemory`], [`ListedReach`]; a few hundred MB at a million
    /// VPLs): the next frame is prepared, culled and shaded in fresh memory, as the first is
    /// (`slc bench` times every frame's preparation so).
    pub fn release_frame_memory(&self) {
        self.frames.release();
        drop(self.bounds.take());
        drop(self.exits.take());
    }

    /// The backend's name in reports and errors ([`Renderer::name`]).
    pub const NAME: &'static str = "cpu";

    /// Everything but the rasterization baselines ([`Renderer::capabilities`]).
    pub const CAPABILITIES: Capabilities = Capabilities {
        raster_culling: false,
        ..Capabilities::ALL
    };
}

impl Renderer for CpuRenderer {
    type Scene = Arc<Tracer>;
    type Prepared = CpuPrepared;
    type Lists = LightLists;
    type Image = Image;

    fn name(&self) -> &'static str {
        Self::NAME
    }

    fn capabilities(&self) -> Capabilities {
        Self::CAPABILITIES
    }

    fn info(&self, _settings: &RenderSettings) -> BackendInfo {
        BackendInfo {
            backend: Self::NAME,
            adapter: format!("CPU ({} rayon threads)", rayon::current_num_threads()),
            notes: Vec::new(),
        }
    }

    fn load(&self, scene: &Scene) -> Result<Arc<Tracer>, RenderError> {
        Ok(Arc::new(Tracer::new(scene)))
    }

    fn prepare(
        &self,
        scene: &Scene,
        loaded: &Arc<Tracer>,
        settings: &RenderSettings,
        pass: Option<u32>,
        progress: Progress,
    ) -> Result<CpuPrepared, RenderError> {
        let tracer = Arc::clone(loaded);
        let p = prepare_watched(scene, settings, tracer, pass, progress, Some(&self.frames));
        progress.check()?;
        Ok(p)
    }

    fn cull(
        &self,
        p: &CpuPrepared,
        strategy: Strategy,
        delta: f32,
        interleaving: Interleaving,
    ) -> Result<LightLists, RenderError> {
        let input = p.cull_input(delta, interleaving);
        let Some(culler) = BoundedCuller::new(strategy) else {
            return Ok(slc_cull::culler(strategy).cull(&input)?);
        };
        let mut memory = self.bounds.take().unwrap_or_default();
        let lists = culler.cull_in(&input, &mut memory);
        self.bounds.keep(memory);
        Ok(lists?)
    }

    fn shade_lists(
        &self,
        _loaded: &Arc<Tracer>,
        p: &CpuPrepared,
        lists: &LightLists,
        delta: f32,
        interleaving: Interleaving,
        visibility: bool,
        progress: Progress,
    ) -> Result<Image, RenderError> {
        let input = p.cull_input(delta, interleaving);
        let spare = self.spare.take();
        let mut exits = self.exits.take().unwrap_or_default();
        let image = shade_lists_into(
            &p.tracer, &input, lists, visibility, progress, spare, &mut exits,
        );
        self.exits.keep(exits);
        let image = image?;
        progress.check()?;
        Ok(image)
    }

    fn listed_pairs(&self, lists: &LightLists) -> Option<u64> {
        Some(lists.listed_pairs())
    }

    /// The filter runs whole once begun (about 0.1 s at 1080p on 2 cores): `progress` is
    /// checked before and after it.
    fn denoise(
        &self,
        p: &CpuPrepared,
        image: Image,
        progress: Progress,
    ) -> Result<Image, RenderError> {
        progress.check()?;
        let filtered = self.filter.filter(&image, p)?;
        self.spare.keep(image);
        progress.check()?;
        Ok(filtered)
    }

    fn read_image(&self, _p: &CpuPrepared, image: Image) -> Result<Image, RenderError> {
        Ok(image)
    }

    fn measure(
        &self,
        p: &CpuPrepared,
        lists: &LightLists,
        delta: f32,
        interleaving: Interleaving,
    ) -> Result<CullMetrics, RenderError> {
        Ok(slc_cull::metrics::measure(
            &p.cull_input(delta, interleaving),
            lists,
        )?)
    }

    fn shade_sampled(
        &self,
        _scene: &Scene,
        _loaded: &Arc<Tracer>,
        p: &CpuPrepared,
        lights: SampledLights,
        sampling: &LightSampling,
        seed: u32,
        visibility: bool,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        let shade = match lights {
            SampledLights::Vsgl => shade_vsgl,
            SampledLights::Vpl => shade_sampled_vpls,
        };
        let shaded =
            shade(p, sampling, seed, visibility, progress).map_err(RenderError::backend)?;
        progress.check()?;
        Ok(shaded)
    }

    fn shade_all_vpls(
        &self,
        _loaded: &Arc<Tracer>,
        p: &CpuPrepared,
        visibility: bool,
        progress: Progress,
    ) -> Result<Image, RenderError> {
        let image = shade_vpls(
            &p.tracer,
            &p.gbuffer,
            &p.vpls,
            VplEstimator::Exact,
            visibility,
            progress,
        )?;
        progress.check()?;
        Ok(image)
    }

    fn path_trace(
        &self,
        scene: &Scene,
        loaded: &Arc<Tracer>,
        settings: &RenderSettings,
        pass: u32,
        progress: Progress,
    ) -> Result<(Image, Image), RenderError> {
        let (w, h) = (settings.width, settings.height);
        let camera = scene.camera_or_default();
        let pixels: Vec<_> = (0..h)
            .into_par_iter()
            .flat_map_iter(|j| {
                // Once cancelled, the rows left are black and the pass an error.
                if progress.cancelled() {
                    return vec![Default::default(); w as usize];
                }
                let row: Vec<_> = (0..w)
                    .map(|i| {
                        trace_pixel_sample(
                            scene,
                            loaded,
                            &camera,
                            j * w + i,
                            (w, h),
                            settings.seed,
                            pass,
                        )
                    })
                    .collect();
                progress.advance(w as u64);
                row
            })
            .collect();
        progress.check()?;
        let (mut direct, mut indirect) = (Image::new(w, h), Image::new(w, h));
        for (k, (d, i)) in pixels.into_iter().enumerate() {
            direct.pixels[k] = d;
            indirect.pixels[k] = i;
        }
        Ok((direct, indirect))
    }
}

/// Renders `scene` on the CPU ([`slc_core::render()`] with [`CpuRenderer`]).
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    progress: Progress,
) -> Result<RenderedFrame, RenderError> {
    slc_core::render(&CpuRenderer::default(), scene, settings, progress)
}
