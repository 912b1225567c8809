//! Memory a caller keeps from frame to frame (`crate::ListedReach`, `crate::BoundedMemory`):
//! a table of a few hundred MB written afresh every frame costs its page faults every frame
//! (about a third of forming a million VPLs' early exits), so the tables are written into the
//! last frame's memory, unless it is much larger than this frame needs.

/// Whether memory kept from an earlier frame with room for `capacity` items is more than four
/// times what a frame of `needed` items uses: then it is dropped, so that a frame much smaller
/// than the last does not hold the last one's memory.
pub(crate) fn too_large_to_keep(capacity: usize, needed: usize) -> bool {
    capacity / 4 > needed
}
