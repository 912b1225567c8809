//! `binned`: each VPL's bound binned into the tiles its screen rectangle overlaps, then
//! tested at every pixel of the rectangle (scatter instead of gather; `crate::binned`,
//! docs/many-vpls.md). A list per pixel, holding every VPL whose bound contains the pixel's
//! G-buffer point (not behind the VPL): the paper's bounds at the finest granularity, at a
//! cost that follows the pixels the bounds cover rather than VPLs × tiles.
use slc_core::{CullError, CullInput, Culler, LightLists, Strategy};

/// The culler of `binned`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BinnedCuller;

impl Culler<CullInput<'_>> for BinnedCuller {
    type Lists = LightLists;
    type Error = CullError;

    fn strategy(&self) -> Strategy {
        Strategy::Binned
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        crate::binned::cull(input)
    }
}
