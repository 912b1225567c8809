//! Upload and readback helpers (plain `create_buffer` + `write_buffer`: unlike
//! `create_buffer_init` they do not panic on a lost device), the storage-binding size check and the 2-D dispatch grid.
use crate::device::context::{GpuContext, GpuError, WAIT_TIMEOUT};
use bytemuck::Pod;
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

/// The smallest buffer for elements of `T`: WGSL runtime-sized arrays bind at least one
/// element (and never zero bytes), even for empty inputs.
fn min_size<T>() -> u64 {
    (std::mem::size_of::<T>() as u64).max(16)
}

/// Refuses a storage buffer of `size` bytes larger than the device allows one
/// ([`GpuContext::storage_limit`]: 128 MiB on lavapipe), naming both sizes.
pub fn check_storage_size(ctx: &GpuContext, label: &str, size: u64) -> Result<(), GpuError> {
    let limit = ctx.storage_limit();
    if size > limit {
        return Err(GpuError::BufferTooLarge {
            label: label.to_owned(),
            size,
            limit,
        });
    }
    Ok(())
}

/// The records of type `T` one storage buffer of `ctx` holds ([`GpuContext::storage_limit`]),
/// at least one.
pub fn per_binding<T>(ctx: &GpuContext) -> usize {
    let record = std::mem::size_of::<T>().max(1) as u64;
    usize::try_from(ctx.storage_limit() / record)
        .unwrap_or(usize::MAX)
        .max(1)
}

/// A read-only storage buffer holding `data` (size-checked).
pub fn upload<T: Pod>(ctx: &GpuContext, label: &str, data: &[T]) -> Result<wgpu::Buffer, GpuError> {
    let bytes: &[u8] = bytemuck::cast_slice(data);
    check_storage_size(ctx, label, bytes.len() as u64)?;
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: (bytes.len() as u64).max(min_size::<T>()),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    ctx.queue.write_buffer(&buffer, 0, bytes);
    Ok(buffer)
}

/// A uniform buffer holding `value`.
pub fn uniform<T: Pod>(ctx: &GpuContext, label: &str, value: &T) -> wgpu::Buffer {
    let bytes = bytemuck::bytes_of(value);
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.len() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    ctx.queue.write_buffer(&buffer, 0, bytes);
    buffer
}

/// A zeroed read-write storage buffer of `count` elements of `T` that can be read back
/// (size-checked).
pub fn output<T: Pod>(
    ctx: &GpuContext,
    label: &str,
    count: usize,
) -> Result<wgpu::Buffer, GpuError> {
    let size = (count as u64)
        .checked_mul(std::mem::size_of::<T>() as u64)
        .ok_or_else(|| GpuError::Input(format!("{label}: {count} elements overflow u64")))?;
    check_storage_size(ctx, label, size)?;
    Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(min_size::<T>()),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    }))
}

/// Copies the first `count` elements of `buffer` to the CPU (waits, bounded, for the GPU).
pub fn read_back<T: Pod>(
    ctx: &GpuContext,
    label: &str,
    buffer: &wgpu::Buffer,
    count: usize,
) -> Result<Vec<T>, GpuError> {
    let size = (count * std::mem::size_of::<T>()) as u64;
    if size == 0 {
        return Ok(Vec::new());
    }
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("staging"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |r| {
        // The receiver lives until after the wait below; a send error cannot happen.
        let _ = sender.send(r);
    });
    ctx.wait()?;
    let failed = |message: String| GpuError::Readback {
        label: label.to_owned(),
        message,
    };
    // On a device other threads poll too (a host's, or contexts made by
    // `GpuContext::share`), one of them may be delivering the callback while this wait
    // returns: wait for it, polling, as long as a wait may take.
    let start = Instant::now();
    let mapped = loop {
        match receiver.recv_timeout(Duration::from_millis(5)) {
            Ok(mapped) => break mapped,
            Err(RecvTimeoutError::Timeout) if start.elapsed() < WAIT_TIMEOUT => {
                ctx.check_lost()?;
                let _ = ctx.device.poll(wgpu::PollType::Poll);
            }
            Err(_) => return Err(failed("the map callback did not run".into())),
        }
    };
    mapped.map_err(|e| failed(e.to_string()))?;
    let view = staging
        .get_mapped_range(..)
        .map_err(|e| failed(e.to_string()))?;
    let out = bytemuck::pod_collect_to_vec(&view);
    drop(view);
    staging.unmap();
    ctx.count_readback(label, size);
    Ok(out)
}

/// A dispatch of `groups` workgroups laid out as `x` x `y` so that neither dimension exceeds
/// the device's `max_compute_workgroups_per_dimension` (65535 on lavapipe): `x` = min(groups,
/// max), `y` = ceil(groups / x). Shaders recover the linear workgroup index as
/// `wid.y * num_workgroups.x + wid.x` and skip indices >= their item count (the last row may
/// be partly beyond it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Grid {
    pub x: u32,
    pub y: u32,
}

impl Grid {
    /// The grid of `groups` workgroups with at most `max` per dimension; an error beyond
    /// `max`².
    pub fn new(groups: u64, max: u32) -> Result<Self, GpuError> {
        let max64 = u64::from(max.max(1));
        if groups <= max64 {
            return Ok(Self {
                x: groups as u32,
                y: 1,
            });
        }
        let y = groups.div_ceil(max64);
        if y > max64 {
            return Err(GpuError::TooManyWorkgroups { groups, max });
        }
        Ok(Self {
            x: max64 as u32,
            y: y as u32,
        })
    }

    /// The grid covering `items` invocations in workgroups of `workgroup_size`.
    pub fn for_items(ctx: &GpuContext, items: u64, workgroup_size: u32) -> Result<Self, GpuError> {
        Self::new(
            items.div_ceil(u64::from(workgroup_size)),
            ctx.limits.max_compute_workgroups_per_dimension,
        )
    }

    /// Records the dispatch (nothing for an empty grid).
    pub fn dispatch(&self, pass: &mut wgpu::ComputePass) {
        if self.x > 0 {
            pass.dispatch_workgroups(self.x, self.y, 1);
        }
    }
}

/// How many workgroups a dispatch runs: a [`Grid`] the host sized, or indirect arguments
/// `[x, y, z]` (u32) a pass wrote on the GPU (a buffer with `INDIRECT` usage), read at
/// offset 0 when the dispatch runs.
#[derive(Clone, Debug)]
pub enum Workgroups {
    Grid(Grid),
    Indirect(wgpu::Buffer),
}

impl From<Grid> for Workgroups {
    fn from(grid: Grid) -> Self {
        Self::Grid(grid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_split_beyond_one_dimension() {
        assert_eq!(Grid::new(0, 65535).unwrap(), Grid { x: 0, y: 1 });
        assert_eq!(Grid::new(65535, 65535).unwrap(), Grid { x: 65535, y: 1 });
        assert_eq!(Grid::new(65536, 65535).unwrap(), Grid { x: 65535, y: 2 });
        let g = Grid::new(1 << 31, 65535).unwrap();
        assert!(u64::from(g.x) * u64::from(g.y) >= 1 << 31 && g.y <= 65535);
        assert!(matches!(
            Grid::new(65535 * 65535 + 1, 65535),
            Err(GpuError::TooManyWorkgroups { .. })
        ));
    }
}
