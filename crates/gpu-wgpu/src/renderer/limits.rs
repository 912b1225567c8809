//! The sizes a frame's largest storage buffers take, checked against the adapter's binding
//! limit before any work ([`Renderer::check`](slc_core::Renderer::check)), so a frame too large
//! for this adapter (`--rsm 1024` on lavapipe, whose bindings hold 128 MiB) is refused with
//! what to lower and how far, not by a pass halfway through.
use crate::device::GpuContext;
use crate::frame::light::records::GpuRsmTexel;
use crate::frame::raster::records::GpuSample;
use crate::renderer::GpuRenderer;
use crate::vpl::records::GpuVpl;
use slc_core::frame::{RenderError, RenderSettings};
use slc_core::Capabilities;
use std::mem::size_of;

/// Refuses `settings` when the G-buffer, one RSM face or the VPLs of one single-face light
/// (the least any scene with a light has) exceed one storage binding.
pub fn check_frame_size(ctx: &GpuContext, settings: &RenderSettings) -> Result<(), RenderError> {
    let limit = ctx.limits.max_storage_buffer_binding_size;
    // VPL generation leaves room for both lobes of every texel whatever `--lobes` selects
    // (`vpl::generate`: two records per texel).
    let texels = u64::from(settings.rsm_resolution).pow(2);
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let per_texel = (size_of::<GpuRsmTexel>() as u64).max(2 * size_of::<GpuVpl>() as u64);
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
    if texels * per_texel > limit {
        let most = ((limit / per_texel) as f64).sqrt().floor();
        return refuse(format!(
            "RSM {n}² ({texels} texels of {per_texel} bytes per face, {} bytes; at most --rsm {most} here)",
            texels * per_texel,
            n = settings.rsm_resolution
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
