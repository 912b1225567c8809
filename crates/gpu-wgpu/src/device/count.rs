//! Counts a pass leaves on the GPU (the VPL total of `vpl::generate`'s scan, the VSGLs of
//! `vsgl::build`) and what the later passes of a frame make of them without a readback:
//! the count copied into their uniforms (where the host would have written it) and indirect
//! dispatch arguments sized by it (`dispatch_args.wesl`). Buffers are sized by the
//! count's capacity, the largest value it can take.
use crate::device::buffers::{read_back, uniform, Grid, Workgroups};
use crate::device::context::{GpuContext, GpuError};
use bytemuck::{Pod, Zeroable};

/// A u32 count on the GPU and the largest value it can take.
#[derive(Clone, Debug)]
pub struct GpuCount {
    /// The buffer holding it.
    pub buffer: wgpu::Buffer,
    /// Its byte offset there (a multiple of 4).
    pub offset: u64,
    /// The largest value it can take: what buffers sized by it hold.
    pub capacity: u32,
}

impl GpuCount {
    /// Records a copy of the count into the u32 at byte `at` of `target` (a uniform with
    /// `COPY_DST` that later passes of `encoder` read, `buffers::uniform`), where the host
    /// would have written it had it read the count back.
    pub fn encode_copy(&self, encoder: &mut wgpu::CommandEncoder, target: &wgpu::Buffer, at: u64) {
        encoder.copy_buffer_to_buffer(&self.buffer, self.offset, target, at, 4);
    }

    /// Reads the count back (waits for the GPU).
    pub fn read(&self, ctx: &GpuContext, label: &str) -> Result<u32, GpuError> {
        let index = (self.offset / 4) as usize;
        let words: Vec<u32> = read_back(ctx, label, &self.buffer, index + 1)?;
        words.get(index).copied().ok_or_else(|| GpuError::Readback {
            label: label.to_owned(),
            message: "short read".into(),
        })
    }
}

/// A number of items a frame's passes work on (VPLs, VSGLs): known to the host (items from
/// the CPU) or left on the GPU by the pass that made them.
#[derive(Clone, Debug)]
pub enum Count {
    Host(u32),
    Gpu(GpuCount),
}

impl Count {
    /// The most items there can be: what buffers with a record per item hold.
    pub fn capacity(&self) -> u32 {
        match self {
            Self::Host(n) => *n,
            Self::Gpu(c) => c.capacity,
        }
    }

    /// A uniform holding `value`, whose u32 at byte `count_at` is the count: as written
    /// (`value` has the host's count), or for a count on the GPU copied there by `encoder`,
    /// before the passes it records next read it.
    pub fn uniform<T: Pod>(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        label: &str,
        value: &T,
        count_at: usize,
    ) -> wgpu::Buffer {
        let buffer = uniform(ctx, label, value);
        if let Self::Gpu(c) = self {
            c.encode_copy(encoder, &buffer, count_at as u64);
        }
        buffer
    }

    /// The count, read back where it lies on the GPU.
    pub fn read(&self, ctx: &GpuContext, label: &str) -> Result<u32, GpuError> {
        match self {
            Self::Host(n) => Ok(*n),
            Self::Gpu(c) => c.read(ctx, label),
        }
    }

    /// The workgroups of `count × per_item` invocations in groups of `workgroup`: a grid the
    /// host sizes, or arguments `args` writes in `encoder` from the count on the GPU.
    pub fn workgroups(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        args: &ArgsPass,
        per_item: u32,
        workgroup: u32,
    ) -> Result<Workgroups, GpuError> {
        match self {
            Self::Host(n) => Ok(Workgroups::Grid(Grid::for_items(
                ctx,
                u64::from(*n) * u64::from(per_item),
                workgroup,
            )?)),
            Self::Gpu(c) => Ok(Workgroups::Indirect(
                args.encode(ctx, encoder, c, per_item, workgroup)?,
            )),
        }
    }
}

/// The parameters of `dispatch_args.wesl`. Keep in sync with `ArgsParams` there.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuArgsParams {
    pub per_item: u32,
    pub workgroup: u32,
    pub max_x: u32,
    pub index: u32,
}
const _: () = assert!(std::mem::size_of::<GpuArgsParams>() == 16);

pub(crate) const SOURCE: &str = kernel!("dispatch_args");

/// The compiled argument pass.
pub struct ArgsPass {
    pipeline: wgpu::ComputePipeline,
}

impl ArgsPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("dispatch args pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("dispatch args", SOURCE),
            })
        })
    }

    /// Records the arguments of a dispatch of `count × per_item` invocations in workgroups of
    /// `workgroup` (a buffer for [`Workgroups::Indirect`]); an error when the count's capacity
    /// times `per_item` exceeds u32. (wgpu keeps what recorded commands use alive until they
    /// ran: the parameters may be dropped here.)
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        count: &GpuCount,
        per_item: u32,
        workgroup: u32,
    ) -> Result<wgpu::Buffer, GpuError> {
        if count.capacity.checked_mul(per_item).is_none() {
            return Err(GpuError::Input(format!(
                "{} items of {per_item} invocations exceed u32",
                count.capacity
            )));
        }
        let params = uniform(
            ctx,
            "dispatch args params",
            &GpuArgsParams {
                per_item,
                workgroup,
                max_x: ctx.limits.max_compute_workgroups_per_dimension,
                index: (count.offset / 4) as u32,
            },
        );
        let args = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("dispatch args"),
            size: 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
            mapped_at_creation: false,
        });
        ctx.encode_dispatch(
            encoder,
            "dispatch args",
            &self.pipeline,
            &[&params, &count.buffer, &args],
            Grid { x: 1, y: 1 },
        );
        Ok(args)
    }
}
