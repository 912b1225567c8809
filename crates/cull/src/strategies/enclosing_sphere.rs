//! `enclosing-sphere`: tiled culling (Modified HalfZ) with glossy VPLs bounded by the sphere
//! of radius r_u around the spheroid's centre c, which encloses the spheroid (section 7).
use crate::tiled::{cull, Clustering};
use crate::vpl_bounds::GlossyBound;
use slc_core::{CullError, CullInput, Culler, LightLists};

/// Tiled culling with the sphere enclosing the GGX spheroid for glossy VPLs and the section-6
/// sphere for diffuse ones, against the two Modified HalfZ frusta of every tile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnclosingSphereCuller;

impl Culler for EnclosingSphereCuller {
    fn name(&self) -> &'static str {
        "enclosing-sphere"
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        cull(input, GlossyBound::EnclosingSphere, Clustering::HalfZ)
    }
}
