//! Shaders: the estimators of indirect light, each written once over the steps of a
//! [`Renderer`], so both backends run the same composition.
use crate::culling::Interleaving;
use crate::frame::{
    merge_optional, LightSampling, Method, RenderError, Shaded, Stochastic, Timings,
};
use crate::progress::Progress;
use crate::renderer::{PreparedFrame, Renderer};
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
    fn name(&self) -> &'static str;

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError>;
}

/// What [`Stochastic::passes`] leaves: the lists and the image where the backend keeps them,
/// and the passes' times.
pub struct StochasticPasses<R: Renderer> {
    pub lists: R::Lists,
    pub image: R::Image,
    /// Wall-clock milliseconds of `culling`, `shading` and (when filtered) `denoise`.
    pub timings: Timings,
    /// The GPU's timestamp times of the same passes, where the backend has trustworthy ones.
    pub gpu_timings: Option<Timings>,
}

impl Stochastic {
    /// The timed passes of the estimate of eq. (3): cull (`culling`), shade the lists
    /// (`shading`), filter (`denoise`), each timed on the wall clock; nothing is read back.
    /// [`Shader::shade`] is this, then the image read back and the metrics; a benchmark that
    /// times frame after frame calls this alone, so a GPU is not left idle while images
    /// travel back (its clocks fall when it idles, and the times with them).
    pub fn passes<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<StochasticPasses<R>, RenderError> {
        let p = input.prepared;
        let interleaving = Interleaving {
            k: self.interleave,
            seed: input.seed,
        };
        let mut timings = Timings::default();
        let ((lists, image), gpu_timings) = r.profiled(|| {
            progress.check()?;
            let lists = timings.time("culling", || {
                r.cull(p, self.strategy, self.delta, interleaving)
            })?;
            progress.check()?;
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
                progress.check()?;
                image = timings.time("denoise", || r.denoise(p, image, progress))?;
            }
            Ok((lists, image))
        })?;
        Ok(StochasticPasses {
            lists,
            image,
            timings,
            gpu_timings,
        })
    }
}

/// The stochastic estimate of eq. (3): [`Stochastic::passes`], then the image read back and,
/// with `metrics`, the metrics by brute force after the timed passes. `progress` is checked
/// between the passes (and by the backend between its tiles).
impl Shader for Stochastic {
    fn name(&self) -> &'static str {
        self.strategy.name()
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
        let passes = self.passes(r, input, progress)?;
        progress.check()?;
        let indirect = r.read_image(p, passes.image)?;
        let metrics = self
            .metrics
            .then(|| {
                progress.check()?;
                r.measure(p, &passes.lists, self.delta, interleaving)
            })
            .transpose()?;
        progress.check()?;
        Ok(Shaded {
            indirect,
            timings: passes.timings,
            gpu_timings: passes.gpu_timings,
            metrics,
            sampled_lights: None,
            listed_pairs: r.listed_pairs(&passes.lists),
        })
    }
}

/// What lights are sampled from the RSMs by importance (VSGL section 4.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampledLights {
    /// Virtual spherical Gaussian lights at the filtered mip level (Tokuyoshi 2015), shaded
    /// analytically: `vsgl_mip`, `importance_map`, `light_sampling`, `light_shading`.
    Vsgl,
    /// The VPLs of the sampled texels with the same importance and points, shaded exactly:
    /// the unbiased equal-count VPL estimator.
    Vpl,
}

impl SampledLights {
    /// Both, VPLs first.
    pub const ALL: [SampledLights; 2] = [SampledLights::Vpl, SampledLights::Vsgl];

    /// `vsgl` or `vpl_sampled`, as folders, tables and CSVs name them.
    pub fn name(self) -> &'static str {
        match self {
            Self::Vsgl => "vsgl",
            Self::Vpl => "vpl_sampled",
        }
    }

    /// The render method of these lights with `sampling`.
    pub fn method(self, sampling: LightSampling) -> Method {
        match self {
            Self::Vsgl => Method::Vsgl(sampling),
            Self::Vpl => Method::SampledVpls(sampling),
        }
    }
}

/// `sampling.count` lights of one kind sampled from the RSMs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampledShader {
    pub lights: SampledLights,
    pub sampling: LightSampling,
}

impl Shader for SampledShader {
    fn name(&self) -> &'static str {
        self.lights.name()
    }

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        // Profiled as the stochastic shader's passes are: a GPU with trusted timestamps gives
        // the VSGL passes' own times beside the wall clock.
        progress.check()?;
        let (mut shaded, gpu_timings) = r.profiled(|| {
            r.shade_sampled(
                input.scene,
                input.loaded,
                input.prepared,
                self.lights,
                &self.sampling,
                input.seed,
                input.visibility,
                progress,
            )
        })?;
        shaded.gpu_timings = gpu_timings;
        progress.check()?;
        Ok(shaded)
    }
}

/// Every VPL at every pixel with p = 1 (`vpl_shading`): the all-VPL reference.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AllVplShader;

impl Shader for AllVplShader {
    fn name(&self) -> &'static str {
        "reference_vpl"
    }

    fn shade<R: Renderer>(
        &self,
        r: &R,
        input: ShadeInput<'_, R>,
        progress: Progress,
    ) -> Result<Shaded, RenderError> {
        let mut timings = Timings::default();
        progress.check()?;
        let indirect = timings.time("vpl_shading", || {
            r.shade_all_vpls(input.loaded, input.prepared, input.visibility, progress)
        })?;
        progress.check()?;
        Ok(Shaded::new(indirect, timings))
    }
}

/// `prepared`'s own times followed by `shaded`'s: the whole frame's wall-clock and GPU times.
pub fn frame_timings(prepared: &impl PreparedFrame, shaded: &Shaded) -> (Timings, Option<Timings>) {
    frame_timings_of(prepared, &shaded.timings, shaded.gpu_timings.as_ref())
}

/// `prepared`'s own times followed by the wall-clock `timings` and GPU times `gpu` of the
/// passes after it ([`frame_timings`] of a shaded frame, or of [`Stochastic::passes`]).
pub fn frame_timings_of(
    prepared: &impl PreparedFrame,
    timings: &Timings,
    gpu: Option<&Timings>,
) -> (Timings, Option<Timings>) {
    let mut all = prepared.timings().clone();
    all.merge(timings);
    let mut all_gpu = None;
    merge_optional(&mut all_gpu, prepared.gpu_timings());
    merge_optional(&mut all_gpu, gpu);
    (all, all_gpu)
}
