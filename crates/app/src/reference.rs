//! What `compare` and `sweep` compute on the CPU whatever the backend: the all-VPL reference
//! (every VPL at every pixel with p = 1), on the frame the backend prepared, read back where
//! it lives elsewhere.
use crate::progress::bar;
use slc_core::shader::{AllVplShader, ShadeInput, Shader};
use slc_core::{Image, Progress, Scene};
use slc_cpu_ref::{CpuPrepared, CpuRenderer};

/// The CPU's view of a prepared frame.
pub fn cpu_input<'a>(
    scene: &'a Scene,
    p: &'a CpuPrepared,
    seed: u32,
    visibility: bool,
) -> ShadeInput<'a, CpuRenderer> {
    ShadeInput {
        scene,
        loaded: &p.tracer,
        prepared: p,
        seed,
        visibility,
    }
}

/// Every VPL of the frame at every pixel with p = 1, with shadow rays when `visibility`,
/// reporting to `progress` and stopping when it is cancelled.
pub fn all_vpl_reference(
    input: ShadeInput<'_, CpuRenderer>,
    progress: Progress,
) -> Result<Image, String> {
    let r = AllVplShader
        .shade(&CpuRenderer::default(), input, progress)
        .map_err(|e| e.to_string())?;
    Ok(r.indirect)
}

/// [`all_vpl_reference`] with the command's progress bar.
pub fn all_vpl_reference_with_bar(input: ShadeInput<'_, CpuRenderer>) -> Result<Image, String> {
    let g = &input.prepared.gbuffer;
    let bar = bar(g.width as u64 * g.height as u64, "all-VPL reference".into());
    let reference = all_vpl_reference(input, &|n| bar.inc(n));
    bar.finish_and_clear();
    reference
}
