//! `#[repr(C)]` twins of the `binned` strategy's WGSL structs (`records.wesl`); a unit test
//! compares their sizes with the layout naga computes from the linked kernels.
use bytemuck::{Pod, Zeroable};

/// The map from the image plane at unit depth to screen pixels (`slc_cull`'s
/// `CullView::screen_map`): X = u scale + offset per axis. Keep in sync with `BinnedParams`
/// in `records.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBinnedParams {
    /// scale (x, y), then offset (x, y).
    pub screen: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBinnedParams>() == 16);

/// One VPL as the binned strategy's tiles and pixels test it (`binned_footprint.wesl` writes
/// it). Keep in sync with `BinnedVpl` in `records.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBinnedVpl {
    /// The screen rectangle (X0, Y0, X1, Y1) its bound may cover (±`f32::MAX` where the
    /// bound reaches the eye's plane).
    pub rect: [f32; 4],
    /// The VPL's position q (xyz) and its bound's largest view depth (w).
    pub q_far: [f32; 4],
    /// The VPL's normal (xyz) and the limit of the per-pixel test (w).
    pub normal_limit: [f32; 4],
    /// The bound relative to q, as [`crate::cull::records::GpuLocalBound`].
    pub center_along: [f32; 4],
    pub axis_across: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBinnedVpl>() == 80);

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        super::super::FOOTPRINT_SOURCE => {
            GpuBinnedParams as "BinnedParams",
            GpuBinnedVpl as "BinnedVpl",
        }
        super::super::SOURCE => {
            GpuBinnedParams as "BinnedParams",
            GpuBinnedVpl as "BinnedVpl",
        }
    }
}
