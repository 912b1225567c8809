//! Clustered light culling on the GPU, the twin of `slc_cull`'s `clustered`,
//! `clustered-sphere` and `clustered-enclosing-sphere` strategies (`ClusteredCuller`; 3D
//! clusters after Olsson et al. 2012, the paper's section-7 comparison): the tiles of
//! `cull::tiled` (16 x 16 pixels of each interleaved subregion image, section 6) cut
//! into 32 exponential slices of the G-buffer's depth range instead of Modified HalfZ's two.
//!
//! Per-VPL bounds (`cull::bounds`) and the subregions' VPLs (`cull::partition`) as in the tiled
//! culler, then `cluster_depth.wesl` twice (the G-buffer's depth range, then each
//! tile's slices, their depth ranges and each pixel's slice) and `clustered_cull.wesl`
//! twice (count and write each slice's list, with the offsets from `device::scan` in between).
//! A slice exists where some pixel falls and is tested with the depth range of its own pixels;
//! lists ascend in the VPL index. Read back, the result is a [`slc_core::LightLists`] in the CPU's
//! convention (empty lists dropped); [`ListCulling::cull_on_gpu`](crate::cull::ListCulling::cull_on_gpu) leaves the lists on the
//! GPU for `shade::lists` instead.
//!
//! The GPU decides in f32 what the CPU decides in f64 (view depths, slice boundaries, box
//! tests): a sample within rounding of a slice boundary may fall in the neighbouring slice.
pub mod records;

use crate::cull::clustered::records::{GpuClusterFrusta, CLUSTER_SLICES, DEPTH_RANGE, DEPTH_SPLIT};
use crate::cull::list_passes::{DepthEncoder, ListKernel, ListPasses, PreparedTiles, TileLayout};
use crate::cull::records::GpuCullParams;
use crate::cull::tight::BaseLayout;
use crate::device::buffers::upload;
use crate::device::context::{GpuContext, GpuError};
use std::mem::offset_of;

/// The kernel of `cluster_depth.wesl`, linked with what it imports (build.rs).
pub(crate) const DEPTH_SOURCE: &str = kernel!("cluster_depth");

/// The kernel of `clustered_cull.wesl`, linked with what it imports (build.rs).
pub(crate) const CULL_SOURCE: &str = kernel!("clustered_cull");

/// The clustered culler's pipelines (the four clustered strategies, by the
/// [`GlossyBound`](slc_cull::GlossyBound) passed to [`ListCulling::cull`](crate::cull::ListCulling::cull)).
pub struct ClusteredCuller {
    passes: ListPasses,
    depth: wgpu::ComputePipeline,
    cull: wgpu::ComputePipeline,
}

impl TileLayout for ClusteredCuller {
    type Prepared = PreparedClusters;
    type Frusta = GpuClusterFrusta;
    const DEPTH: (&'static str, u32) = ("cluster depth", CLUSTER_SLICES);

    fn passes(&self) -> &ListPasses {
        &self.passes
    }

    /// The G-buffer's depth range, then each tile's occupied slices with each pixel's slice.
    fn encode_depth(
        &self,
        on: DepthEncoder,
        tiles: PreparedTiles,
    ) -> Result<PreparedClusters, GpuError> {
        // Smallest and largest depth as f32 bits, before any sample is seen.
        let depth_range = upload(on.ctx, "depth range", &[u32::MAX, 0])?;
        for (label, mode) in [
            ("cluster depth range", DEPTH_RANGE),
            ("cluster depth split", DEPTH_SPLIT),
        ] {
            let params = GpuCullParams {
                mode,
                ..tiles.params
            };
            let at = offset_of!(GpuCullParams, vpl_count);
            let params = tiles
                .bounds
                .count
                .uniform(on.ctx, on.encoder, label, &params, at);
            on.ctx.encode_dispatch(
                on.encoder,
                label,
                &self.depth,
                &[
                    &params,
                    &on.frame.positions,
                    &tiles.frusta,
                    &tiles.pixel_list,
                    &tiles.status,
                    &depth_range,
                ],
                tiles.grid,
            );
        }
        Ok(PreparedClusters { tiles, depth_range })
    }

    /// One list per depth slice, counted and written by `clustered_cull.wesl`.
    fn kernel<'a>(&'a self, clusters: &'a PreparedClusters) -> ListKernel<'a> {
        let tiles = &clusters.tiles;
        ListKernel {
            label: "clustered cull",
            pipeline: &self.cull,
            layout: BaseLayout {
                clusters: CLUSTER_SLICES,
                split: false,
            },
            tiles,
            own: vec![&tiles.partition.sub_offsets, &tiles.partition.order],
        }
    }
}

impl ClusteredCuller {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let (passes, (depth, cull)) = ListPasses::new(ctx, "clustered culling pipelines", || {
            (
                ctx.compute_pipeline("cluster depth", DEPTH_SOURCE),
                ctx.compute_pipeline("clustered cull", CULL_SOURCE),
            )
        })?;
        Ok(Self {
            passes,
            depth,
            cull,
        })
    }
}

/// A clustered culling up to its cluster frusta ([`ClusteredCuller::prepare`]): what the
/// list passes and the rasterized clusters (`cull::raster::clusters`) read.
pub struct PreparedClusters {
    /// The tile grid's passes; `GpuClusterFrusta` per tile (occupied slices in `info.x`),
    /// each pixel's cluster (32 t + slice; `NO_LIST` without a sample).
    pub tiles: PreparedTiles,
    /// The G-buffer's smallest and largest view depth as f32 bits.
    pub depth_range: wgpu::Buffer,
}
