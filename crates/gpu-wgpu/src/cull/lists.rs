//! Light lists as the GPU cullers leave them ([`GpuLightLists`], in the CSR layout of
//! [`LightLists`]), uploaded from the CPU or read back in the CPU's convention.
use crate::cull::frame::read_status;
use crate::cull::room::ListWrite;
use crate::device::buffers::{output, read_back, upload};
use crate::device::context::{GpuContext, GpuError};
use slc_core::{LightLists, NO_LIST};

/// Light lists on the GPU in [`LightLists`]' CSR layout: list `l` holds
/// `indices[offsets[l]..offsets[l + 1]]` (VPL indices), pixel `p` shades with list
/// `pixel_list[p]` ([`NO_LIST`]: none). Empty lists are allowed. Clones share the buffers.
///
/// Lists a culler wrote on the GPU may have outgrown their buffer: their totals are read
/// after the work that uses them ([`Self::outgrown`], [`crate::cull::room::use_settled`]).
#[derive(Clone)]
pub struct GpuLightLists {
    pub offsets: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub pixel_list: wgpu::Buffer,
    /// Number of lists (`offsets` holds one more entry).
    pub list_count: u32,
    /// Number of list entries the indices buffer holds: at least the last offset, unless
    /// the lists outgrew it ([`Self::outgrown`]).
    pub entries: u32,
    /// Number of pixels (`pixel_list` entries).
    pub pixels: u32,
    /// The list writes whose totals are still to be read, in the order they ran.
    pub(crate) writes: Vec<ListWrite>,
}

impl GpuLightLists {
    /// Validates `lists` for `pixels` pixels and `vpl_count` VPLs (what indexing them on the
    /// CPU would require: offsets ascending within `indices`, list ids below the list count or
    /// [`NO_LIST`], VPL indices in range) and uploads them; a pixel's two lists (where the
    /// lists give it a second, [`LightLists::shared_list`]) are uploaded as one.
    pub fn upload(
        ctx: &GpuContext,
        lists: &LightLists,
        pixels: usize,
        vpl_count: usize,
    ) -> Result<Self, GpuError> {
        // The shader reads one list per pixel: a pixel's two lists become one, once checked.
        let flat;
        let lists = if lists.shared_list.is_empty() {
            lists
        } else {
            let input = |e: slc_core::CullError| GpuError::Input(e.to_string());
            lists.check(pixels, vpl_count).map_err(input)?;
            flat = lists.flattened().map_err(input)?;
            &flat
        };
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
            writes: Vec::new(),
        })
    }

    /// Reads the fault records of the culling that wrote these lists (16 bytes per list
    /// write) once the work that used them is submitted: a fault of the culling (a sample
    /// behind the camera, a bound beyond f32, entries beyond u32) is an error; `true` where
    /// the lists outgrew their buffer, so they are incomplete (their culler has learnt the
    /// room they need: cull again). Lists that were read before, uploaded or never
    /// counted read nothing.
    pub fn outgrown(&self, ctx: &GpuContext) -> Result<bool, GpuError> {
        for write in &self.writes {
            let total = read_status(ctx, &write.status, write.width)?;
            if total > write.held {
                write.room.learn(total);
                return Ok(true);
            }
        }
        Ok(false)
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
        writes: Vec::new(),
    })
}

/// Reads `gpu` back as [`LightLists`] in the CPU's convention: empty lists dropped (their
/// pixels get [`NO_LIST`]) and the rest renumbered in order. Lists that outgrew their buffer
/// are [`GpuError::ListsOutgrown`] (read them through [`crate::cull::room::use_settled`]).
pub fn read_lists(ctx: &GpuContext, gpu: &GpuLightLists) -> Result<LightLists, GpuError> {
    if gpu.outgrown(ctx)? {
        return Err(GpuError::ListsOutgrown(
            "cull again (the culler now leaves room for them)".into(),
        ));
    }
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
    // The entries may be fewer than the buffer holds (a count's capacity, `device::count`).
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
        shared_list: Vec::new(),
    }
}
