//! Room for light lists whose total stays on the GPU inside a frame.
//!
//! A list culler (tiled lists, clustered, the tight refinement) counts its lists, scans the
//! counts and writes the lists in one submission, into a buffer sized from what earlier
//! frames needed ([`ListRoom`]); the write kernels drop entries beyond the buffer's end. The
//! scan's total lands in the culling's fault record, which is read once the work that used
//! the lists is done ([`GpuLightLists::outgrown`], with the shaded image). Lists that
//! outgrew their buffer are culled again with room for them and used again
//! ([`use_settled`]): a frame whose lists grow beyond every earlier frame's pays a second
//! culling, and no frame waits for a count between culling and shading.
use crate::cull::frame::CullFrame;
use crate::cull::lists::GpuLightLists;
use crate::device::buffers::output;
use crate::device::context::{GpuContext, GpuError};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

/// The most times [`use_settled`] culls again: each retry settles at least the first list
/// write of a chain that outgrew its buffer (a chain has at most two: base lists and their
/// tight refinement), so two retries always suffice.
const RETRIES: usize = 2;

/// The room a list buffer gets before any frame needed more: 2^20 entries (4 MiB of `u32`)
/// or one per pixel, whichever is more.
const FIRST_ROOM: u64 = 1 << 20;

/// What a culler's lists needed in earlier frames: the room its next list buffer gets.
/// Shared (`Arc`) with the lists it wrote, which report their totals back to it.
#[derive(Debug, Default)]
pub struct ListRoom {
    /// The most entries a frame needed or the room set by [`Self::set`]; 0 before either.
    needed: AtomicU32,
}

impl ListRoom {
    pub fn new() -> Self {
        Self::default()
    }

    /// Entries of `T` in the next buffer for `frame`'s lists, `lists_per_subregion` in each
    /// of its K² subregions: what the most demanding earlier frame needed with a quarter
    /// more, before any frame `FIRST_ROOM` or one per pixel; never more than the lists can
    /// hold (`most_entries`) or the storage-binding limit allows, never less than an
    /// earlier frame's total.
    pub fn entries<T>(&self, ctx: &GpuContext, frame: &CullFrame, lists_per_subregion: u64) -> u32 {
        let size = std::mem::size_of::<T>().max(1) as u64;
        let most = most_entries(lists_per_subregion, frame.vpls.capacity());
        let limit = (ctx.storage_limit() / size).min(most);
        let pixels = u64::from(frame.width) * u64::from(frame.height);
        room(self.needed.load(Ordering::Relaxed), pixels, limit)
    }

    /// A zeroed list buffer of [`Self::entries`] `u32`s for `frame`'s lists, and the
    /// [`ListWrite`] that reads their total from `status` (the fault record their scan
    /// fills) and reports it to this room.
    pub(crate) fn buffer(
        self: &Arc<Self>,
        ctx: &GpuContext,
        frame: &CullFrame,
        label: &str,
        lists_per_subregion: u64,
        status: &wgpu::Buffer,
    ) -> Result<(wgpu::Buffer, ListWrite), GpuError> {
        let entries = self.entries::<u32>(ctx, frame, lists_per_subregion);
        let buffer = output::<u32>(ctx, label, entries as usize)?;
        let write = ListWrite {
            status: status.clone(),
            // What the write kernels' `arrayLength` sees: at least the smallest binding.
            held: u32::try_from(buffer.size() / 4).unwrap_or(u32::MAX),
            room: Arc::clone(self),
            width: frame.width,
        };
        Ok((buffer, write))
    }

    /// Records that a frame's lists needed `total` entries.
    pub fn learn(&self, total: u32) {
        self.needed.fetch_max(total, Ordering::Relaxed);
    }

    /// Sets the room of the next frames to `entries` (at least 1), e.g. to preallocate for a
    /// known scene or to test culling again; later frames that need more grow it again.
    pub fn set(&self, entries: u32) {
        self.needed.store(entries.max(1), Ordering::Relaxed);
    }
}

