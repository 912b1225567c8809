//! Runs that cannot fit in this machine's memory are refused before any work.
use slc_core::{RenderSettings, Scene};

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
        "{}x{} with RSM {}² needs about {:.1} GiB (G-buffer {:.1}, images {:.1}, RSM {:.1}, VPLs {:.1}, metrics {:.1}), more than the {:.1} GiB of memory available: lower the width, height or RSM resolution",
        settings.width,
        settings.height,
        settings.rsm_resolution,
        gib(estimate.total()),
        gib(estimate.gbuffer),
        gib(estimate.images),
        gib(estimate.rsm),
        gib(estimate.vpls),
        gib(estimate.metrics),
        gib(available)
    ))
}

/// Bytes of memory available to a new allocation, from `/proc/meminfo`.
fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
