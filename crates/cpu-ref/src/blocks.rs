//! Images computed 4x2 pixel block by block, the eight pixels of a block as the lanes of a
//! ray packet ([`crate::tracer::Rays8`]): bands of two rows in parallel, every pixel written
//! in place once (no per-pixel allocation, no clear).
use crate::frame_images::emptied;
use rayon::prelude::*;

/// Pixels per block: 4 across, 2 down; lane `l` is pixel (l % 4, l / 4) of the block.
pub const BLOCK: (u32, u32) = (4, 2);

/// One block of a `width` x `height` image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    /// The top-left pixel.
    pub i0: u32,
    pub j0: u32,
    /// Lane l is a pixel of the image where bit l is set (blocks at the right and bottom
    /// edges have fewer).
    pub used: u8,
    width: u32,
}

impl Block {
    /// The pixel (column, row) of lane `lane`.
    pub fn pixel(&self, lane: usize) -> (u32, u32) {
        (
            self.i0 + lane as u32 % BLOCK.0,
            self.j0 + lane as u32 / BLOCK.0,
        )
    }

    /// The row-major index of lane `lane`'s pixel.
    pub fn index(&self, lane: usize) -> usize {
        let (i, j) = self.pixel(lane);
        j as usize * self.width as usize + i as usize
    }

    /// The lanes in use, lowest first.
    pub fn lanes(&self) -> impl Iterator<Item = usize> {
        let used = self.used;
        (0..8).filter(move |l| used & (1 << l) != 0)
    }
}

/// The `width` x `height` row-major image whose pixels `block` gives, eight at a time (its
/// lanes outside the image are dropped), written into `spare`'s memory (a previous frame's)
/// where it fits (`frame_images::emptied`): a frame's fresh memory costs page faults, about
/// a fifth of a second per GB on this machine, where memory written before costs none.
pub fn par_blocks<T: Send>(
    width: u32,
    height: u32,
    spare: Vec<T>,
    block: impl Fn(Block) -> [T; 8] + Sync,
) -> Vec<T> {
    let n = width as usize * height as usize;
    let mut pixels = emptied(spare, n);
    let band_len = BLOCK.1 as usize * width.max(1) as usize;
    pixels.spare_capacity_mut()[..n]
        .par_chunks_mut(band_len)
        .enumerate()
        .for_each(|(b, band)| {
            let rows = (band.len() / width as usize) as u32;
            let j0 = b as u32 * BLOCK.1;
            for i0 in (0..width).step_by(BLOCK.0 as usize) {
                let mut used = 0u8;
                for lane in 0..8u32 {
                    if i0 + lane % BLOCK.0 < width && lane / BLOCK.0 < rows {
                        used |= 1 << lane;
                    }
                }
                let block_at = Block {
                    i0,
                    j0,
                    used,
                    width,
                };
                for (lane, value) in block(block_at).into_iter().enumerate() {
                    if used & (1 << lane) != 0 {
                        let (i, j) = block_at.pixel(lane);
                        band[(j - j0) as usize * width as usize + i as usize].write(value);
                    }
                }
            }
        });
    // SAFETY: the bands cover the first n elements, the blocks of a band cover its rows, and
    // every pixel of a block (the lanes in `used`) is written just above.
    unsafe { pixels.set_len(n) };
    pixels
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pixel is written once, with its own block's lane, at sizes with partial blocks.
    #[test]
    fn blocks_cover_every_pixel_once() {
        for (w, h) in [(0, 0), (1, 1), (3, 5), (4, 2), (9, 7), (64, 3)] {
            // Fresh memory, and memory of a larger and of a smaller image before.
            for spare in [0, 100, 2] {
                let spare = vec![((7, 7), 7); spare];
                let image = par_blocks(w, h, spare, |b| {
                    std::array::from_fn(|l| (b.pixel(l), b.index(l)))
                });
                assert_eq!(image.len(), (w * h) as usize);
                for (k, &((i, j), index)) in image.iter().enumerate() {
                    assert_eq!((index, (j * w + i) as usize), (k, k));
                }
            }
        }
    }
}
