//! Tiled culling and shading in one pass on the GPU (`tiled_shade.wesl`, the
//! paper's Fig. 2): after the bounds, partition and tile-depth passes of
//! [`TiledCuller::prepare`](crate::cull::list_passes::TileLayout::prepare), one workgroup
//! per tile tests its subregion's VPLs 256 at a time against the tile's frusta and shades
//! each pixel from the hits of its cluster, kept in workgroup memory. No list is counted,
//! scanned, stored or read back; the image equals `shade::lists` over the tiled culler's lists
//! (the same VPLs in the same order).
//!
//! This is the tiled strategies' frame path. The list passes stay where lists are needed:
//! the brute-force metrics, the clustered layout (32 slices per tile) and the tight
//! strategies' per-block refinement.
use crate::cull::frame::{read_status, CullFrame};
use crate::cull::list_passes::PreparedTiles;
use crate::cull::records::GpuCullParams;
use crate::device::buffers::output;
use crate::device::context::{GpuContext, GpuError};
use crate::shade::records::GpuShadeParams;
use std::mem::offset_of;

/// The kernel of `tiled_shade.wesl` without the feature `subgroups`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("tiled_shade");

/// The kernel of `tiled_shade.wesl` with the feature `subgroups`, linked with what it imports (build.rs).
pub(crate) const SUBGROUP_SOURCE: &str = kernel!("tiled_shade_subgroups");

/// The compiled one-pass pipeline.
pub struct TiledShadePass {
    pipeline: wgpu::ComputePipeline,
    subgroups: bool,
}

impl TiledShadePass {
    /// The kernel with subgroup operations where the device has them
    /// ([`GpuContext::subgroups`]), else with one atomic per hit: the same image.
    pub fn new(ctx: &GpuContext) -> Self {
        Self::with_subgroups(ctx, ctx.subgroups)
    }

    /// The kernel with (`true`, on a device that has them) or without subgroup operations.
    pub fn with_subgroups(ctx: &GpuContext, subgroups: bool) -> Self {
        let source = if subgroups { SUBGROUP_SOURCE } else { SOURCE };
        Self {
            pipeline: ctx.compute_pipeline("tiled shade", source),
            subgroups,
        }
    }

    /// Whether the kernel uses subgroup operations.
    pub fn subgroups(&self) -> bool {
        self.subgroups
    }

    /// The indirect image of `frame` (its `GpuSample`s in `samples`), culled as `tiles` and
    /// shaded in the same pass: RGB, 3 f32 per pixel row-major, left on the GPU. The culling
    /// passes' fault record is read afterwards (16 bytes): a sample behind the camera or a
    /// bound beyond f32 is an error, as with the lists.
    pub fn shade(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        samples: &wgpu::Buffer,
        tiles: &PreparedTiles,
    ) -> Result<wgpu::Buffer, GpuError> {
        let image = output::<f32>(ctx, "indirect image", 3 * tiles.pixels as usize)?;
        let count = &tiles.bounds.count;
        let params = GpuShadeParams {
            width: frame.width,
            height: frame.height,
            pixel_count: tiles.pixels,
            vpl_count: count.capacity(),
            list_count: 0,
            delta: frame.delta,
            scale: frame.interleaving.scale(),
            pad: 0,
        };
        ctx.submit("tiled shade", |encoder| {
            let cull = count.uniform(
                ctx,
                encoder,
                "tiled shade cull params",
                &tiles.params,
                offset_of!(GpuCullParams, vpl_count),
            );
            let shade = count.uniform(
                ctx,
                encoder,
                "tiled shade params",
                &params,
                offset_of!(GpuShadeParams, vpl_count),
            );
            ctx.encode_dispatch_at(
                encoder,
                "tiled shade",
                &self.pipeline,
                &tiles.bounds.vpls.with(&[
                    &cull,
                    &shade,
                    &tiles.frusta,
                    &tiles.bounds.buffer,
                    &tiles.partition.order,
                    samples,
                    &frame.positions,
                    &tiles.pixel_list,
                    &image,
                ]),
                tiles.grid,
            );
            Ok(())
        })?;
        read_status(ctx, &tiles.status, frame.width)?;
        Ok(image)
    }
}
