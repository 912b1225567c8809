//! The backend trait: the steps of the paper's pipeline (Fig. 2) that a backend runs, so
//! that shaders ([`crate::shader`]), the frame loop ([`crate::render::render`]) and the `slc`
//! commands are written once for every backend. `slc_cpu_ref::CpuRenderer` and
//! `slc_gpu_wgpu::GpuRenderer` implement it.
//!
//! A frame goes prepare (G-buffer, RSMs, VPLs, direct light) → cull → shade → denoise →
//! read back; VSGLs replace culling and VPL shading by their own step. Each step leaves its
//! result where the backend keeps it ([`Renderer::Lists`], [`Renderer::Image`]), so a GPU
//! frame stays on the device until [`Renderer::read_image`].
use crate::camera::Camera;
use crate::culling::{CullMetrics, Interleaving};
use crate::frame::{LightSampling, Method, PassTime, RenderError, RenderSettings, Shaded, Timings};
use crate::framebuffer::Image;
use crate::progress::Progress;
use crate::scene::Scene;
use crate::shader::SampledLights;
use crate::strategy::{GlossyBound, Strategy};
use crate::vpl::Vpl;
use std::collections::BTreeMap;

/// What a report says about the backend that rendered.
#[derive(Clone, Debug, PartialEq)]
pub struct BackendInfo {
    /// The backend's name ([`Renderer::name`]).
    pub backend: &'static str,
    /// The device: the CPU backend names its thread count, the GPU backend its adapter.
    pub adapter: String,
    /// Where each pass ran and how it was timed, when that is not obvious.
    pub notes: Vec<String>,
}

/// What a backend has beyond the stochastic VPL estimate and VSGLs without visibility, which
/// every backend renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capabilities {
    /// Shadow rays between VPLs and pixels.
    pub vpl_visibility: bool,
    /// VSGL eq. 3's visibility to each VSGL's mean.
    pub vsgl_visibility: bool,
    /// The all-VPL and path-traced references.
    pub references: bool,
    /// VPLs sampled at equal count with the VSGLs' importance.
    pub sampled_vpls: bool,
    /// The `tight` and `clustered-tight` culling strategies (`GlossyBound::Tight`).
    pub tight_culling: bool,
    /// The rasterization baselines `splatting` and `clustered-raster` ([`Strategy::RASTER`]).
    pub raster_culling: bool,
}

impl Capabilities {
    /// Nothing beyond what every backend renders.
    pub const NONE: Self = Self::every(false);

    /// Everything.
    pub const ALL: Self = Self::every(true);

    const fn every(has: bool) -> Self {
        Self {
            vpl_visibility: has,
            vsgl_visibility: has,
            references: has,
            sampled_vpls: has,
            tight_culling: has,
            raster_culling: has,
        }
    }

    /// What `settings` ask of a backend beyond what every backend renders.
    pub fn needed(settings: &RenderSettings) -> Self {
        let vpls = Self {
            vpl_visibility: settings.visibility,
            ..Self::NONE
        };
        match settings.method {
            Method::VplReference => Self {
                references: true,
                ..vpls
            },
            Method::Path => Self {
                references: true,
                ..Self::NONE
            },
            Method::SampledVpls(_) => Self {
                sampled_vpls: true,
                ..vpls
            },
            Method::Vsgl(_) => Self {
                vsgl_visibility: settings.visibility,
                ..Self::NONE
            },
            Method::Stochastic(s) => Self {
                vpl_visibility: settings.visibility,
                ..Self::culling(s.strategy)
            },
        }
    }

    /// What culling with `strategy` asks of a backend.
    pub fn culling(strategy: Strategy) -> Self {
        Self {
            tight_culling: strategy.parts().1 == GlossyBound::Tight,
            raster_culling: strategy.is_raster(),
            ..Self::NONE
        }
    }

    /// What of `needs` these capabilities lack, described, most particular first.
    fn lacking(&self, needs: &Self) -> impl Iterator<Item = &'static str> {
        let lacks = |need: bool, have: bool| need && !have;
        [
            (lacks(needs.references, self.references), "the references"),
            (lacks(needs.sampled_vpls, self.sampled_vpls), "sampled VPLs"),
            (
                lacks(needs.vsgl_visibility, self.vsgl_visibility),
                "visibility for VSGLs",
            ),
            (
                lacks(needs.raster_culling, self.raster_culling),
                "the rasterization baselines (splatting, clustered-raster)",
            ),
            (
                lacks(needs.tight_culling, self.tight_culling),
                "the tight culling strategies (tight, clustered-tight)",
            ),
            (
                lacks(needs.vpl_visibility, self.vpl_visibility),
                "shadow rays between VPLs and pixels (visibility)",
            ),
        ]
        .into_iter()
        .filter_map(|(lacking, what)| lacking.then_some(what))
    }

    /// Whether these capabilities have everything `needs` asks for.
    pub fn covers(&self, needs: &Self) -> bool {
        self.lacking(needs).next().is_none()
    }

    /// Whether the backend runs the culling strategy `strategy`.
    pub fn runs(&self, strategy: Strategy) -> bool {
        self.covers(&Self::culling(strategy))
    }

    /// [`RenderError::Unsupported`] naming the first thing `settings` asks for that
    /// `backend` (with these capabilities) does not have, with all they need (a front end
    /// that knows the other backends points to the one that has it).
    pub fn check(
        &self,
        backend: &'static str,
        settings: &RenderSettings,
    ) -> Result<(), RenderError> {
        let needs = Self::needed(settings);
        match self.lacking(&needs).next() {
            Some(what) => Err(RenderError::Unsupported {
                backend,
                what: what.into(),
                needs,
            }),
            None => Ok(()),
        }
    }
}

