//! The sizes a frame's largest storage buffers take, checked against the adapter's binding
//! limit before any work ([`Renderer::check`](slc_core::Renderer::check)), so a frame too large
//! for this adapter (`--rsm 1024` with both lobes on lavapipe, whose bindings hold 128 MiB) is
//! refused with what to lower and how far, not by a pass halfway through.
use crate::device::GpuContext;
use crate::frame::light::records::GpuRsmTexel;
use crate::frame::raster::records::GpuSample;
use crate::renderer::GpuRenderer;
use crate::vpl::generate::VplLobes;
use crate::vpl::records::GpuVpl;
use slc_core::frame::{RenderError, RenderSettings};
use slc_core::Capabilities;
use std::mem::size_of;

/// Refuses `settings` when the G-buffer, one RSM face or the VPLs of one single-face light
/// (the least any scene with a light has) exceed one storage binding.
pub fn check_frame_size(ctx: &GpuContext, settings: &RenderSettings) -> Result<(), RenderError> {
    let limit = ctx.limits.max_storage_buffer_binding_size;
    // VPL generation leaves room for one record per texel and lobe `--lobes` selects
    // (`vpl::generate`).
    let texels = u64::from(settings.rsm_resolution).pow(2);
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let per_texel_with = |vpls_per_texel: u64| {
        (size_of::<GpuRsmTexel>() as u64).max(vpls_per_texel * size_of::<GpuVpl>() as u64)
    };
    let per_texel = per_texel_with(u64::from(VplLobes::from(settings.lobes).per_texel()));
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
        // Both lobes make two VPLs per texel; one lobe may fit where both do not.
        let n = settings.rsm_resolution;
        let one_lobe = if texels * per_texel_with(1) <= limit {
            format!(", or --rsm {n} with one lobe (--lobes glossy or --lobes diffuse)")
        } else {
            String::new()
        };
        return refuse(format!(
            "RSM {n}² ({texels} texels of {per_texel} bytes per face, {} bytes; at most --rsm \
             {most} here{one_lobe})",
            texels * per_texel,
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
