//! The GPU's rasterization baselines (`splatting`, `clustered-raster`; `Strategy::RASTER`)
//! as a CPU culler: they draw bounding meshes with the GPU's rasterizer and have no CPU twin,
//! so culling with them here is a clear error rather than some other strategy's lists.
use slc_core::{CullError, CullInput, Culler, LightLists, Strategy};

/// A strategy only the GPU backend runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GpuOnly(pub Strategy);

impl Culler<CullInput<'_>> for GpuOnly {
    type Lists = LightLists;
    type Error = CullError;

    fn strategy(&self) -> Strategy {
        self.0
    }

    fn cull(&self, _input: &CullInput) -> Result<LightLists, CullError> {
        Err(CullError::Input(format!(
            "culling strategy '{}' rasterizes bounding meshes on the GPU (--backend gpu); \
             the CPU has no culler for it",
            self.0
        )))
    }
}
