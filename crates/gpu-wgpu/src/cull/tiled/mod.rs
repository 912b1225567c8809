//! Tiled light culling on the GPU (paper sections 5-6, supplemental Listing 2): per-VPL
//! bounds (`cull::bounds`), the subregions' VPLs (`cull::partition`), Modified HalfZ tile
//! frusta (`cull::tiled::depth`), then
//! `tiled_cull.wesl` twice, counting and then writing each tile cluster's list, with
//! the offsets from `device::scan` in between. Tiles are 16 x 16 pixels of each interleaved
//! subregion image (section 6, Fig. 8) and test only their subregion's VPLs. The result,
//! read back, is a [`slc_core::LightLists`] in the CPU's convention: empty lists are dropped, every
//! list ascends in the VPL index, and each pixel with a sample points to its cluster's list.
//!
//! Counting and writing run in one submission, into a buffer of the room earlier frames'
//! lists needed (`cull::room`): no count is read back inside a frame; lists that outgrew
//! their buffer are culled again with the total their fault record reports. A total beyond
//! the storage-binding limit is refused ([`GpuError::BufferTooLarge`]).
//! [`ListCulling::cull_on_gpu`](crate::cull::ListCulling::cull_on_gpu) leaves the lists on the GPU for `shade::lists` instead;
//! [`TiledCuller::prepare`] stops before the lists, for the one-pass culling and shading of
//! `shade::tiled`, and [`TiledCuller::lists`] builds them from there. With
//! [`GlossyBound::Tight`](slc_cull::GlossyBound::Tight) the lists are refined per block (`cull::tight`).
pub mod depth;

use crate::cull::list_passes::{DepthEncoder, ListKernel, ListPasses, PreparedTiles, TileLayout};
use crate::cull::records::{GpuCullParams, GpuTileFrusta};
use crate::cull::tight::BaseLayout;
use crate::cull::tiled::depth::{TileDepthBuffers, TileDepthPass};
use crate::device::context::{GpuContext, GpuError};
use std::mem::offset_of;

/// The kernel of `tiled_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("tiled_cull");

/// The tiled culler's pipelines (sphere, enclosing-sphere, ellipsoid and tight strategies,
/// by the [`GlossyBound`](slc_cull::GlossyBound) passed to [`ListCulling::cull`](crate::cull::ListCulling::cull)).
pub struct TiledCuller {
    passes: ListPasses,
    depth: TileDepthPass,
    pipeline: wgpu::ComputePipeline,
}

impl TileLayout for TiledCuller {
    type Prepared = PreparedTiles;
    type Frusta = GpuTileFrusta;
    const DEPTH: (&'static str, u32) = ("tile depth", 2);

    fn passes(&self) -> &ListPasses {
        &self.passes
    }

    /// The Modified HalfZ frusta of every tile, with each pixel's cluster.
    fn encode_depth(
        &self,
        on: DepthEncoder,
        tiles: PreparedTiles,
    ) -> Result<PreparedTiles, GpuError> {
        let depth_params = tiles.bounds.count.uniform(
            on.ctx,
            on.encoder,
            "cull params (depth)",
            &tiles.params,
            offset_of!(GpuCullParams, vpl_count),
        );
        let buffers = TileDepthBuffers {
            params: &depth_params,
            positions: &on.frame.positions,
            frusta: &tiles.frusta,
            pixel_list: &tiles.pixel_list,
            status: &tiles.status,
            sub_offsets: &tiles.partition.sub_offsets,
        };
        self.depth.encode(on.ctx, on.encoder, &buffers, tiles.grid);
        Ok(tiles)
    }

    /// Two lists per tile, counted and written by `tiled_cull.wesl`.
    fn kernel<'a>(&'a self, tiles: &'a PreparedTiles) -> ListKernel<'a> {
        ListKernel {
            label: "tiled cull",
            pipeline: &self.pipeline,
            layout: BaseLayout {
                clusters: 2,
                split: true,
            },
            tiles,
            own: vec![&tiles.partition.order],
        }
    }
}

impl TiledCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let (passes, (depth, pipeline)) = ListPasses::new(ctx, "tiled culling pipelines", || {
            (
                TileDepthPass::new(ctx),
                ctx.compute_pipeline("tiled cull", SOURCE),
            )
        })?;
        Ok(Self {
            passes,
            depth,
            pipeline,
        })
    }
}
