//! `clustered`: 3D clusters (Olsson et al. 2012; the paper's section-7 comparison uses 32
//! depth clusters per 16x16 tile). Each tile of a subregion image is cut into 32 exponential
//! depth slices of the G-buffer's depth range (its nearest to its farthest sample, rather
//! than the camera's znear..zfar, so no slice is wasted on empty depths); a cluster exists
//! only where some pixel falls, and is tested with the depth range of its own pixels.
use crate::tiled::{cull, Clustering};
use crate::vpl_bounds::GlossyBound;
use slc_core::{CullError, CullInput, Culler, LightLists};

/// Clustered culling with the given bound for glossy VPLs (the section-6 sphere for diffuse
/// ones). Named `clustered` with ellipsoids, `clustered-sphere` with the r/α sphere and
/// `clustered-enclosing-sphere` with the sphere around the spheroid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClusteredCuller {
    pub glossy_bound: GlossyBound,
}

impl Culler for ClusteredCuller {
    fn name(&self) -> &'static str {
        match self.glossy_bound {
            GlossyBound::Ellipsoid => "clustered",
            GlossyBound::Sphere => "clustered-sphere",
            GlossyBound::EnclosingSphere => "clustered-enclosing-sphere",
        }
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        cull(input, self.glossy_bound, Clustering::ExponentialSlices)
    }
}
