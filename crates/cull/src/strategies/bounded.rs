//! Every strategy that tests bounds (Strategy::parts): tiled culling (Modified HalfZ,
//! section 5.1, two depth clusters per 16×16 tile of each subregion image) or clustered
//! culling (Olsson et al. 2012; the paper's section-7 comparison: 32 exponential depth slices
//! of the G-buffer's depth range per tile, a cluster only where some pixel falls, tested with
//! the depth range of its own pixels). Diffuse VPLs are bounded by the section-6 sphere;
//! glossy ones by
//! - `Sphere`: the sphere of radius r/α around the VPL (section 7, after Tokuyoshi and Harada
//!   2016);
//! - `EnclosingSphere`: the sphere of radius r_u around the spheroid's centre c (section 7);
//! - `Ellipsoid`: the GGX spheroid of eq. 12-15, tested as a unit sphere in the stretched and
//!   rotated space BS (eq. 16-17) against the box of each cluster frustum's image there
//!   (section 5.2, supplemental Listing 2): the paper's method.
use crate::tiled::{cull, BoundedMemory, Clustering};
use slc_core::{CullError, CullInput, Culler, Layout, LightLists, Strategy};

/// The culler of a bound-testing strategy (any but `none`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BoundedCuller {
    strategy: Strategy,
    clustering: Clustering,
}

impl BoundedCuller {
    /// The culler of `strategy`, or `None` for the unculled layout and the GPU's raster
    /// baselines.
    pub fn new(strategy: Strategy) -> Option<Self> {
        let clustering = match strategy.parts().0 {
            Layout::Unculled | Layout::Splatting | Layout::ClusteredRaster | Layout::Binned => {
                return None
            }
            Layout::Tiled => Clustering::HalfZ,
            Layout::Clustered => Clustering::ExponentialSlices,
        };
        Some(Self {
            strategy,
            clustering,
        })
    }

    /// [`Culler::cull`] with its bounds, the G-buffer's positions and `tight`'s refinement
    /// formed in `memory`, which a caller keeps from frame to frame ([`BoundedMemory`]): the
    /// same lists, without the page faults of a few hundred MB of fresh memory at a million
    /// VPLs.
    pub fn cull_in(
        &self,
        input: &CullInput,
        memory: &mut BoundedMemory,
    ) -> Result<LightLists, CullError> {
        cull(input, self.strategy.parts().1, self.clustering, memory)
    }
}

impl Culler<CullInput<'_>> for BoundedCuller {
    type Lists = LightLists;
    type Error = CullError;

    fn strategy(&self) -> Strategy {
        self.strategy
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        self.cull_in(input, &mut BoundedMemory::default())
    }
}
