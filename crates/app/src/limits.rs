//! The checks every front end runs before any work: each frame's settings in their domains,
//! the scene renderable, and the largest frame within this machine's memory.
use slc_core::frame::memory::available_memory;
use slc_core::{RenderSettings, Scene};

/// Checks every frame a run will render ([`RenderSettings::validate`]), that the scene can
/// be rendered, and that the largest frame fits in memory ([`check_memory`]): the one check
/// `render`, `compare`, `sweep`, `bench` and the Python package make before any work.
pub fn check_frames(scene: &Scene, frames: &[RenderSettings]) -> Result<(), String> {
    for settings in frames {
        settings.validate().map_err(|e| e.to_string())?;
    }
    scene.validate_for_render().map_err(|e| e.to_string())?;
    for settings in frames {
        check_memory(settings, scene)?;
    }
    Ok(())
}

/// Refuses `settings` on `scene` when the estimate of its largest buffers
/// ([`RenderSettings::memory_estimate`]) exceeds the memory available now (`MemAvailable` of
/// `/proc/meminfo`; where that cannot be read, nothing is checked).
pub fn check_memory(settings: &RenderSettings, scene: &Scene) -> Result<(), String> {
    let estimate = settings.memory_estimate(scene);
    let Some(available) = available_memory() else {
        return Ok(());
    };
    if estimate.total() <= available {
        return Ok(());
    }
    let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
    Err(format!(
        "{}x{} with RSM {}² needs about {:.1} GiB (scene {:.1}, BVH {:.1}, G-buffer {:.1}, images {:.1}, RSM {:.1}, VPLs {:.1}, metrics {:.1}), more than the {:.1} GiB of memory available: lower the width, height or RSM resolution",
        settings.width,
        settings.height,
        settings.rsm_resolution,
        gib(estimate.total()),
        gib(estimate.scene),
        gib(estimate.bvh),
        gib(estimate.gbuffer),
        gib(estimate.images),
        gib(estimate.rsm),
        gib(estimate.vpls),
        gib(estimate.metrics),
        gib(available)
    ))
}

/// The most memory this process has held so far (`VmHWM` of `/proc/self/status`), in bytes.
pub fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
