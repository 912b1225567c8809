//! Records of one kind over two storage buffers ([`SplitBuffers`]): a frame's per-VPL
//! records may need more bytes than one storage binding holds (a 1024² RSM's VPLs of both
//! lobes take 256 MiB, and the tight strategies' bounds over boxes of Sponza's 1.6M VPLs
//! 184 MB, where lavapipe binds 128 MiB). A kernel reads and writes them through a module
//! of its own that binds the two at fixed numbers and picks one by the index
//! (`vpl_buffers.wesl`, `box_bound_buffers.wesl`).
use crate::device::buffers::{check_storage_size, output, per_binding, read_back, upload};
use crate::device::context::{GpuContext, GpuError};
use bytemuck::Pod;
use std::marker::PhantomData;

/// Records of type `T`: record i is `low`'s i-th below `low_capacity`, `high`'s
/// (i − `low_capacity`)-th above. `low` holds as many as one storage binding allows
/// ([`per_binding`]), or all where they fit; `high` the rest, or one unused record
/// (a binding is never empty).
pub struct SplitBuffers<T> {
    pub low: wgpu::Buffer,
    pub high: wgpu::Buffer,
    /// How many records `low` holds (`arrayLength` of its binding where `high` holds any).
    low_capacity: usize,
    /// How many records both hold.
    capacity: usize,
    /// The label the buffers were made with, for readbacks and errors.
    label: String,
    record: PhantomData<fn() -> T>,
}

// Not derived: the derives would ask `T: Clone` and `T: Debug` of the record type the
// buffers only name.
impl<T> Clone for SplitBuffers<T> {
    fn clone(&self) -> Self {
        Self {
            low: self.low.clone(),
            high: self.high.clone(),
            low_capacity: self.low_capacity,
            capacity: self.capacity,
            label: self.label.clone(),
            record: PhantomData,
        }
    }
}

impl<T> std::fmt::Debug for SplitBuffers<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SplitBuffers")
            .field("label", &self.label)
            .field("capacity", &self.capacity)
            .field("low_capacity", &self.low_capacity)
            .finish_non_exhaustive()
    }
}

impl<T: Pod> SplitBuffers<T> {
    /// Where `capacity` records split: how many go into the low buffer and how many into the
    /// high one; an error where they need more than two bindings.
    fn split(ctx: &GpuContext, label: &str, capacity: usize) -> Result<[usize; 2], GpuError> {
        let per = per_binding::<T>(ctx);
        let low = capacity.min(per);
        let high = capacity - low;
        if high > per {
            // The high buffer would hold more than a binding does: the check fails, naming
            // the buffer, its size and the limit.
            let size = (high as u64).saturating_mul(std::mem::size_of::<T>() as u64);
            check_storage_size(ctx, &format!("{label} (the second of two)"), size)?;
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
            capacity,
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
            capacity: records.len(),
            label: label.to_owned(),
            record: PhantomData,
        })
    }

    /// The first `count` records, read back; an error where the buffers hold fewer.
    pub fn read_back(&self, ctx: &GpuContext, count: usize) -> Result<Vec<T>, GpuError> {
        if count > self.capacity {
            return Err(GpuError::Input(format!(
                "{count} records of {:?} read back where it holds {}",
                self.label, self.capacity
            )));
        }
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

    /// A kernel's bindings (`GpuContext::encode_dispatch_at`): `buffers` numbered from 0,
    /// then the two buffers at `bindings` ([`Self::at`]).
    pub fn after<'a>(
        &'a self,
        buffers: &[&'a wgpu::Buffer],
        bindings: [u32; 2],
    ) -> Vec<(u32, &'a wgpu::Buffer)> {
        (0u32..)
            .zip(buffers.iter().copied())
            .chain(self.at(bindings))
            .collect()
    }
}
