//! Virtual spherical Gaussian lights (Tokuyoshi 2015, "Virtual Spherical Gaussian Lights for
//! Real-time Glossy Indirect Illumination"; "VSGL" below) built from a reflective shadow map.
//!
//! - [`TexelLobes`]: the per-VPL quantities of VSGL section 3.1.1 for one RSM texel, the
//!   reflectances `R_d`, `R_s` and the normalized lobes `G(ω; ξ_i, λ_i)/A(λ_i)` of its diffuse
//!   and specular radiant intensity.
//! - [`ClusterSums`]: the buffers of VSGL Fig. 4 (diffuse and specular weights, the weighted
//!   Toksvig mean vectors, the weighted position and squared norm), summable over any set of
//!   texels.
//! - [`MipRsm`]: the mipmapped reflective shadow map of VSGL section 4.1, one sum-based pyramid
//!   per RSM face laid out by a [`Quadtree`]: each texel of level `l` is a cluster of up to
//!   `4^l` VPLs.
//! - [`Vsgl`]: the light of one cluster, VSGL section 3.1 (`c_v`, `ξ_v`, `λ_v` per lobe, the
//!   positional mean `μ_v` and variance `σ_v²`, and the coefficient `c_v/(2πσ_v²)` of eq. 1).
//! - [`ImportanceMap`] and [`FilteredSampler`]: filtered importance sampling of clusters
//!   (section 4.2), by hierarchical sample warping of [`sample_points`] down the quadtree of
//!   importance masses, stopping at the level `l = l_max − ½ log2(N p(s))`.
//! - [`vsgl_radiance`] and [`shade_vsgls`]: shading (section 3.2, eq. 2-5), the incoming
//!   radiance of a VSGL as SGs (one per emitted lobe, three for a specular lobe of GGX's
//!   profile) against the receiver's diffuse + GGX lobe, eight VSGLs per vector, with an
//!   optional shadow ray to `μ_v`.
//! - [`bidirectional_importance`]: the optional importance of section 4.3, estimated with
//!   VSGLs generated on the G-buffer ([`camera_rsm`]).
mod bidirectional;
mod emitter;
mod emitter_lanes;
mod error;
mod importance;
mod light;
mod mip;
mod sampling;
mod shading;
mod sums;
mod texel;

pub use bidirectional::{bidirectional_importance, camera_rsm, FLUX_SHARE};
pub use error::VsglError;
pub use importance::ImportanceMap;
pub use light::Vsgl;
pub use mip::MipRsm;
pub use sampling::{
    point_shift, sample_points, Cluster, FilteredSampler, Footprint, SampleSet, WeightedCluster,
};
pub use shading::{shade_vsgls, vsgl_radiance};
pub use slc_core::vsgl::Quadtree;
pub use sums::{footprint_variance, ClusterSums};
pub use texel::TexelLobes;

#[cfg(test)]
mod sampling_tests;
#[cfg(test)]
mod shading_tests;
#[cfg(test)]
mod tests;
