//! The sizes a frame's largest storage buffers take, checked against the adapter's binding
//! limit before any work ([`Renderer::check`](slc_core::Renderer::check)), so a frame too large
//! for this adapter (`--rsm 1024` with both lobes on lavapipe, whose bindings hold 128 MiB)
//! is refused with what to lower and how far, not by a pass halfway through.
use crate::cull::binned::records::GpuBinnedVpl;
use crate::cull::records::{GpuBound, GpuBoxBound};
use crate::device::GpuContext;
use crate::frame::light::records::GpuRsmTexel;
use crate::frame::raster::records::GpuSample;
use crate::renderer::GpuRenderer;
use crate::vpl::buffers::VplBuffers;
use crate::vpl::generate::VplLobes;
use crate::vpl::records::GpuVpl;
use slc_core::frame::{Method, RenderError, RenderSettings};
use slc_core::{Capabilities, GlossyBound};
use std::mem::size_of;

/// Refuses `settings` when the G-buffer or one RSM face exceed one storage binding, or the
/// VPLs of one single-face light (the least any scene with a light has) the room the
/// culling keeps for them: their records in the two bindings [`VplBuffers`] spreads them
/// over, and one record per VPL in one binding (its bound: [`per_vpl_bytes`]).
pub fn check_frame_size(ctx: &GpuContext, settings: &RenderSettings) -> Result<(), RenderError> {
    let limit = ctx.limits.max_storage_buffer_binding_size;
    let texels = u64::from(settings.rsm_resolution).pow(2);
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    // VPL generation leaves room for one VPL per texel and lobe `--lobes` selects
    // (`vpl::generate`).
    let texels_fitting = |lobes: u64| {
        let vpls = (2 * VplBuffers::per_binding(ctx) as u64).min(limit / per_vpl_bytes(settings));
        (limit / size_of::<GpuRsmTexel>() as u64).min(vpls / lobes.max(1))
    };
    let lobes = u64::from(VplLobes::from(settings.lobes).per_texel());
    let per_pixel = size_of::<GpuSample>() as u64;
    let refuse = |what: String| {
        Err(RenderError::Unsupported {
            backend: GpuRenderer::NAME,
            what: format!(
                "{what}, more than the {limit} bytes one storage binding holds on {}",
                ctx.adapter_name
            ),
            needs: Capabilities::needed(settings),
        })
    };
    if texels > texels_fitting(lobes) {
        let most = (texels_fitting(lobes) as f64).sqrt().floor();
        // Both lobes make two VPLs per texel; one lobe may fit where both do not.
        let n = settings.rsm_resolution;
        let one_lobe = if lobes > 1 && texels <= texels_fitting(1) {
            format!(", or --rsm {n} with one lobe (--lobes glossy or --lobes diffuse)")
        } else {
            String::new()
        };
        return refuse(format!(
            "RSM {n}² ({texels} texels of {} bytes per face and up to {lobes} VPLs a texel, \
             each with a record of {} bytes and a bound of {} bytes; at most --rsm {most} \
             here{one_lobe})",
            size_of::<GpuRsmTexel>(),
            size_of::<GpuVpl>(),
            per_vpl_bytes(settings),
        ));
    }
    if pixels * per_pixel > limit {
        return refuse(format!(
            "{}x{} ({pixels} pixels of {per_pixel} bytes, {} bytes; at most {} pixels here)",
            settings.width,
            settings.height,
            pixels * per_pixel,
            limit / per_pixel
        ));
    }
    Ok(())
}

/// The bytes of the largest record the culling of `settings` keeps per VPL in one binding:
/// the bounds over boxes of the tight strategies' refinement, else the bound (`binned`'s
/// per-VPL records are as large).
fn per_vpl_bytes(settings: &RenderSettings) -> u64 {
    let tight = matches!(settings.method, Method::Stochastic(s)
        if s.strategy.parts().1 == GlossyBound::Tight);
    let bytes = match tight {
        true => size_of::<GpuBoxBound>(),
        false => size_of::<GpuBound>().max(size_of::<GpuBinnedVpl>()),
    };
    bytes as u64
}