/// What the references need.
const REFERENCES: Capabilities = Capabilities {
    references: true,
    ..Capabilities::NONE
};

/// A frame up to its VPLs and direct light, as any backend leaves it.
pub trait PreparedFrame {
    fn camera(&self) -> &Camera;
    /// The number of VPLs; a backend that keeps them on a device reads their number back
    /// when first asked, which can fail.
    fn vpl_count(&self) -> Result<usize, RenderError>;
    /// The VPLs, sorted by id; a backend that keeps them on a device reads them back on
    /// first use, which can fail.
    fn vpls(&self) -> Result<&[Vpl], RenderError>;
    fn direct(&self) -> &Image;
    /// Wall-clock milliseconds of the preparing passes.
    fn timings(&self) -> &Timings;
    /// The GPU's timestamp times of the same passes, where the adapter has trustworthy ones.
    fn gpu_timings(&self) -> Option<&Timings> {
        None
    }
}

/// A rendering backend: the steps of one frame. Steps a backend does not have return
/// [`RenderError::Unsupported`]; [`Renderer::capabilities`] says which those are. Steps that
/// take a [`Progress`] report their finished pixels to it and check it between their tiles
/// (or rows, or dispatches): once it is cancelled they return [`RenderError::Cancelled`].
pub trait Renderer {
    /// The scene as this backend keeps it between frames (its BVH, its uploaded buffers).
    type Scene;
    /// A frame up to its VPLs and direct light.
    type Prepared: PreparedFrame;
    /// Light lists where culling leaves them.
    type Lists;
    /// An image where shading leaves it.
    type Image;

    /// The backend's name in reports and errors.
    fn name(&self) -> &'static str;

    fn capabilities(&self) -> Capabilities;

    /// What a report of a frame rendered with `settings` says about this backend.
    fn info(&self, settings: &RenderSettings) -> BackendInfo;

    /// Bytes read back from a device so far, by what was read (cumulative); `None` for a
    /// backend without one.
    fn readback_bytes(&self) -> Option<BTreeMap<String, u64>> {
        None
    }

    /// [`RenderError::Unsupported`] if `settings` asks for something this backend lacks.
    fn check(&self, settings: &RenderSettings) -> Result<(), RenderError> {
        self.capabilities().check(self.name(), settings)
    }

    /// Makes what every frame of `scene` shares.
    fn load(&self, scene: &Scene) -> Result<Self::Scene, RenderError>;

    /// The G-buffer, the RSMs, the VPLs (ξ from the seed of `settings` and `pass`) and the
    /// direct light. `pass` = `None` samples pixel and texel centres; `Some(p)` jitters
    /// them for pass p of several. `progress` is only checked (the frame's pixel-passes are
    /// counted by its shading).
    fn prepare(
        &self,
        scene: &Scene,
        loaded: &Self::Scene,
        settings: &RenderSettings,
        pass: Option<u32>,
        progress: Progress,
    ) -> Result<Self::Prepared, RenderError>;

    /// The light lists of `strategy` (section 5-7): never without a VPL whose p(ωo, l) > ξ.
    fn cull(
        &self,
        p: &Self::Prepared,
        strategy: Strategy,
        delta: f32,
        interleaving: Interleaving,
    ) -> Result<Self::Lists, RenderError>;

    /// The stochastic estimate of eq. (3) from `lists`, times K² (section 6).
    #[allow(clippy::too_many_arguments)]
    fn shade_lists(
        &self,
        loaded: &Self::Scene,
        p: &Self::Prepared,
        lists: &Self::Lists,
        delta: f32,
        interleaving: Interleaving,
        visibility: bool,
        progress: Progress,
    ) -> Result<Self::Image, RenderError>;

    /// Pixel-VPL pairs `lists` hold ([`crate::LightLists::listed_pairs`]), where this backend
    /// can count them without reading the lists back; `None` elsewhere.
    fn listed_pairs(&self, _lists: &Self::Lists) -> Option<u64> {
        None
    }

    /// The cross bilateral filter guided by depth and normal (section 6); `progress` is only
    /// checked.
    fn denoise(
        &self,
        p: &Self::Prepared,
        image: Self::Image,
        progress: Progress,
    ) -> Result<Self::Image, RenderError>;

