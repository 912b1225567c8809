//! `ellipsoid`: the paper's method. Tiled culling (Modified HalfZ, section 5.1) with glossy
//! VPLs bounded by the GGX spheroid (eq. 12-15), tested as a unit sphere in the stretched and
//! rotated space BS (eq. 16-17) against the box of each cluster frustum's image there
//! (section 5.2, supplemental Listing 2).
use crate::tiled::{cull, Clustering};
use crate::vpl_bounds::GlossyBound;
use slc_core::{CullError, CullInput, Culler, LightLists};

/// Tiled culling with bounding ellipsoids for glossy VPLs and the section-6 sphere for
/// diffuse ones, against the two Modified HalfZ frusta of every tile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EllipsoidCuller;

impl Culler for EllipsoidCuller {
    fn name(&self) -> &'static str {
        "ellipsoid"
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        cull(input, GlossyBound::Ellipsoid, Clustering::HalfZ)
    }
}
