//! Culling metrics by brute force: every light list against the truth of every (pixel, VPL)
//! pair of the pixel's interleaved subregion (paper section 7, Fig. 9-10: lights per pixel
//! and false discovery rate).
//!
//! A pair *contributes* when the VPL is in the pixel's subregion and the roulette of eq. (3)
//! accepts it there: p(ωo, l) > ξ with p of eq. (2), `I = scalar_intensity(vpl.intensity(ωo))`,
//! ωo the unit direction from the VPL to the pixel's G-buffer position and l² its squared
//! distance, computed exactly as the shader does. A pair at distance 0 has no direction and
//! contributes nothing. Pairs outside the VPL's own bound (the spheroid or section-6 sphere,
//! [`crate::reach`], tested against a tile's samples eight at a time by [`ReceiverChunks`])
//! and those whose roulette the lanes reject are skipped without evaluating p exactly as the
//! shader: there p <= ξ, which the property test
//! of slc-cpu-ref (`tests/early_exits.rs`) checks at the bounds' edges and the guarantee tests
//! check against every pair's p on their scenes.
use crate::lists::pixel_count;
use crate::partition::Partition;
use crate::reach::VplReach;
use crate::receiver_chunks::{Passing, ReceiverChunks};
use crate::tiles::{Band, Tile, TileOrder};
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::{scalar_intensity, StochasticParams};
pub use slc_core::CullMetrics;
use slc_core::{CullError, CullInput, GSample, LightLists, Vpl};

/// The metrics of `lists` for `input`; see [`measure_all`].
pub fn measure(input: &CullInput, lists: &LightLists) -> Result<CullMetrics, CullError> {
    Ok(measure_all(input, &[lists])?.remove(0))
}

/// The metrics of several sets of light lists for the same input, evaluating each pair's
/// truth once: O(pixels x VPLs per subregion), in parallel over bands of rows. Errors when δ
/// or a ξ is out of its domain, or when a set of lists does not fit the input.
pub fn measure_all(
    input: &CullInput,
    lists: &[&LightLists],
) -> Result<Vec<CullMetrics>, CullError> {
    let pixels = pixel_count(input.gbuffer)?;
    let partition = Partition::new(input.vpls, input.interleaving)?;
    for l in lists {
        l.check(pixels, input.vpls.len())?;
    }
    let (roulette, reach) = VplReach::of_frame(input.vpls, input.delta, None)?;
    let m = lists.len();
    let (w, h, k) = (
        input.gbuffer.width,
        input.gbuffer.height,
        input.interleaving.k,
    );
    let order = TileOrder::new(w, h, k)?;
    // Per pixel and list set: [listed, true positives, missed].
    let mut stats = vec![[0u32; 3]; pixels * m];
    order.bands(&mut stats, m)?.into_par_iter().for_each_init(
        TruthScratch::default,
        |scratch, band| {
            let Band { tiles, mut rows } = band;
            for tile in tiles {
                scratch.truth(
                    input,
                    tile,
                    partition.of(tile.subregion(k)),
                    &reach,
                    &roulette,
                );
                scratch.stats.clear();
                for (slot, [x, y]) in tile.pixels(k).enumerate() {
                    let p = (y * w + x) as usize;
                    let truth = &scratch.truth[slot];
                    for l in lists {
                        let listed = l.for_pixel(p);
                        let tp = matches(&listed, truth, &mut scratch.sorted);
                        scratch
                            .stats
                            .push([listed.len() as u32, tp, truth.len() as u32 - tp]);
                    }
                }
                rows.put(tile, &scratch.stats);
            }
        },
    );
    Ok((0..m)
        .map(|k| summarize(stats.iter().skip(k).step_by(m.max(1)), pixels))
        .collect())
}

/// Scratch of one thread: per pixel of a tile the VPLs the roulette accepts there, the
/// tile's receivers in lanes and the chunks where one VPL passes, a sorted copy of a list
/// and the tile's statistics per pixel and list set.
#[derive(Default)]
struct TruthScratch {
    truth: Vec<Vec<u32>>,
    stats: Vec<[u32; 3]>,
    slots: Vec<usize>,
    receivers: ReceiverChunks,
    passing: Vec<Passing>,
    sorted: Vec<u32>,
}

