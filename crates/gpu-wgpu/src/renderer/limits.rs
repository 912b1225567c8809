//! The sizes a frame's largest storage buffers take, checked against the adapter's binding
//! limit before any work ([`Renderer::check`](slc_core::Renderer::check)), so a frame too large
//! for this adapter (`--rsm 2048` on lavapipe, whose bindings hold 128 MiB) is refused with
//! what to lower and how far, not by a pass halfway through.
use crate::device::GpuContext;
use crate::frame::light::records::GpuRsmTexel;
use crate::frame::raster::records::GpuSample;
use crate::renderer::GpuRenderer;
use crate::vpl::buffers::VplBuffers;
use crate::vpl::generate::VplLobes;
use crate::vpl::records::GpuVpl;
use slc_core::frame::{RenderError, RenderSettings};
use slc_core::Capabilities;
use std::mem::size_of;

/// Refuses `settings` when the G-buffer or one RSM face exceed one storage binding, or the
/// VPL records of one single-face light (the least any scene with a light has) the two that
/// [`VplBuffers`] spreads them over. The VPLs' bounds (one binding, sized by the VPLs a frame
/// makes: `GpuVpls::fit_capacity`) are checked once their number is known.
pub fn check_frame_size(ctx: &GpuContext, settings: &RenderSettings) -> Result<(), RenderError> {
    let limit = ctx.limits.max_storage_buffer_binding_size;
    let texels = u64::from(settings.rsm_resolution).pow(2);
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    // VPL generation leaves room for one record per texel and lobe `--lobes` selects
    // (`vpl::generate`).
    let lobes = u64::from(VplLobes::from(settings.lobes).per_texel());
    let records = 2 * VplBuffers::per_binding(ctx) as u64;
    let texels_fitting = (limit / size_of::<GpuRsmTexel>() as u64).min(records / lobes.max(1));
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
    if texels > texels_fitting {
        let most = (texels_fitting as f64).sqrt().floor();
        return refuse(format!(
            "RSM {n}² ({texels} texels of {} bytes per face and up to {lobes} VPLs of {} bytes \
             a texel; at most --rsm {most} here)",
            size_of::<GpuRsmTexel>(),
            size_of::<GpuVpl>(),
            n = settings.rsm_resolution,
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
