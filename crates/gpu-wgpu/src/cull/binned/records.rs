//! `#[repr(C)]` twins of the `binned` strategy's WGSL structs (`records.wesl`); a unit test
//! compares their sizes with the layout naga computes from the linked kernels.
use bytemuck::{Pod, Zeroable};

/// The binned strategy's own parameters: the map from the image plane at unit depth to screen
/// pixels (`slc_cull`'s `CullView::screen_map`), X = u scale + offset per axis, and how its
/// bins split each subregion's VPLs. Keep in sync with `BinnedParams` in `records.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBinnedParams {
    /// scale (x, y), then offset (x, y).
    pub screen: [f32; 4],
    /// The bins' slices per subregion and rounds of 256 VPLs per slice (`bin_slices` in
    /// `cull/binned/mod.rs`), then two unused words.
    pub bins: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBinnedParams>() == 32);

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

/// One tile as the binned strategy's bins and lists test it (`binned_tiles.wesl` writes it).
/// Keep in sync with `BinnedTile` in `records.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBinnedTile {
    /// The rectangle (X0, Y0, X1, Y1) of its samples' screen positions, grown by `pad` for
    /// their rounding (X0 > X1 without samples).
    pub rect: [f32; 4],
    /// Their smallest view depth, shrunk for its rounding.
    pub near: f32,
    /// How much the rectangle is grown.
    pub pad: f32,
    pub unused: [u32; 2],
    /// Per strip of 16 x 2 pixels, the smallest and the largest (X, Y, depth, 0) of its
    /// samples.
    pub strips: [[f32; 4]; 16],
}
const _: () = assert!(std::mem::size_of::<GpuBinnedTile>() == 288);

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
        super::super::TILES_SOURCE => {
            GpuBinnedParams as "BinnedParams",
            GpuBinnedTile as "BinnedTile",
        }
        super::super::BINS_SOURCE => {
            GpuBinnedParams as "BinnedParams",
            GpuBinnedVpl as "BinnedVpl",
            GpuBinnedTile as "BinnedTile",
        }
    }
}
