//! The VPL records of a frame on the GPU over two storage buffers ([`VplBuffers`]), read
//! through `vpl_buffers.wesl`: a frame's VPLs may need more bytes than one storage binding
//! holds (a 1024² RSM's VPLs of both lobes take 256 MiB where lavapipe binds 128 MiB).
use crate::device::buffers::{check_storage_size, output, read_back, upload};
use crate::device::context::{GpuContext, GpuError};
use crate::vpl::records::GpuVpl;

/// The binding numbers of the low and the high buffer in `vpl_buffers.wesl`, past every
/// other binding of the kernels that import it.
pub const VPL_BINDINGS: [u32; 2] = [14, 15];

/// VPL records (`GpuVpl`): record i is `low`'s i-th below `low_capacity`, `high`'s
/// (i − `low_capacity`)-th above. `low` holds as many as one storage binding allows
/// ([`Self::per_binding`]), or all where they fit; `high` the rest, or one unused record
/// (a binding is never empty).
#[derive(Clone, Debug)]
pub struct VplBuffers {
    pub low: wgpu::Buffer,
    pub high: wgpu::Buffer,
    /// How many records `low` holds (`arrayLength` of its binding).
    low_capacity: usize,
}

impl VplBuffers {
    /// The records one storage binding of `ctx` holds.
    pub fn per_binding(ctx: &GpuContext) -> usize {
        let records =
            ctx.limits.max_storage_buffer_binding_size / std::mem::size_of::<GpuVpl>() as u64;
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
            let size = (capacity as u64).saturating_mul(std::mem::size_of::<GpuVpl>() as u64);
            check_storage_size(ctx, &format!("{label} (each of two)"), size.div_ceil(2))?;
        }
        Ok([low, high])
    }

    /// Zeroed room for `capacity` records.
    pub fn output(ctx: &GpuContext, label: &str, capacity: usize) -> Result<Self, GpuError> {
        let [low, high] = Self::split(ctx, label, capacity)?;
        Ok(Self {
            low: output::<GpuVpl>(ctx, label, low)?,
            high: output::<GpuVpl>(ctx, label, high.max(1))?,
            low_capacity: low,
        })
    }

    /// The records `records`, uploaded.
    pub fn upload(ctx: &GpuContext, label: &str, records: &[GpuVpl]) -> Result<Self, GpuError> {
        let [low, high] = Self::split(ctx, label, records.len())?;
        let (below, above) = records.split_at(low);
        let high_buffer = match high {
            0 => output::<GpuVpl>(ctx, label, 1)?,
            _ => upload(ctx, label, above)?,
        };
        Ok(Self {
            low: upload(ctx, label, below)?,
            high: high_buffer,
            low_capacity: low,
        })
    }

    /// The first `count` records, read back.
    pub fn read_back(&self, ctx: &GpuContext, count: usize) -> Result<Vec<GpuVpl>, GpuError> {
        let low = count.min(self.low_capacity);
        let mut records: Vec<GpuVpl> = read_back(ctx, "vpls", &self.low, low)?;
        records.extend(read_back::<GpuVpl>(ctx, "vpls", &self.high, count - low)?);
        Ok(records)
    }

    /// `buffers` numbered from 0, then the two buffers at [`VPL_BINDINGS`]: the bindings of
    /// a kernel that imports `vpl_buffers.wesl` (`GpuContext::encode_dispatch_at`).
    pub fn with<'a>(&'a self, buffers: &[&'a wgpu::Buffer]) -> Vec<(u32, &'a wgpu::Buffer)> {
        (0u32..)
            .zip(buffers.iter().copied())
            .chain(VPL_BINDINGS.into_iter().zip([&self.low, &self.high]))
            .collect()
    }
}
