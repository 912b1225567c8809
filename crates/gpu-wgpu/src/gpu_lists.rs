//! Light lists as the GPU cullers leave them ([`GpuLightLists`], in the CSR layout of
//! [`LightLists`]), uploaded from the CPU or read back in the CPU's convention.
use crate::buffers::{output, read_back, upload};
use crate::context::{GpuContext, GpuError};
use slc_core::{LightLists, NO_LIST};

/// Light lists on the GPU in [`LightLists`]' CSR layout: list `l` holds
/// `indices[offsets[l]..offsets[l + 1]]` (VPL indices), pixel `p` shades with list
/// `pixel_list[p]` ([`NO_LIST`]: none). Empty lists are allowed. Clones share the buffers.
#[derive(Clone)]
pub struct GpuLightLists {
    pub offsets: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub pixel_list: wgpu::Buffer,
    /// Number of lists (`offsets` holds one more entry).
    pub list_count: u32,
    /// Number of list entries the indices buffer holds (at least the last offset).
    pub entries: u32,
    /// Number of pixels (`pixel_list` entries).
    pub pixels: u32,
}

impl GpuLightLists {
    /// Validates `lists` for `pixels` pixels and `vpl_count` VPLs (what indexing them on the
    /// CPU would require: offsets ascending within `indices`, list ids below the list count or
    /// [`NO_LIST`], VPL indices in range) and uploads them.
    pub fn upload(
        ctx: &GpuContext,
        lists: &LightLists,
        pixels: usize,
        vpl_count: usize,
    ) -> Result<Self, GpuError> {
        let bad = |what: String| Err(GpuError::Input(format!("light lists: {what}")));
        if lists.pixel_list.len() != pixels {
            return bad(format!(
                "{} pixel entries for {pixels} pixels",
                lists.pixel_list.len()
            ));
        }
        let list_count = lists.len();
        if lists.offsets.windows(2).any(|w| w[1] < w[0])
            || lists
                .offsets
                .last()
                .is_some_and(|&e| e as usize > lists.indices.len())
        {
            return bad("offsets descend or pass the end of the indices".into());
        }
        if let Some(p) = lists
            .pixel_list
            .iter()
            .position(|&l| l != NO_LIST && l as usize >= list_count)
        {
            return bad(format!(
                "pixel {p} names a list beyond the {list_count} lists"
            ));
        }
        if let Some(&v) = lists.indices.iter().find(|&&v| v as usize >= vpl_count) {
            return bad(format!("VPL index {v} beyond the {vpl_count} VPLs"));
        }
        let count = |n: usize, what: &str| {
            u32::try_from(n).map_err(|_| GpuError::Input(format!("{n} {what} exceed u32")))
        };
        let offsets: &[u32] = if lists.offsets.is_empty() {
            &[0]
        } else {
            &lists.offsets
        };
        Ok(Self {
            list_count: count(list_count, "light lists")?,
            entries: count(lists.indices.len(), "light-list entries")?,
            pixels: count(pixels, "pixels")?,
            offsets: upload(ctx, "list offsets", offsets)?,
            indices: upload(ctx, "light lists", &lists.indices)?,
            pixel_list: upload(ctx, "pixel lists", &lists.pixel_list)?,
        })
    }
}

/// Lists of an image without pixels: no list, no entry.
pub(crate) fn no_lists(ctx: &GpuContext) -> Result<GpuLightLists, GpuError> {
    Ok(GpuLightLists {
        offsets: output::<u32>(ctx, "list offsets", 1)?,
        indices: output::<u32>(ctx, "light lists", 0)?,
        pixel_list: output::<u32>(ctx, "pixel lists", 0)?,
        list_count: 0,
        entries: 0,
        pixels: 0,
    })
}

/// Reads `gpu` back as [`LightLists`] in the CPU's convention: empty lists dropped (their
/// pixels get [`NO_LIST`]) and the rest renumbered in order.
pub fn read_lists(ctx: &GpuContext, gpu: &GpuLightLists) -> Result<LightLists, GpuError> {
    if gpu.pixels == 0 {
        return Ok(LightLists {
            offsets: vec![0],
            ..LightLists::default()
        });
    }
    let offsets: Vec<u32> = read_back(
        ctx,
        "list offsets",
        &gpu.offsets,
        gpu.list_count as usize + 1,
    )?;
    // The entries may be fewer than the buffer holds (a count's capacity, `gpu_count`).
    let entries = offsets.last().map_or(0, |&e| e.min(gpu.entries));
    let indices: Vec<u32> = read_back(ctx, "light lists", &gpu.indices, entries as usize)?;
    let pixel_list: Vec<u32> = read_back(ctx, "pixel lists", &gpu.pixel_list, gpu.pixels as usize)?;
    Ok(compact(&offsets, indices, &pixel_list))
}

/// [`LightLists`] from lists that may be empty: empty lists are dropped (their pixels get
/// `NO_LIST`, as on the CPU) and the rest renumbered in order.
pub(crate) fn compact(offsets: &[u32], indices: Vec<u32>, pixel_list: &[u32]) -> LightLists {
    let mut renumber = vec![NO_LIST; offsets.len().saturating_sub(1)];
    let mut kept = vec![0u32];
    for (l, pair) in offsets.windows(2).enumerate() {
        if pair[1] > pair[0] {
            renumber[l] = (kept.len() - 1) as u32;
            kept.push(pair[1]);
        }
    }
    LightLists {
        offsets: kept,
        indices,
        pixel_list: pixel_list
            .iter()
            .map(|&l| renumber.get(l as usize).copied().unwrap_or(NO_LIST))
            .collect(),
    }
}
