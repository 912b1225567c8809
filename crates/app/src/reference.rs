//! What `compare` and `sweep` compute on the CPU whatever the backend: the all-VPL reference
//! (every VPL at every pixel with p = 1), with a progress bar, on the frame the backend
//! prepared, read back where it lives elsewhere.
use crate::progress::bar_if;
use slc_core::shader::{AllVplShader, ShadeInput, Shader};
use slc_core::{Image, Scene};
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

/// Every VPL of the frame at every pixel with p = 1, with shadow rays when `visibility`, with
/// a progress bar when `progress`.
pub fn all_vpl_reference(
    input: ShadeInput<'_, CpuRenderer>,
    progress: bool,
) -> Result<Image, String> {
    let g = &input.prepared.gbuffer;
    let bar = bar_if(
        progress,
        g.width as u64 * g.height as u64,
        "all-VPL reference".into(),
    );
    let r = AllVplShader
        .shade(&CpuRenderer::default(), input, &|n| bar.inc(n))
        .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    Ok(r.indirect)
}