    /// `image` where the CPU can read it.
    fn read_image(&self, p: &Self::Prepared, image: Self::Image) -> Result<Image, RenderError>;

    /// True and false positives and misses of `lists`, by brute force.
    fn measure(
        &self,
        p: &Self::Prepared,
        lists: &Self::Lists,
        delta: f32,
        interleaving: Interleaving,
    ) -> Result<CullMetrics, RenderError>;

    /// Indirect light from `sampling.count` sampled lights (VSGL sections 3-4): VSGLs, which
    /// every backend shades, or the sampled texels' VPLs ([`Capabilities::sampled_vpls`]).
    #[allow(clippy::too_many_arguments)]
    fn shade_sampled(
        &self,
        scene: &Scene,
        loaded: &Self::Scene,
        p: &Self::Prepared,
        lights: SampledLights,
        sampling: &LightSampling,
        seed: u32,
        visibility: bool,
        progress: Progress,
    ) -> Result<Shaded, RenderError>;

    /// Every VPL at every pixel with p = 1: the all-VPL reference.
    fn shade_all_vpls(
        &self,
        _loaded: &Self::Scene,
        _p: &Self::Prepared,
        _visibility: bool,
        _progress: Progress,
    ) -> Result<Image, RenderError> {
        Err(self.unsupported("the all-VPL reference", REFERENCES))
    }

    /// One pass of the path-traced one-bounce reference: direct and indirect light.
    fn path_trace(
        &self,
        _scene: &Scene,
        _loaded: &Self::Scene,
        _settings: &RenderSettings,
        _pass: u32,
        _progress: Progress,
    ) -> Result<(Image, Image), RenderError> {
        Err(self.unsupported("the path-traced reference", REFERENCES))
    }

    /// Runs `f`, returning with its result the GPU's timestamp times of the passes it ran,
    /// where the backend has trustworthy ones.
    fn profiled<T>(
        &self,
        f: impl FnOnce() -> Result<T, RenderError>,
    ) -> Result<(T, Option<Timings>), RenderError> {
        Ok((f()?, None))
    }

    /// The GPU's timestamp times of each pass of the last [`Renderer::profiled`] run (where
    /// [`Renderer::profiled`] returned times): finer than its stages, for profiling a
    /// kernel. `None` for a backend without them.
    fn last_pass_times(&self) -> Option<Vec<PassTime>> {
        None
    }

    /// The error of a step this backend does not have, which `needs` these capabilities.
    fn unsupported(&self, what: &str, needs: Capabilities) -> RenderError {
        RenderError::Unsupported {
            backend: self.name(),
            what: what.into(),
            needs,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::{LobeSelection, Stochastic};

    fn stochastic(strategy: Strategy, visibility: bool) -> RenderSettings {
        RenderSettings {
            width: 8,
            height: 8,
            rsm_resolution: 4,
            seed: 0,
            method: Method::Stochastic(Stochastic {
                delta: 1e-3,
                strategy,
                interleave: 2,
                denoise: false,
                metrics: false,
            }),
            visibility,
            spp: 1,
            lobes: LobeSelection::Both,
        }
    }

    /// A refusal says what is missing and what the settings need in all, so that a front
    /// end finds the backend that has it, or none where no backend has the combination (a
    /// raster baseline, which the second capabilities below have, with visibility, which
    /// only the first have).
    #[test]
    fn refusals_carry_what_the_settings_need() {
        let first = Capabilities {
            raster_culling: false,
            ..Capabilities::ALL
        };
        let second = Capabilities {
            vpl_visibility: false,
            references: false,
            sampled_vpls: false,
            raster_culling: true,
            ..first
        };
        let refusal = |caps: Capabilities, settings| match caps.check("this", &settings) {
            Err(RenderError::Unsupported { what, needs, .. }) => (what, needs),
            other => panic!("{other:?}"),
        };
        let raster = stochastic(Strategy::Splatting, false);
        let (what, needs) = refusal(first, raster.clone());
        assert!(what.contains("rasterization"), "{what}");
        assert!(second.covers(&needs) && !first.covers(&needs));
        assert!(second.check("that", &raster).is_ok());
        let (what, needs) = refusal(second, stochastic(Strategy::Ellipsoid, true));
        assert!(what.contains("visibility"), "{what}");
        assert!(first.covers(&needs));
        let (_, needs) = refusal(second, stochastic(Strategy::ClusteredRaster, true));
        assert!(!first.covers(&needs) && !second.covers(&needs));
        let no_blending = Capabilities {
            raster_culling: false,
            ..second
        };
        let (_, needs) = refusal(no_blending, raster);
        assert!(second.covers(&needs) && !first.covers(&needs));
        let e = second.check("that", &stochastic(Strategy::Tight, false));
        assert!(e.is_ok(), "{e:?}");
        assert_eq!(
            Capabilities::needed(&stochastic(Strategy::Tight, true)),
            Capabilities {
                vpl_visibility: true,
                tight_culling: true,
                ..Capabilities::NONE
            }
        );
    }
}
