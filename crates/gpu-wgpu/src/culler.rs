//! One entry point for every culling strategy of `slc_cull::CULLER_NAMES` on the GPU:
//! [`Strategy`] names one, [`GpuCuller`] runs it with the pass that implements it
//! (`none_cull_pass`, `tiled_cull_pass`, `clustered_cull_pass`), lists read back as a
//! [`LightLists`] or left on the GPU for `shade_pass`.
use crate::clustered_cull_pass::ClusteredCuller;
use crate::context::{GpuContext, GpuError};
use crate::cull_frame::CullFrame;
use crate::none_cull_pass::NoneCuller;
use crate::shade_pass::GpuLightLists;
use crate::tiled_cull_pass::TiledCuller;
use slc_core::{CullInput, LightLists};
use slc_cull::GlossyBound;

/// A culling strategy, as `slc_cull::culler_by_name` knows them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Strategy {
    /// `none`: every VPL of the pixel's interleaved subregion.
    None,
    /// `sphere`, `enclosing-sphere`, `ellipsoid`: Modified HalfZ tiles (section 5).
    Tiled(GlossyBound),
    /// `clustered-sphere`, `clustered-enclosing-sphere`, `clustered`: 32 depth slices per
    /// tile (section 7).
    Clustered(GlossyBound),
}

impl Strategy {
    /// The strategy called `name` (one of `slc_cull::CULLER_NAMES`), or `None`.
    pub fn by_name(name: &str) -> Option<Self> {
        use GlossyBound::{Ellipsoid, EnclosingSphere, Sphere};
        Some(match name {
            "none" => Self::None,
            "sphere" => Self::Tiled(Sphere),
            "enclosing-sphere" => Self::Tiled(EnclosingSphere),
            "ellipsoid" => Self::Tiled(Ellipsoid),
            "clustered" => Self::Clustered(Ellipsoid),
            "clustered-sphere" => Self::Clustered(Sphere),
            "clustered-enclosing-sphere" => Self::Clustered(EnclosingSphere),
            _ => return None,
        })
    }

    /// The strategy's name, as the command line spells it.
    pub fn name(self) -> &'static str {
        use GlossyBound::{Ellipsoid, EnclosingSphere, Sphere};
        match self {
            Self::None => "none",
            Self::Tiled(Sphere) => "sphere",
            Self::Tiled(EnclosingSphere) => "enclosing-sphere",
            Self::Tiled(Ellipsoid) => "ellipsoid",
            Self::Clustered(Ellipsoid) => "clustered",
            Self::Clustered(Sphere) => "clustered-sphere",
            Self::Clustered(EnclosingSphere) => "clustered-enclosing-sphere",
        }
    }
}

/// The pipelines of every strategy.
pub struct GpuCuller {
    none: NoneCuller,
    tiled: TiledCuller,
    clustered: ClusteredCuller,
}

impl GpuCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Ok(Self {
            none: NoneCuller::new(ctx)?,
            tiled: TiledCuller::new(ctx)?,
            clustered: ClusteredCuller::new(ctx)?,
        })
    }

    /// The lists of `strategy` for `input`, read back: equal to the CPU strategy's per pixel
    /// (up to f32-versus-f64 decisions at bound and slice boundaries).
    pub fn cull(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        strategy: Strategy,
    ) -> Result<LightLists, GpuError> {
        match strategy {
            Strategy::None => self.none.cull(ctx, input),
            Strategy::Tiled(glossy) => self.tiled.cull(ctx, input, glossy),
            Strategy::Clustered(glossy) => self.clustered.cull(ctx, input, glossy),
        }
    }

    /// [`Self::cull`] without the readback, for `shade_pass::ShadePass::shade_gpu_lists`.
    pub fn cull_on_gpu(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        strategy: Strategy,
    ) -> Result<GpuLightLists, GpuError> {
        self.cull_frame(ctx, &CullFrame::upload(ctx, input)?, strategy)
    }

    /// The lists of `strategy` for `frame` (a G-buffer on the GPU, uploaded or rasterized),
    /// left on the GPU.
    pub fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        strategy: Strategy,
    ) -> Result<GpuLightLists, GpuError> {
        match strategy {
            Strategy::None => self.none.cull_frame(ctx, frame),
            Strategy::Tiled(glossy) => self.tiled.cull_frame(ctx, frame, glossy),
            Strategy::Clustered(glossy) => self.clustered.cull_frame(ctx, frame, glossy),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_cpu_strategy_name_has_a_gpu_strategy_of_that_name() {
        for &name in slc_cull::CULLER_NAMES {
            let strategy = Strategy::by_name(name).unwrap_or_else(|| panic!("{name}"));
            assert_eq!(strategy.name(), name);
            assert_eq!(
                slc_cull::culler_by_name(name).unwrap().name(),
                strategy.name()
            );
        }
        assert_eq!(Strategy::by_name("bogus"), None);
    }
}
