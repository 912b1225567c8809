//! The VPL records of a frame on the GPU over two storage buffers ([`VplBuffers`]), read
//! through `vpl_buffers.wesl`: a frame's VPLs may need more bytes than one storage binding
//! holds (a 1024² RSM's VPLs of both lobes take 256 MiB where lavapipe binds 128 MiB).
use crate::device::split_buffers::SplitBuffers;
use crate::vpl::records::GpuVpl;

/// The binding numbers of the low and the high buffer in `vpl_buffers.wesl`, past every
/// other binding of the kernels that import it.
pub const VPL_BINDINGS: [u32; 2] = [14, 15];

/// VPL records (`GpuVpl`) over two buffers.
pub type VplBuffers = SplitBuffers<GpuVpl>;

impl VplBuffers {
    /// `buffers` numbered from 0, then the two buffers at [`VPL_BINDINGS`]: the bindings of
    /// a kernel that imports `vpl_buffers.wesl` (`GpuContext::encode_dispatch_at`).
    pub fn with<'a>(&'a self, buffers: &[&'a wgpu::Buffer]) -> Vec<(u32, &'a wgpu::Buffer)> {
        self.after(buffers, VPL_BINDINGS)
    }
}
