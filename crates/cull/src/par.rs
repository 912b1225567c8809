//! A parallel map that may fail, written straight into a `Vec` that a caller may keep from
//! frame to frame. rayon's `collect::<Result<Vec<_>, _>>()` is not indexed: it
//! gathers pieces in a linked list and copies them into place, which for per-VPL records of a
//! hundred bytes and more costs as much as building a good part of them.
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};

/// Whether memory kept from an earlier frame with room for `capacity` items is more than four
/// times what a frame of `needed` items uses: then it is dropped, so that a frame much smaller
/// than the last does not hold the last one's memory (`crate::ListedReach`,
/// `crate::BoundedMemory`).
pub(crate) fn too_large_to_keep(capacity: usize, needed: usize) -> bool {
    capacity / 4 > needed
}

/// `f(i, item)` for every item, in parallel, collected in the items' order; or, if any call
/// fails, one of the errors (which one when several fail depends on the threads, as with
/// rayon's collect). Unlike rayon's collect it does not stop early: the other items are
/// still mapped, and `placeholder` fills the slots of those that failed.
///
/// Written into `out`, whose old items are dropped and whose memory is reused where it has
/// room: a table of a few hundred MB written afresh every frame costs its page faults every
/// frame (about a third of forming a million VPLs' early exits). On an error `out` holds the
/// mapped items with `placeholder` in the failed slots.
pub(crate) fn try_map_into<T, U, E>(
    items: &[T],
    placeholder: U,
    f: impl Fn(usize, &T) -> Result<U, E> + Sync + Send,
    out: &mut Vec<U>,
) -> Result<(), E>
where
    T: Sync,
    U: Copy + Send + Sync,
    E: Send,
{
    let error = Mutex::new(None);
    items
        .par_iter()
        .enumerate()
        .map(|(i, item)| {
            f(i, item).unwrap_or_else(|e| {
                error
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .get_or_insert(e);
                placeholder
            })
        })
        .collect_into_vec(out);
    match error.into_inner().unwrap_or_else(PoisonError::into_inner) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Into a new `Vec`.
    fn try_map<E: Send>(
        items: &[u32],
        f: impl Fn(usize, &u32) -> Result<u32, E> + Sync + Send,
    ) -> Result<Vec<u32>, E> {
        let mut out = Vec::new();
        try_map_into(items, 0, f, &mut out)?;
        Ok(out)
    }

    #[test]
    fn maps_in_order_or_fails() {
        let items: Vec<u32> = (0..10_000).collect();
        let doubled = try_map(&items, |i, &v| Ok::<_, ()>(v * 2 + i as u32)).unwrap();
        assert_eq!(doubled, (0..10_000).map(|v| v * 3).collect::<Vec<_>>());
        let failed = try_map(&items, |_, &v| if v == 7_777 { Err(v) } else { Ok(v) });
        assert_eq!(failed, Err(7_777));
        assert_eq!(try_map(&[], |_, &v| Ok::<_, ()>(v)), Ok(vec![]));
    }

    /// Into a used `Vec`, larger or smaller than the items: the same items, its memory
    /// kept where it had room.
    #[test]
    fn maps_into_used_memory() {
        let items: Vec<u32> = (0..5_000).collect();
        let mut out = vec![7u32; 9_000];
        let before = out.as_ptr();
        try_map_into(&items, 0, |i, &v| Ok::<_, ()>(v + i as u32), &mut out).unwrap();
        assert_eq!(out, (0..5_000).map(|v| 2 * v).collect::<Vec<_>>());
        assert_eq!(out.as_ptr(), before);
        let more: Vec<u32> = (0..20_000).collect();
        try_map_into(&more, 0, |_, &v| Ok::<_, ()>(v), &mut out).unwrap();
        assert_eq!(out, more);
        let failed = try_map_into(
            &items,
            9,
            |_, &v| if v == 3 { Err(v) } else { Ok(v) },
            &mut out,
        );
        assert_eq!(failed, Err(3));
        assert_eq!((out.len(), out[3], out[4]), (5_000, 9, 4));
    }
}
