//! [`LightLists`] from (pixel, VPL) pairs gathered with each pixel's in VPL order: a counting
//! sort by pixel that keeps each pixel's VPLs in their order. The pairs arrive split into
//! bands of [`BAND_PIXELS`] consecutive pixels ([`Bands`]), so each band is sorted on its
//! own, in parallel, with its counters in cache: millions of pairs over a whole image's
//! counters miss the cache at nearly every step.
use rayon::prelude::*;
use slc_core::{CullError, LightLists, NO_LIST};

/// Pixels per band: 32,768, whose counters and next places (128 KiB each) stay in a core's
/// cache (1 MiB of L2 on the machine measured).
pub(crate) const BAND_PIXELS: usize = 1 << 15;

/// The pairs of one piece of work, per band (pixel / [`BAND_PIXELS`]), each band's in the
/// order they were pushed.
#[derive(Clone, Debug)]
pub(crate) struct Bands(Vec<Vec<(u32, u32)>>);

impl Bands {
    /// No pairs, for an image of `pixels` pixels.
    pub(crate) fn new(pixels: usize) -> Self {
        Self(vec![Vec::new(); pixels.div_ceil(BAND_PIXELS)])
    }

    /// Adds VPL `vpl` to pixel `pixel`'s list.
    #[inline]
    pub(crate) fn push(&mut self, pixel: u32, vpl: u32) {
        self.0[pixel as usize / BAND_PIXELS].push((pixel, vpl));
    }
}

/// One list per pixel with pairs, numbered in pixel order, from `pieces` (each a [`Bands`]
/// of an image of `pixels` pixels) taken in order: a pixel's list holds its VPLs in the order
/// the pieces, and each piece's pushes, gave them.
pub(crate) fn lists(pieces: &[Bands], pixels: usize) -> Result<LightLists, CullError> {
    let bands = pixels.div_ceil(BAND_PIXELS);
    let range = |b: usize| b * BAND_PIXELS..((b + 1) * BAND_PIXELS).min(pixels);
    let pairs_of = |b: usize| pieces.iter().flat_map(move |piece| &piece.0[b]);
    // Per band: each pixel's count, and how many lists and pairs the band holds.
    let counts: Vec<(Vec<u32>, usize, usize)> = (0..bands)
        .into_par_iter()
        .map(|b| {
            let first = range(b).start;
            let mut counts = vec![0u32; range(b).len()];
            let mut total = 0;
            for &(p, _) in pairs_of(b) {
                counts[p as usize - first] += 1;
                total += 1;
            }
            let lists = counts.iter().filter(|&&c| c > 0).count();
            (counts, lists, total)
        })
        .collect();
    let list_count: usize = counts.iter().map(|c| c.1).sum();
    let total: usize = counts.iter().map(|c| c.2).sum();
    if u32::try_from(total).is_err() {
        return Err(CullError::Input(format!(
            "{total} light-list entries exceed 32-bit offsets"
        )));
    }
    let mut offsets = vec![0u32; list_count + 1];
    offsets[list_count] = total as u32;
    let mut indices = vec![0u32; total];
    let mut pixel_list = vec![NO_LIST; pixels];
    // Each band's share of the three arrays, and its first list and entry.
    let mut shares = Vec::with_capacity(bands);
    let (mut offsets_left, mut indices_left) = (&mut offsets[..list_count], &mut indices[..]);
    let mut pixels_left = &mut pixel_list[..];
    let (mut first_list, mut first_entry) = (0, 0);
    for (b, (_, lists, pairs)) in counts.iter().enumerate() {
        let (o, rest) = offsets_left.split_at_mut(*lists);
        offsets_left = rest;
        let (i, rest) = indices_left.split_at_mut(*pairs);
        indices_left = rest;
        let (p, rest) = pixels_left.split_at_mut(range(b).len());
        pixels_left = rest;
        shares.push((b, o, i, p, first_list, first_entry));
        first_list += lists;
        first_entry += pairs;
    }
    shares.into_par_iter().for_each(
        |(b, offsets, indices, pixel_list, first_list, first_entry)| {
            let first = range(b).start;
            // Per pixel of the band, where its next entry goes within the band's entries.
            let mut next = vec![0u32; range(b).len()];
            let (mut list, mut entry) = (0, 0u32);
            for (p, &count) in counts[b].0.iter().enumerate() {
                if count > 0 {
                    pixel_list[p] = (first_list + list) as u32;
                    offsets[list] = first_entry as u32 + entry;
                    next[p] = entry;
                    list += 1;
                    entry += count;
                }
            }
            for &(p, vpl) in pairs_of(b) {
                let p = p as usize - first;
                indices[next[p] as usize] = vpl;
                next[p] += 1;
            }
        },
    );
    Ok(LightLists {
        offsets,
        indices,
        pixel_list,
        shared_list: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;

    /// The lists of `pairs` as a plain counting sort over the whole image forms them.
    fn by_pixel(pairs: &[(u32, u32)], pixels: usize) -> LightLists {
        let mut per_pixel = vec![Vec::new(); pixels];
        for &(p, v) in pairs {
            per_pixel[p as usize].push(v);
        }
        let mut lists = LightLists {
            offsets: vec![0],
            indices: Vec::new(),
            pixel_list: vec![NO_LIST; pixels],
            shared_list: Vec::new(),
        };
        for (p, vpls) in per_pixel.iter().enumerate() {
            if !vpls.is_empty() {
                lists.pixel_list[p] = (lists.offsets.len() - 1) as u32;
                lists.indices.extend(vpls);
                lists.offsets.push(lists.indices.len() as u32);
            }
        }
        lists
    }

    #[test]
    fn bands_give_the_lists_of_one_counting_sort() {
        let mut rng = Rng(5);
        for pixels in [0, 1, 7, BAND_PIXELS - 1, BAND_PIXELS, 3 * BAND_PIXELS + 5] {
            // Pairs in VPL order across three pieces, clustered on some pixels, none on most.
            let mut pairs = Vec::new();
            let mut pieces = vec![Bands::new(pixels); 3];
            if pixels > 0 {
                for vpl in 0..3000u32 {
                    for _ in 0..(rng.f32() * 4.0) as u32 {
                        let p = (rng.f64().powi(3) * pixels as f64) as u32;
                        pairs.push((p, vpl));
                        pieces[vpl as usize / 1000].push(p, vpl);
                    }
                }
            }
            assert_eq!(
                lists(&pieces, pixels).unwrap(),
                by_pixel(&pairs, pixels),
                "{pixels}"
            );
        }
    }
}
