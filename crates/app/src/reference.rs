//! The all-VPL reference of `compare` and `sweep` (every VPL at every pixel with p = 1), with
//! a progress bar, and the frame it is shaded on, prepared by the command's backend.
use crate::gpu_frame::{GpuFrame, GpuPrepared};
use crate::progress::bar;
use slc_core::{Image, Scene};
use slc_cpu_ref::vpl_shading::{shade_vpls, VplEstimator};
use slc_cpu_ref::{prepare, Prepared, RenderSettings, Tracer};

/// Every VPL of `p` at every pixel with p = 1 (`VplEstimator::Exact`), with shadow rays when
/// `visibility`.
pub fn all_vpl_reference(p: &Prepared, visibility: bool) -> Result<Image, String> {
    let pixels = p.gbuffer.width as u64 * p.gbuffer.height as u64;
    let bar = bar(pixels, "all-VPL reference".into());
    let r = shade_vpls(
        &p.tracer,
        &p.gbuffer,
        &p.vpls,
        VplEstimator::Exact,
        visibility,
        &|n| bar.inc(n),
    )
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    Ok(r)
}

/// The frame of `settings` as the CPU passes see it: traced on the CPU, or with `gpu`
/// prepared on the GPU (rasterized G-buffer, its RSMs and VPLs) and read back, in which case
/// the GPU's frame is returned too.
pub fn prepare_on(
    gpu: Option<&GpuFrame>,
    scene: &Scene,
    settings: &RenderSettings,
) -> Result<(Prepared, Option<GpuPrepared>), String> {
    let tracer = Tracer::new(scene);
    match gpu {
        None => Ok((prepare(scene, settings, tracer, None), None)),
        Some(g) => {
            let on_gpu = g.prepare(scene, &g.upload(scene)?, settings, None)?;
            Ok((g.to_cpu(&on_gpu, tracer)?, Some(on_gpu)))
        }
    }
}
