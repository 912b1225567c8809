//! A software prefetch, for the loops that know which records they will read next (a tile's
//! G-buffer samples, K pixels apart; the scatter's next eight VPLs): the hint is issued a
//! step ahead, so the reads that follow find the records in cache.

/// Asks the CPU to bring the cache lines of `value` in. A hint only: it changes no result,
/// and does nothing on other architectures.
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let start = (value as *const T).cast::<i8>();
        let size = core::mem::size_of::<T>();
        let mut offset = 0;
        while offset < size {
            // SAFETY: a prefetch never faults and has no effect on memory; SSE is part of
            // every x86_64 CPU.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) };
            offset += 64;
        }
        if size > 0 {
            // SAFETY: as above: the line of the last byte, when the record straddles one more.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(size - 1)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
