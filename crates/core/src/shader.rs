//! Shaders: the estimators of indirect light, each written once over the steps of a
//! [`Renderer`], so both backends run the same composition.
use crate::culling::Interleaving;
use crate::frame::{merge_optional, LightSampling, RenderError, Shaded, Stochastic, Timings};
use crate::renderer::{PreparedFrame, Progress, Renderer};
use crate::scene::Scene;

/// What a shader reads: the scene, what the backend keeps of it, and a prepared frame.
pub struct ShadeInput<'a, R: Renderer> {
    pub scene: &'a Scene,
    pub loaded: &'a R::Scene,
    pub prepared: &'a R::Prepared,
    /// The seed of ξ, the interleaving and the sampled points.
    pub seed: u32,
    /// Shadow rays (or shadow maps) between lights and pixels.
    pub visibility: bool,
}

impl<R: Renderer> Clone for ShadeInput<'_, R> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<R: Renderer> Copy for ShadeInput<'_, R> {}

/// An estimator of indirect light from a prepared frame.
pub trait Shader {
    /// The estimator's name, as reports and tables name it.
    fn name(&self) -> String;

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError>;
}

/// The stochastic estimate of eq. (3): cull (`culling`), shade the lists (`shading`), filter
/// (`denoise`), each timed on the wall clock; metrics by brute force after the timed passes.
impl Shader for Stochastic {
    fn name(&self) -> String {
        self.strategy.name().into()
    }

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        let p = input.prepared;
        let interleaving = Interleaving {
            k: self.interleave,
            seed: input.seed,
        };
        let mut timings = Timings::default();
        let ((lists, image), gpu_timings) = r.profiled(|| {
            let lists = timings.time("culling", || {
                r.cull(p, self.strategy, self.delta, interleaving)
            })?;
            let mut image = timings.time("shading", || {
                r.shade_lists(
                    input.loaded,
                    p,
                    &lists,
                    self.delta,
                    interleaving,
                    input.visibility,
                    progress,
                )
            })?;
            if self.denoise {
                image = timings.time("denoise", || r.denoise(p, image))?;
            }
            Ok((lists, image))
        })?;
        let indirect = r.read_image(p, image)?;
        let metrics = self
            .metrics
            .then(|| r.measure(p, &lists, self.delta, interleaving))
            .transpose()?;
        Ok(Shaded {
            indirect,
            timings,
            gpu_timings,
            metrics,
            sampled_lights: None,
        })
    }
}

/// `count` virtual spherical Gaussian lights sampled from the mipmapped RSMs (Tokuyoshi
/// 2015): `vsgl_mip`, `importance_map`, `light_sampling`, `light_shading`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VsglShader(pub LightSampling);

impl Shader for VsglShader {
    fn name(&self) -> String {
        "vsgl".into()
    }

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        r.shade_vsgls(
            input.scene,
            input.loaded,
            input.prepared,
            &self.0,
            input.seed,
            input.visibility,
            progress,
        )
    }
}

/// The VPLs of `count` texels sampled with the VSGLs' importance and points: the unbiased
/// equal-count VPL estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampledVplShader(pub LightSampling);

impl Shader for SampledVplShader {
    fn name(&self) -> String {
        "vpl_sampled".into()
    }

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        r.shade_sampled_vpls(
            input.loaded,
            input.prepared,
            &self.0,
            input.seed,
            input.visibility,
            progress,
        )
    }
}

/// Every VPL at every pixel with p = 1 (`vpl_shading`): the all-VPL reference.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AllVplShader;

impl Shader for AllVplShader {
    fn name(&self) -> String {
        "reference_vpl".into()
    }

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        let mut timings = Timings::default();
        let indirect = timings.time("vpl_shading", || {
            r.shade_all_vpls(input.loaded, input.prepared, input.visibility, progress)
        })?;
        Ok(Shaded::new(indirect, timings))
    }
}

/// `prepared`'s own times followed by `shaded`'s: the whole frame's wall-clock and GPU times.
pub fn frame_timings(prepared: &impl PreparedFrame, shaded: &Shaded) -> (Timings, Option<Timings>) {
    let mut timings = prepared.timings().clone();
    timings.merge(&shaded.timings);
    let mut gpu = None;
    merge_optional(&mut gpu, prepared.gpu_timings());
    merge_optional(&mut gpu, shaded.gpu_timings.as_ref());
    (timings, gpu)
}
