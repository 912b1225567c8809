//! The sizes of a frame's textures and largest storage buffers, checked against the device's
//! limits before any work ([`Renderer::check`](slc_core::Renderer::check)), so a frame too
//! large for this device (`--rsm 2048` on lavapipe, whose bindings hold 128 MiB) is refused
//! with what to lower and how far, not by a pass halfway through.
use crate::device::buffers::per_binding;
use crate::device::GpuContext;
use crate::frame::light::records::GpuRsmTexel;
use crate::frame::raster::records::GpuSample;
use crate::renderer::GpuRenderer;
use crate::vpl::generate::VplLobes;
use crate::vpl::records::GpuVpl;
use slc_core::frame::{RenderError, RenderSettings};
use slc_core::Capabilities;
use std::mem::size_of;

/// Refuses `settings` when the image or the RSM is wider or taller than the device's 2-D
/// textures (`max_texture_dimension_2d`: the G-buffer and each RSM face are rasterized into
/// them), the G-buffer or one RSM face exceed one storage buffer
/// ([`GpuContext::storage_limit`]), or the VPL records of one single-face light (the least
/// any scene with a light has) the two that
/// [`VplBuffers`](crate::vpl::buffers::VplBuffers) spreads them over: what is known
/// before the scene ([`check_scene_size`] once it is). The VPLs' bounds (one binding, sized
/// by the VPLs a frame makes: `GpuVpls::fit_capacity`) are checked once their number is
/// known.
pub fn check_frame_size(ctx: &GpuContext, settings: &RenderSettings) -> Result<(), RenderError> {
    check_scene_size(ctx, settings, &[1])
}

/// [`check_frame_size`] for lights whose maps have `faces` faces each (a spot light's one, a
/// point light's cube six): each light's RSM texels lie in one binding, and the VPL records
/// of all of them in two. Run before a frame's first pass. The largest `--rsm` it names is
/// what the texels and the records allow; the VPLs' bounds, sized by the VPLs made (fewer
/// than the texels where some see nothing), may still outgrow their binding there, refused
/// by name once the count is known.
pub fn check_scene_size(
    ctx: &GpuContext,
    settings: &RenderSettings,
    faces: &[usize],
) -> Result<(), RenderError> {
    let refuse = |what: String| {
        Err(RenderError::Unsupported {
            backend: GpuRenderer::NAME,
            what: format!("{what} on {}", ctx.adapter_name),
            needs: Capabilities::needed(settings),
        })
    };
    let side = ctx.limits.max_texture_dimension_2d;
    let (width, height, n) = (settings.width, settings.height, settings.rsm_resolution);
    if width.max(height).max(n) > side {
        return refuse(format!(
            "{width}x{height} with RSM {n}²: more than the {side} texels a side 2-D textures \
             hold"
        ));
    }
    let limit = ctx.storage_limit();
    let texels = u64::from(n).pow(2);
    let pixels = u64::from(width) * u64::from(height);
    let beyond = |what: String| {
        refuse(format!(
            "{what}, more than the {limit} bytes one storage binding holds"
        ))
    };
    // Per face: one light's faces share its texels' binding; VPL generation leaves room for
    // one record per texel of every face and lobe `--lobes` selects (`vpl::generate`) in two.
    let (most_faces, all_faces) = (
        faces.iter().copied().max().unwrap_or(0) as u64,
        faces.iter().sum::<usize>() as u64,
    );
    let lobes = u64::from(VplLobes::from(settings.lobes).per_texel());
    let records = 2 * per_binding::<GpuVpl>(ctx) as u64;
    let texels_fitting = (limit / size_of::<GpuRsmTexel>() as u64 / most_faces.max(1))
        .min(records / (lobes * all_faces).max(1));
    if texels > texels_fitting && all_faces > 0 {
        let most = (texels_fitting as f64).sqrt().floor();
        let lights = match (faces.len(), all_faces) {
            (1, 1) => "1 face".to_owned(),
            (1, _) => format!("{all_faces} faces"),
            (count, _) => format!("{all_faces} faces of {count} lights"),
        };
        return beyond(format!(
            "RSM {n}² over {lights} ({texels} texels of {} bytes per face, each light's in one \
             binding, and up to {lobes} VPLs of {} bytes a texel in two; at most --rsm {most} \
             here)",
            size_of::<GpuRsmTexel>(),
            size_of::<GpuVpl>(),
        ));
    }
    let per_pixel = size_of::<GpuSample>() as u64;
    if pixels * per_pixel > limit {
        return beyond(format!(
            "{width}x{height} ({pixels} pixels of {per_pixel} bytes, {} bytes; at most {} pixels \
             here)",
            pixels * per_pixel,
            limit / per_pixel
        ));
    }
    Ok(())
}
