//! `binned`: each VPL's bound mapped to the rectangle of pixels it may cover in its
//! subregion image (scatter instead of gather; `crate::binned`, docs/many-vpls.md), then
//! tested at every pixel of the rectangle, or, for rectangles larger than a tile, at every
//! 4 x 4 cell of it against the box of the cell's samples. A list per pixel, holding every
//! VPL whose bound contains the pixel's G-buffer point (not behind the VPL), and a list per
//! cell shared by its pixels: the paper's bounds at a pixel's or a cell's granularity, at a
//! cost that follows the pixels the bounds cover rather than VPLs × tiles.
use crate::binned::LARGE_PIXELS;
use slc_core::{CullError, CullInput, Culler, LightLists, Strategy};

/// The culler of `binned`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BinnedCuller {
    /// A VPL whose rectangle covers more pixels than this is culled per cell into the
    /// pixels' shared lists ([`LightLists::shared_list`]) instead of pixel by pixel; `u64::MAX`
    /// tests every VPL per pixel, as the GPU's `binned` does.
    pub shared_above: u64,
}

impl Default for BinnedCuller {
    /// Rectangles larger than a tile (256 pixels) shared per cell.
    fn default() -> Self {
        Self {
            shared_above: LARGE_PIXELS,
        }
    }
}

impl BinnedCuller {
    /// Every VPL tested at every pixel of its rectangle: one list per pixel, as the GPU's.
    pub fn per_pixel() -> Self {
        Self {
            shared_above: u64::MAX,
        }
    }
}

impl Culler<CullInput<'_>> for BinnedCuller {
    type Lists = LightLists;
    type Error = CullError;

    fn strategy(&self) -> Strategy {
        Strategy::Binned
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        crate::binned::cull(input, self.shared_above)
    }
}
