//! `#[repr(C)]` twin of the WGSL struct of the cross bilateral filter, in the convention of
//! every `records.rs` (a compile-time size check and a unit test against the layout naga
//! computes from the shader).
use bytemuck::{Pod, Zeroable};

/// `GpuBilateralParams::axis`: along x (demodulating the image), then along y
/// (remodulating the result).
pub const PASS_HORIZONTAL: u32 = 0;
pub const PASS_VERTICAL: u32 = 1;

/// Parameters of one pass of the cross bilateral filter. Keep in sync with
/// `BilateralParams` in `bilateral.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBilateralParams {
    /// The camera position (xyz): a sample's depth is `(position − eye)·forward`.
    pub eye: [f32; 4],
    /// The camera's unit forward axis (xyz).
    pub forward: [f32; 4],
    pub width: u32,
    pub height: u32,
    /// Kernel radius r in pixels (2r + 1 taps per pass).
    pub radius: u32,
    /// k of the normal weight max(n·n', 0)^(2^k).
    pub normal_squarings: u32,
    /// 1 / (2 σ_s²) of the spatial Gaussian.
    pub inv_2ss: f32,
    /// 1 / (2 σ_z²) of the relative depth difference.
    pub inv_2sd: f32,
    /// [`PASS_HORIZONTAL`] or [`PASS_VERTICAL`].
    pub axis: u32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuBilateralParams>() == 64);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::raster::records::GpuSample;

    wgsl_twins! {
        crate::frame::denoise::SOURCE => {
            GpuBilateralParams as "BilateralParams",
            GpuSample as "Sample",
        }
    }
}
