//! What a report says about a GPU frame: where each pass ran and how it was timed.
use crate::device::context::GpuContext;
use crate::vsgl::ism::IsmSettings;

/// Notes of every GPU frame: what ran on the GPU, what came back, how the passes were timed.
pub fn frame_notes(ctx: &GpuContext) -> Vec<String> {
    vec![
        format!(
            "every pass ran on the GPU ({}): G-buffer and RSMs by rasterization (visibility \
             buffer resolved by the pixel's own ray), VPL generation, direct light with the \
             RSM depth as shadow maps, culling and shading (light lists kept on the GPU, \
             or none at all in a one-pass frame) and the cross bilateral filter",
            ctx.adapter_name
        ),
        "the VPLs and their count stay on the GPU from their generation to the shading (the \
         passes after it are sized there: indirect dispatches, the count copied into their \
         parameters); the light lists are written into buffers sized from earlier frames; \
         what is read back is the images, the culling's 16-byte fault record after the \
         shading (two for the tight strategies; a frame whose lists outgrew their buffer is \
         culled and shaded again) and the VPL count for the report after the frame"
            .to_string(),
        if ctx.timestamps_trusted {
            "timings_ms of GPU passes are wall clock around the GPU work (uploads, readbacks \
             and the wait for completion included); gpu_timings_ms are the GPU's execution \
             times of the same passes from timestamp queries"
                .to_string()
        } else if ctx.timestamps {
            "this adapter's timestamp queries are not used: on a CPU adapter (lavapipe) they \
             stop bracketing compute work once a render pass has run; GPU pass times are \
             wall clock around the GPU work (uploads, readbacks and the wait for completion \
             included) and gpu_timings_ms is null"
                .to_string()
        } else {
            "this adapter has no timestamp queries: GPU pass times are wall clock around the \
             GPU work (uploads, readbacks and the wait for completion included) and \
             gpu_timings_ms is null"
                .to_string()
        },
    ]
}

/// The note of frames of a tiled strategy (but `tight`), culled and shaded in one pass.
pub fn one_pass_note(subgroups: bool) -> String {
    let marks = if subgroups {
        "a subgroup's hits combined by subgroup operations before they reach workgroup memory"
    } else {
        "one workgroup atomic per hit (the device has no subgroup operations)"
    };
    format!(
        "tiled culling and shading in one pass (the paper's Fig. 2, tiled_shade): 'culling' \
         times the bounds, partition and tile-depth passes, 'shading' the one pass that tests \
         each tile's VPLs and shades its pixels from the hits in workgroup memory ({marks}); \
         no light list is stored or read back"
    )
}

/// The note of frames splatted (`cull::raster::splat`).
pub const SPLAT_NOTE: &str = "splatting [DS06]: 'culling' times the bounds, partition and \
     tile-depth passes, 'shading' the draws of each VPL's 80-triangle bounding mesh over its \
     subregion's pixels, blended additively, and the pass back to screen order; metrics count \
     the pixels each mesh covers";

/// The note of frames culled by rasterized clusters (`cull::raster::clusters`).
pub fn cluster_raster_note(hardware: bool) -> String {
    let form = if hardware {
        "in hardware (the adapter's conservative rasterization draws each triangle)"
    } else {
        "in software (each triangle drawn as the whole cells around it)"
    };
    format!(
        "clustered shading by rasterized bounding meshes [OP16]: 'culling' times the bounds, \
         partition and depth-slice passes, the shell pass (each VPL's 20-triangle mesh at \
         tile resolution, conservatively {form}: every cell a triangle meets, marked with its \
         depth range there) and the fill pass into a linked-list node buffer; 'shading' walks \
         each pixel's cluster list (and, where the node buffer was too small, fills and \
         shades again)"
    )
}

/// The note of frames whose culling metrics were measured.
pub const METRICS_NOTE: &str = "metrics were measured by brute force on the CPU against the \
     GPU's light lists and G-buffer, read back after the timed passes (a one-pass tiled \
     frame's lists built then by the list passes, which list the same VPLs)";

/// The note of a GPU VSGL frame: what ran where, and with `visibility` what the GPU used
/// for it.
pub fn vsgl_note(visibility: bool) -> String {
    let head = "--shader vsgl: the VSGLs were built and sampled from the RSMs on the GPU \
                (vsgl_mip, importance_map, light_sampling; no RSM read back) and shaded there \
                (light_shading) instead of culling and VPL shading";
    if !visibility {
        return format!("{head}; without --visibility GPU VSGL shading has no visibility term");
    }
    let s = IsmSettings::paper(0.0);
    format!(
        "{head}; --visibility on the GPU: V(x_p, mu_v) from imperfect shadow maps \
         (shadow_maps; {} caster points sampled by area, one {}x{} octahedral distance map \
         per VSGL, depth bias {} + {} tan(incidence) texels), not the CPU's shadow rays: light \
         leaks through gaps and small occluders and contact shadows within the bias are lost",
        s.points, s.resolution, s.resolution, s.bias_constant, s.bias_slope
    )
}