impl TruthScratch {
    /// Fills `self.truth[slot]` for every pixel of `tile` with the VPLs of `subregion`
    /// (ascending) that the roulette accepts there: each VPL tested against eight of the
    /// tile's samples at a time ([`ReceiverChunks`], normals ignored), the pairs that pass
    /// checked by [`accepts`].
    fn truth(
        &mut self,
        input: &CullInput,
        tile: &Tile,
        subregion: &[u32],
        reach: &[VplReach],
        roulette: &[StochasticParams],
    ) {
        let (width, k) = (input.gbuffer.width, input.interleaving.k);
        self.slots.clear();
        let pixels = tile.pixel_count();
        let samples = &input.gbuffer.samples;
        let receivers = tile.pixels(k).enumerate().filter_map(|(slot, [x, y])| {
            let g = samples[(y * width + x) as usize].as_ref()?;
            self.slots.push(slot);
            Some((g.position, g.normal))
        });
        self.receivers.refill(receivers);
        self.truth
            .resize_with(self.truth.len().max(pixels), Vec::new);
        for t in &mut self.truth[..pixels] {
            t.clear();
        }
        self.receivers
            .passing(reach, subregion, false, &mut self.passing);
        for chunk in &self.passing {
            let i = chunk.vpl;
            let mut bits = chunk.bits;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let slot = self.slots[chunk.chunk * 8 + lane];
                // Where the lanes decided with the shader's own values, they accepted.
                let accepted = chunk.exact(lane).is_some() || {
                    let [x, y] = tile.pixel(k, slot);
                    let g = samples[(y * width + x) as usize]
                        .as_ref()
                        .expect("a receiver has a sample");
                    accepts(&roulette[i as usize], g, &input.vpls[i as usize])
                };
                if accepted {
                    self.truth[slot].push(i);
                }
            }
        }
    }
}

/// Totals and per-pixel arrays of one list set from its per-pixel [listed, TP, missed].
fn summarize<'a>(stats: impl Iterator<Item = &'a [u32; 3]>, pixels: usize) -> CullMetrics {
    let mut m = CullMetrics {
        lights_per_pixel: Vec::with_capacity(pixels),
        fdr_per_pixel: Vec::with_capacity(pixels),
        ..CullMetrics::default()
    };
    let mut listed_total = 0u64;
    for &[listed, tp, missed] in stats {
        let fp = listed - tp;
        m.true_positive_pairs += u64::from(tp);
        m.false_positive_pairs += u64::from(fp);
        m.missed_pairs += u64::from(missed);
        listed_total += u64::from(listed);
        m.lights_per_pixel.push(listed);
        m.fdr_per_pixel
            .push(ratio(u64::from(fp), u64::from(listed)) as f32);
    }
    m.lights_per_pixel_mean = ratio(listed_total, pixels as u64);
    m.false_discovery_rate = ratio(m.false_positive_pairs, listed_total);
    m
}

/// `a / b`, 0 when b = 0.
fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 {
        0.0
    } else {
        a as f64 / b as f64
    }
}

/// The number of distinct entries of `listed` that are in `truth` (ascending): the true
/// positives. `listed` is sorted into `scratch` first unless already ascending.
fn matches(listed: &[u32], truth: &[u32], scratch: &mut Vec<u32>) -> u32 {
    let listed = if listed.is_sorted() {
        listed
    } else {
        scratch.clear();
        scratch.extend_from_slice(listed);
        scratch.sort_unstable();
        scratch
    };
    let (mut j, mut tp) = (0, 0);
    for &t in truth {
        while j < listed.len() && listed[j] < t {
            j += 1;
        }
        if j < listed.len() && listed[j] == t {
            tp += 1;
        }
    }
    tp
}

/// Whether the roulette of eq. (3) with `params` accepts `vpl` at the G-buffer sample `g`.
#[inline]
fn accepts(params: &StochasticParams, g: &GSample, vpl: &Vpl) -> bool {
    let d: Vec3 = g.position - vpl.position;
    let l2 = d.length_squared();
    if l2 <= 0.0 {
        return false;
    }
    let omega = d / l2.sqrt();
    params.probability(scalar_intensity(vpl.intensity(omega)), l2) > params.xi()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_counts_distinct_true_entries() {
        let mut s = Vec::new();
        assert_eq!(matches(&[1, 3, 5, 7], &[3, 4, 7, 9], &mut s), 2);
        assert_eq!(
            matches(&[7, 3, 3, 1], &[3, 7], &mut s),
            2,
            "unsorted, duplicated"
        );
        assert_eq!(matches(&[], &[1], &mut s), 0);
        assert_eq!(matches(&[1], &[], &mut s), 0);
    }
}
