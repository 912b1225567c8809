//! The full-frame images the CPU passes shade into: cleared on every rayon thread
//! ([`black_image`]), shaded row by row ([`shade_rows`]), or a frame the renderer is done
//! with, reused ([`Spare`]).
use glam::Vec3;
use rayon::prelude::*;
use slc_core::progress::Progress;
use slc_core::{GBuffer, GSample, Image};
use std::fmt;
use std::sync::{Mutex, PoisonError};

/// A `width` x `height` image of zeros, its pixels written by every rayon thread: one thread
/// takes about 3.5 ms to clear a 1920x1080 frame (25 MB) whose pages are resident, and about
/// 11 ms where they are fresh (each page faulted in), a tenth of the CPU shading's time.
pub(crate) fn black_image(width: u32, height: u32) -> Image {
    let mut pixels = Vec::new();
    rayon::iter::repeat_n(Vec3::ZERO, width as usize * height as usize)
        .collect_into_vec(&mut pixels);
    Image {
        width,
        height,
        pixels,
    }
}

/// An image of `gbuffer`'s size, its rows shaded in parallel: `shade(sample, pixel)` adds
/// to each pixel with a sample. Once `progress` is cancelled the rows not begun stay black;
/// each finished row is counted.
pub(crate) fn shade_rows<E: Send>(
    gbuffer: &GBuffer,
    progress: Progress,
    shade: impl Fn(&GSample, &mut Vec3) -> Result<(), E> + Sync,
) -> Result<Image, E> {
    let mut image = black_image(gbuffer.width, gbuffer.height);
    let w = gbuffer.width as usize;
    image
        .pixels
        .par_chunks_mut(w)
        .zip(gbuffer.samples.par_chunks(w))
        .try_for_each(|(out, row)| {
            if progress.cancelled() {
                return Ok(());
            }
            for (o, g) in out.iter_mut().zip(row) {
                if let Some(g) = g {
                    shade(g, o)?;
                }
            }
            progress.advance(w as u64);
            Ok(())
        })?;
    Ok(image)
}

/// Memory a renderer is done with, kept for its next frame: the noisy image its filter
/// consumed (a fresh 1920x1080 frame, 25 MB, is about 5 ms of page faults and writes on two
/// threads), or a prepared frame's buffers (`crate::prepare::FrameSpares`). One value at
/// most; a clone starts empty.
pub(crate) struct Spare<T>(Mutex<Option<T>>);

/// The noisy image kept for the next shading of the same size, which writes every pixel:
/// that frame then costs neither an allocation nor a clear.
pub(crate) type SpareImage = Spare<Image>;

impl<T> Default for Spare<T> {
    fn default() -> Self {
        Self(Mutex::new(None))
    }
}

impl<T> Clone for Spare<T> {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// Whether something is kept, not what.
impl<T> fmt::Debug for Spare<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kept = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        f.write_str(if kept.is_some() {
            "Spare(kept)"
        } else {
            "Spare(none)"
        })
    }
}

impl<T> Spare<T> {
    /// Keeps `value`, in place of the one kept before.
    pub(crate) fn keep(&self, value: T) {
        *self.0.lock().unwrap_or_else(PoisonError::into_inner) = Some(value);
    }

    /// The value kept, if any (no longer kept).
    pub(crate) fn take(&self) -> Option<T> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner).take()
    }
}

/// `spare`, emptied, where it has room for `n` elements and not more than four times that;
/// otherwise a new `Vec` with room for `n`. A frame much smaller than the last does not keep
/// its memory, and none is grown by copying.
pub(crate) fn emptied<T>(mut spare: Vec<T>, n: usize) -> Vec<T> {
    if spare.capacity() < n || spare.capacity() / 4 > n {
        return Vec::with_capacity(n);
    }
    spare.clear();
    spare
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn black_image_is_image_new_written_in_parallel() {
        for (w, h) in [(0, 0), (1, 1), (3, 0), (641, 359)] {
            let image = black_image(w, h);
            let want = Image::new(w, h);
            assert_eq!((image.width, image.height), (want.width, want.height));
            assert_eq!(image.pixels, want.pixels);
        }
    }

    #[test]
    fn spare_memory_is_kept_only_where_it_fits() {
        let spare = |capacity| Vec::<u8>::with_capacity(capacity);
        let kept = |capacity, n| {
            let s = spare(capacity);
            let at = s.as_ptr();
            let e = emptied(s, n);
            assert!(e.is_empty() && e.capacity() >= n);
            e.as_ptr() == at
        };
        assert!(kept(100, 100) && kept(100, 25) && kept(100, 60));
        assert!(!kept(100, 101) && !kept(100, 24) && !kept(0, 1));
    }

    #[test]
    fn a_spare_image_is_taken_once_and_clones_start_empty() {
        let spare = SpareImage::default();
        assert!(spare.take().is_none());
        assert_eq!(format!("{spare:?}"), "Spare(none)");
        spare.keep(Image::new(2, 3));
        spare.keep(Image::new(4, 5));
        assert!(spare.clone().take().is_none());
        assert_eq!(format!("{spare:?}"), "Spare(kept)");
        let kept = spare.take().expect("kept");
        assert_eq!((kept.width, kept.height), (4, 5));
        assert!(spare.take().is_none());
    }
}