/// [`ListRoom::entries`] for `needed` (0: nothing learnt yet), at most `limit` unless an
/// earlier frame needed more (then its allocation is refused as too large).
fn room(needed: u32, pixels: u64, limit: u64) -> u32 {
    let limit = limit.min(u64::from(u32::MAX));
    match u64::from(needed) {
        0 => FIRST_ROOM.max(pixels).min(limit) as u32,
        n => (n + n / 4).min(limit).max(n) as u32,
    }
}

/// The most entries lists can hold: each lists only VPLs of its own subregion, so with
/// `lists_per_subregion` lists in each of the K² subregions they hold at most that many
/// times the frame's VPLs (`vpls`, the count's capacity).
fn most_entries(lists_per_subregion: u64, vpls: usize) -> u64 {
    lists_per_subregion.saturating_mul(vpls as u64)
}

/// One list write of a culling whose total is read after the frame: its fault record
/// (`GpuCullStatus`, the total from the scan of its counts), the entries its buffer held and
/// the room it was sized from.
#[derive(Clone)]
pub struct ListWrite {
    pub(crate) status: wgpu::Buffer,
    pub(crate) held: u32,
    pub(crate) room: Arc<ListRoom>,
    /// The frame's width (names a faulty pixel).
    pub(crate) width: u32,
}

/// Runs `use_lists` on `lists`, then reads whether they outgrew their buffer
/// ([`GpuLightLists::outgrown`]); where they did, culls again (`recull`, now with room for
/// them) and runs `use_lists` again. Returns what the last run gave and the lists it ran
/// on, whose records are read (reading them again reads nothing).
pub fn use_settled<T>(
    ctx: &GpuContext,
    mut lists: GpuLightLists,
    recull: impl Fn() -> Result<GpuLightLists, GpuError>,
    mut use_lists: impl FnMut(&GpuLightLists) -> Result<T, GpuError>,
) -> Result<(T, GpuLightLists), GpuError> {
    for retry in 0..=RETRIES {
        let out = use_lists(&lists)?;
        if !lists.outgrown(ctx)? {
            lists.writes.clear();
            return Ok((out, lists));
        }
        if retry < RETRIES {
            lists = recull()?;
        }
    }
    Err(GpuError::ListsOutgrown(format!(
        "still after {RETRIES} cullings with the room they needed"
    )))
}

/// The lists `cull` makes, complete: their totals read, culled again where they outgrew
/// their buffer.
pub fn settled(
    ctx: &GpuContext,
    cull: impl Fn() -> Result<GpuLightLists, GpuError>,
) -> Result<GpuLightLists, GpuError> {
    Ok(use_settled(ctx, cull()?, cull, |_| Ok(()))?.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn room_follows_what_frames_needed_within_the_limits() {
        // Before any frame: 2^20 entries or one per pixel, within the bound.
        assert_eq!(room(0, 640 * 360, u64::MAX), 1 << 20);
        assert_eq!(room(0, 1920 * 1080, u64::MAX), 1920 * 1080);
        assert_eq!(room(0, 1920 * 1080, 5_000), 5_000);
        assert_eq!(room(0, 1 << 40, u64::MAX), u32::MAX);
        assert_eq!(room(0, 0, 0), 0);
        // After: a quarter more than the most a frame needed, within the bound and the
        // binding limit, but never less than that total (its allocation then fails loudly).
        assert_eq!(room(1_000, 10, u64::MAX), 1_250);
        assert_eq!(room(1_000, 10, 1_100), 1_100);
        assert_eq!(room(1_000, 10, 900), 1_000);
        assert_eq!(room(u32::MAX, 10, u64::MAX), u32::MAX);
        assert_eq!(room(u32::MAX - 3, 10, u64::MAX), u32::MAX);
        // Learning keeps the largest; setting overrides it.
        let r = ListRoom::new();
        r.learn(7);
        r.learn(3);
        assert_eq!(r.needed.load(Ordering::Relaxed), 7);
        r.set(0);
        assert_eq!(r.needed.load(Ordering::Relaxed), 1);
    }

    #[test]
    fn lists_hold_at_most_their_subregions_vpls() {
        assert_eq!(most_entries(2 * 15 * 9, 51_468), 2 * 15 * 9 * 51_468);
        assert_eq!(most_entries(u64::MAX, 2), u64::MAX);
    }
}
