//! The counter-based RNG of `crates/core/src/rng.rs` evaluated on the GPU by its WGSL twin
//! `rng.wesl`: the conformance pass that proves the two agree bit for bit (the ξ of
//! eq. 3 and the interleaved subregions must be the same numbers on both backends).
use crate::device::buffers::{output, read_back, uniform, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::vpl::records::{RngParams, RngSample};

/// The kernel of `rng_eval.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("rng_eval");
const WORKGROUP: u32 = 64;

/// Which numbers to draw: `stream` and `counter` of `hash4`, `seed`, and the interleaving
/// factor K of the subregion column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RngQuery {
    pub seed: u32,
    pub stream: u32,
    pub counter: u32,
    pub k: u32,
}

/// The compiled RNG evaluation pipeline.
pub struct RngPass {
    pipeline: wgpu::ComputePipeline,
}

impl RngPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("rng pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("rng", SOURCE),
            })
        })
    }

    /// Evaluates the WGSL twin for indices `0..count` and reads the results back. Errors if
    /// K is 0, the output exceeds the storage-binding limit, or the device fails.
    pub fn run(
        &self,
        ctx: &GpuContext,
        query: RngQuery,
        count: u32,
    ) -> Result<Vec<RngSample>, GpuError> {
        if query.k == 0 {
            return Err(GpuError::Input(
                "interleaving factor K must be at least 1".into(),
            ));
        }
        let samples = output::<RngSample>(ctx, "rng samples", count as usize)?;
        let grid = Grid::for_items(ctx, u64::from(count), WORKGROUP)?;
        ctx.scoped("rng", || {
            let params = uniform(
                ctx,
                "rng params",
                &RngParams {
                    seed: query.seed,
                    stream: query.stream,
                    counter: query.counter,
                    k: query.k,
                    count,
                    pad: [0; 3],
                },
            );
            ctx.dispatch("rng", &self.pipeline, &[&params, &samples], grid);
            Ok(())
        })?;
        read_back(ctx, "rng samples", &samples, count as usize)
    }
}
