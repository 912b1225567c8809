//! The parameters of the cross bilateral filter that removes the noise of interleaved
//! sampling (paper section 6), one type for every backend's filter.

/// Parameters of the cross bilateral filter: a spatial Gaussian weighted by how alike the
/// neighbours' depth and normal are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BilateralParams {
    /// Kernel radius in pixels (8 in the paper).
    pub radius: u32,
    /// Spatial standard deviation in pixels.
    pub sigma_spatial: f32,
    /// Standard deviation of the relative depth difference |z − z'| / z.
    pub sigma_depth: f32,
    /// Exponent of the normal weight max(n·n', 0)^(2^k): k squarings.
    pub normal_squarings: u32,
}

impl Default for BilateralParams {
    fn default() -> Self {
        Self {
            radius: 8,
            sigma_spatial: 4.0,
            sigma_depth: 0.05,
            normal_squarings: 5,
        }
    }
}
