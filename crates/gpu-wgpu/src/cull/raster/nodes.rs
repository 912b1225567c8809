//! Light lists as linked lists in a node buffer, as the raster baselines build them
//! (\[OP16\]'s node buffer; splatting's metrics): one head per list (`END`: empty) and nodes
//! `(VPL, next)` taken from one counter, the `total` of the frame's `GpuCullStatus`. A
//! buffer that was too small is seen in the count afterwards; the caller refills with
//! [`NodeLists::new`] at that capacity.
use crate::cull::lists::compact;
use crate::device::buffers::{output, read_back, upload};
use crate::device::context::{GpuContext, GpuError};
use slc_core::LightLists;

/// The end of a list (and an empty list's head).
pub const END: u32 = u32::MAX;

/// Heads and nodes on the GPU.
pub struct NodeLists {
    pub heads: wgpu::Buffer,
    pub nodes: wgpu::Buffer,
    pub list_count: u32,
    /// Nodes the buffer holds.
    pub capacity: u32,
}

impl NodeLists {
    /// `list_count` empty lists and room for `capacity` nodes.
    pub fn new(ctx: &GpuContext, list_count: u32, capacity: u32) -> Result<Self, GpuError> {
        Ok(Self {
            heads: upload(ctx, "list heads", &vec![END; list_count as usize])?,
            nodes: output::<[u32; 2]>(ctx, "list nodes", capacity as usize)?,
            list_count,
            capacity,
        })
    }

    /// The `count` nodes appended, read back as [`LightLists`] in the CPU's convention (each
    /// list ascending, empty lists dropped) for pixels shading with `pixel_list`. An error
    /// if the nodes did not fit.
    pub fn read(
        &self,
        ctx: &GpuContext,
        count: u32,
        pixel_list: &[u32],
    ) -> Result<LightLists, GpuError> {
        if count > self.capacity {
            return Err(GpuError::Input(format!(
                "{count} list nodes for a node buffer of {}",
                self.capacity
            )));
        }
        let heads: Vec<u32> = read_back(ctx, "list heads", &self.heads, self.list_count as usize)?;
        let nodes: Vec<[u32; 2]> = read_back(ctx, "list nodes", &self.nodes, count as usize)?;
        let mut offsets = Vec::with_capacity(heads.len() + 1);
        let mut indices = Vec::with_capacity(count as usize);
        offsets.push(0);
        for &head in &heads {
            let start = indices.len();
            let mut n = head;
            while n != END {
                let [vpl, next] = *nodes.get(n as usize).ok_or_else(|| {
                    GpuError::Input(format!("list node {n} beyond the {count} appended"))
                })?;
                indices.push(vpl);
                if indices.len() > count as usize {
                    return Err(GpuError::Input("the list nodes form a cycle".into()));
                }
                n = next;
            }
            indices[start..].sort_unstable();
            offsets.push(indices.len() as u32);
        }
        Ok(compact(&offsets, indices, pixel_list))
    }
}
