//! `sphere`: tiled culling (Modified HalfZ) with glossy VPLs bounded by the sphere of radius
//! r/α around the VPL (section 7, after Tokuyoshi and Harada 2016).
use crate::tiled::{cull, Clustering};
use crate::vpl_bounds::GlossyBound;
use slc_core::{CullError, CullInput, Culler, LightLists};

/// Tiled culling with the r/α sphere for glossy VPLs and the section-6 sphere for diffuse
/// ones, each tested against the boxes of the two Modified HalfZ frusta of every tile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SphereCuller;

impl Culler for SphereCuller {
    fn name(&self) -> &'static str {
        "sphere"
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        cull(input, GlossyBound::Sphere, Clustering::HalfZ)
    }
}
