//! Records of one kind over two storage buffers ([`SplitBuffers`]): a frame's per-VPL
//! records may need more bytes than one storage binding holds (a 1024² RSM's VPLs of both
//! lobes take 256 MiB, and the tight strategies' bounds over boxes of Sponza's 1.6M VPLs
//! 184 MB, where lavapipe binds 128 MiB). A kernel reads and writes them through a module
//! of its own that binds the two at fixed numbers and picks one by the index
//! (`vpl_buffers.wesl`, `box_bound_buffers.wesl`).
use crate::device::buffers::{check_storage_size, output, read_back, upload};
use crate::device::context::{GpuContext, GpuError};
use bytemuck::Pod;
use std::marker::PhantomData;

/// Records of type `T`: record i is `low`'s i-th below `low_capacity`, `high`'s
/// (i − `low_capacity`)-th above. `low` holds as many as one storage binding allows
/// ([`Self::per_binding`]), or all where they fit; `high` the rest, or one unused record
/// (a binding is never empty).
#[derive(Debug)]
pub struct SplitBuffers<T> {
    pub low: wgpu::Buffer,
    pub high: wgpu::Buffer,
    /// How many records `low` holds (`arrayLength` of its binding).
    low_capacity: usize,
    /// The label the buffers were made with, for readbacks and errors.
    label: String,
    record: PhantomData<fn() -> T>,
}

// Not derived: the derive would ask `T: Clone` of the record type the buffers only name.
impl<T> Clone for SplitBuffers<T> {
    fn clone(&self) -> Self {
        Self {
            low: self.low.clone(),
            high: self.high.clone(),
            low_capacity: self.low_capacity,
            label: self.label.clone(),
            record: PhantomData,
        }
    }
}

impl<T: Pod> SplitBuffers<T> {
    /// The records one storage binding of `ctx` holds.
    pub fn per_binding(ctx: &GpuContext) -> usize {
        let records = ctx.limits.max_storage_buffer_binding_size / std::mem::size_of::<T>() as u64;
        usize::try_from(records).unwrap_or(usize::MAX).max(1)
    }

    /// Where `capacity` records split: how many go into the low buffer and how many into the
    /// high one; an error where they need more than two bindings.
    fn split(ctx: &GpuContext, label: &str, capacity: usize) -> Result<[usize; 2], GpuError> {
        let per = Self::per_binding(ctx);
        let low = capacity.min(per);
        let high = capacity - low;
        if high > per {
            // Each of the two bindings would need half of them.
            let size = (capacity as u64).saturating_mul(std::mem::size_of::<T>() as u64);
            check_storage_size(ctx, &format!("{label} (each of two)"), size.div_ceil(2))?;
        }
        Ok([low, high])
    }

    /// Zeroed room for `capacity` records.
    pub fn output(ctx: &GpuContext, label: &str, capacity: usize) -> Result<Self, GpuError> {
        let [low, high] = Self::split(ctx, label, capacity)?;
        Ok(Self {
            low: output::<T>(ctx, label, low)?,
            high: output::<T>(ctx, label, high.max(1))?,
            low_capacity: low,
            label: label.to_owned(),
            record: PhantomData,
        })
    }

    /// The records `records`, uploaded.
    pub fn upload(ctx: &GpuContext, label: &str, records: &[T]) -> Result<Self, GpuError> {
        let [low, high] = Self::split(ctx, label, records.len())?;
        let (below, above) = records.split_at(low);
        let high_buffer = match high {
            0 => output::<T>(ctx, label, 1)?,
            _ => upload(ctx, label, above)?,
        };
        Ok(Self {
            low: upload(ctx, label, below)?,
            high: high_buffer,
            low_capacity: low,
            label: label.to_owned(),
            record: PhantomData,
        })
    }

    /// The first `count` records, read back.
    pub fn read_back(&self, ctx: &GpuContext, count: usize) -> Result<Vec<T>, GpuError> {
        let low = count.min(self.low_capacity);
        let mut records: Vec<T> = read_back(ctx, &self.label, &self.low, low)?;
        records.extend(read_back::<T>(ctx, &self.label, &self.high, count - low)?);
        Ok(records)
    }

    /// The two buffers at binding numbers `bindings` (low, high), as the module that reads
    /// them declares them.
    pub fn at(&self, bindings: [u32; 2]) -> [(u32, &wgpu::Buffer); 2] {
        [(bindings[0], &self.low), (bindings[1], &self.high)]
    }
}
