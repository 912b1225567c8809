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
    /// An importance value is negative or not finite, or does not match the map it is for.
    #[error("invalid VSGL importance: {0}")]
    Importance(String),
}
