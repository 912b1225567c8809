//! Why building, sampling or shading VSGLs failed.
use slc_bounds::BoundsError;

/// An error of the VSGL pipeline: invalid surface data reaching the SG math, or an importance
/// that cannot be sampled from.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum VsglError {
    /// A texel's or pixel's BRDF or lobe is out of the SG math's domain, or a derived quantity
    /// left the `f32` range.
    #[error(transparent)]
    Bounds(#[from] BoundsError),
    /// A VSGL's positional variance `σ_v²` must be positive and finite for eq. (1) and (4):
    /// build it with a positive floor ([`super::Vsgl::from_sums`]).
    #[error("a VSGL's positional variance must be positive and finite, got {0}")]
    Variance(f32),
    /// An importance value is negative or not finite, or does not match the map it is for.
    #[error("invalid VSGL importance: {0}")]
    Importance(String),
}
