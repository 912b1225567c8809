//! The VPLs a frame's light lists hold, for the shading's table of early exits
//! (`slc_cull::VplReach`): which VPLs, where each lies in that table, and whether forming
//! its bounds pays ([`BOUNDED_PIXELS`]).
use rayon::prelude::*;
use slc_core::{LightLists, NO_LIST};
use std::sync::atomic::{AtomicU32, Ordering};

/// A listed VPL's early exits include its bounds (`VplReach::new`) where the lists that hold
/// it cover at least this many pixels (each list counted with the pixels whose own or shared
/// list it is, and at least once), else only its sign tests and roulette
/// (`VplReach::without_bounds`: about 52 ns a VPL on one thread against 192, measured on
/// Sponza's VPLs at RSM 1024; 155 against 222 when the limit was chosen, before the own
/// bounds' lanes). With a million VPLs most of `binned`'s listed VPLs reach only
/// a pixel or two (docs/many-vpls.md), while nearly every tile's or cluster's list covers
/// more than this on its own. Of the limits tried in scratch runs on Sponza at 480x270
/// (1, that is every VPL bounded, 32 and 255; at 6b6e493, where the VPLs without bounds
/// skipped their own bound too), 32 and 255 made `binned`'s shading at RSM 1024 equally
/// faster than 1, and none changed it at RSM 256 beyond the noise; 32 keeps the
/// bounds for the VPLs that reach tens of pixels. The exits reject only pairs the shader
/// gives 0, so the image is the same either way.
pub(crate) const BOUNDED_PIXELS: u8 = 32;

/// The VPLs a frame's lists hold ([`ListedVpls::of`]).
#[derive(Debug, PartialEq)]
pub(crate) struct ListedVpls {
    /// The VPLs the lists hold, ascending.
    pub listed: Vec<u32>,
    /// Per listed VPL, whether its lists cover at least [`BOUNDED_PIXELS`] pixels.
    pub bounded: Vec<bool>,
    /// The lists' entries renumbered to their places in `listed` (an order-preserving map:
    /// every list keeps its order).
    pub indices: Vec<u32>,
}

impl ListedVpls {
    /// The listed VPLs of `lists`, which must be checked for `vpls` VPLs. The entries
    /// (millions with many VPLs) are counted and renumbered in parallel; the result does not
    /// depend on the threads.
    pub(crate) fn of(lists: &LightLists, vpls: usize) -> Self {
        let covers = list_pixels(lists);
        // Per VPL, the pixels of the lists that hold it, added until they reach
        // `BOUNDED_PIXELS`: read first, so a VPL listed at many pixels is mostly read, its
        // line not fought over. A VPL stays below the limit only where every entry was
        // added, so the outcome does not depend on the threads.
        let mut count: Vec<AtomicU32> = (0..vpls)
            .into_par_iter()
            .map(|_| AtomicU32::new(0))
            .collect();
        let enough = u32::from(BOUNDED_PIXELS);
        let add = |entries: &[u32], pixels: u32| {
            for &v in entries {
                let c = &count[v as usize];
                if c.load(Ordering::Relaxed) < enough {
                    c.fetch_add(pixels, Ordering::Relaxed);
                }
            }
        };
        (0..lists.len())
            .into_par_iter()
            .with_min_len(256)
            .for_each(|l| {
                let (entries, pixels) = (lists.list(l as u32), u32::from(covers[l]).max(1));
                // A long list (`none` lists every VPL K² times) is shared out as well.
                match entries.len() > LONG_LIST {
                    true => entries
                        .par_chunks(LONG_LIST)
                        .for_each(|entries| add(entries, pixels)),
                    false => add(entries, pixels),
                }
            });
        let (mut listed, mut bounded) = (Vec::new(), Vec::new());
        for (v, c) in count.iter_mut().enumerate() {
            let c = c.get_mut();
            if *c != 0 {
                bounded.push(*c >= enough);
                *c = listed.len() as u32;
                listed.push(v as u32);
            }
        }
        let indices = lists
            .indices
            .par_iter()
            .map(|&v| count[v as usize].load(Ordering::Relaxed))
            .collect();
        Self {
            listed,
            bounded,
            indices,
        }
    }
}

/// Entries of one list counted on one thread, at most.
const LONG_LIST: usize = 1 << 14;

/// Pieces of the pixels counted apart by [`list_pixels`], at most: each holds a count per
/// list (a byte per pixel with lists per pixel), so many threads do not each get one.
const MOST_PIECES: usize = 4;

/// Per list of `lists`, how many pixels name it as their own or shared list, up to
/// [`BOUNDED_PIXELS`]: counted over a few pieces of the pixels in parallel, then added in
/// parallel over the lists.
fn list_pixels(lists: &LightLists) -> Vec<u8> {
    let pixels = lists.pixel_list.len();
    let pieces = rayon::current_num_threads().clamp(1, MOST_PIECES);
    let piece = pixels.div_ceil(pieces).max(1);
    let counts: Vec<Vec<u8>> = (0..pixels.div_ceil(piece))
        .into_par_iter()
        .map(|i| {
            let range = i * piece..((i + 1) * piece).min(pixels);
            let shared = lists.shared_list.get(range.clone()).unwrap_or(&[]);
            let mut counts = vec![0u8; lists.len()];
            for &l in lists.pixel_list[range].iter().chain(shared) {
                if l != NO_LIST {
                    let c = &mut counts[l as usize];
                    *c = c.saturating_add(1).min(BOUNDED_PIXELS);
                }
            }
            counts
        })
        .collect();
    let mut counts = counts.into_iter();
    let mut total = counts.next().unwrap_or_else(|| vec![0; lists.len()]);
    let more: Vec<Vec<u8>> = counts.collect();
    const SPAN: usize = 1 << 16;
    total
        .par_chunks_mut(SPAN)
        .enumerate()
        .for_each(|(i, span)| {
            for piece in &more {
                for (t, &m) in span.iter_mut().zip(&piece[i * SPAN..]) {
                    *t = t.saturating_add(m).min(BOUNDED_PIXELS);
                }
            }
        });
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random lists of up to `vpls` VPLs (up to `longest` entries each) for `pixels` pixels:
    /// own lists (some named by many pixels, some by one, some by none) and, in half the
    /// cases, shared lists.
    fn random_lists(seed: u64, pixels: usize, vpls: u32, longest: u64) -> LightLists {
        let mut state = seed | 1;
        let mut next = move |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        let mut lists = LightLists::default();
        lists.offsets.push(0);
        let count = 1 + next(pixels as u64 / 2 + 2) as u32;
        for _ in 0..count {
            let len = next(longest);
            let mut list: Vec<u32> = (0..len).map(|_| next(u64::from(vpls)) as u32).collect();
            list.sort_unstable();
            list.dedup();
            lists.indices.extend(list);
            lists.offsets.push(lists.indices.len() as u32);
        }
        let mut pick = |wide: bool| {
            let l = match wide {
                true => next(u64::from(count).min(3)) as u32,
                false => next(u64::from(count)) as u32,
            };
            if next(5) == 0 {
                NO_LIST
            } else {
                l
            }
        };
        lists.pixel_list = (0..pixels).map(|p| pick(p % 2 == 0)).collect();
        if seed.is_multiple_of(2) {
            lists.shared_list = (0..pixels).map(|p| pick(p % 3 == 0)).collect();
        }
        lists
    }

    /// The same, one entry at a time.
    fn brute_force(lists: &LightLists, vpls: usize) -> ListedVpls {
        let mut pixels = vec![0u32; lists.len()];
        for &l in lists.pixel_list.iter().chain(&lists.shared_list) {
            if l != NO_LIST {
                pixels[l as usize] += 1;
            }
        }
        let mut covered = vec![0u32; vpls];
        let mut held = vec![false; vpls];
        for (l, &pixels) in pixels.iter().enumerate() {
            for &v in lists.list(l as u32) {
                covered[v as usize] += pixels.max(1);
                held[v as usize] = true;
            }
        }
        let listed: Vec<u32> = (0..vpls as u32).filter(|&v| held[v as usize]).collect();
        let bounded = listed
            .iter()
            .map(|&v| covered[v as usize] >= u32::from(BOUNDED_PIXELS))
            .collect();
        let indices = lists
            .indices
            .iter()
            .map(|v| listed.binary_search(v).unwrap() as u32)
            .collect();
        ListedVpls {
            listed,
            bounded,
            indices,
        }
    }

    /// Random lists give what counting one entry at a time gives, on one thread and on
    /// several; both kinds of VPL occur.
    #[test]
    fn listed_vpls_are_the_lists_vpls_with_the_pixels_they_cover() {
        let pools: Vec<rayon::ThreadPool> = [1, 3]
            .map(|n| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .unwrap()
            })
            .into();
        let mut kinds = [0usize; 2];
        for seed in 0..202u64 {
            let (pixels, vpls, longest) = match seed {
                // Lists enough for several spans of the counts' addition.
                200 => (300_000, 5_000, 12),
                // Lists longer than one thread counts.
                201 => (100, 100_000, 60_000),
                _ => (
                    1 + (seed as usize * 37) % 900,
                    1 + (seed as u32 * 13) % 300,
                    12,
                ),
            };
            let lists = random_lists(seed + 1, pixels, vpls, longest);
            lists.check(pixels, vpls as usize).unwrap();
            assert!(
                seed != 200 || lists.len() > 1 << 16,
                "{} lists",
                lists.len()
            );
            assert!(
                seed != 201 || (0..lists.len()).any(|l| lists.list(l as u32).len() > LONG_LIST),
                "no long list"
            );
            let want = brute_force(&lists, vpls as usize);
            for pool in &pools {
                assert_eq!(
                    pool.install(|| ListedVpls::of(&lists, vpls as usize)),
                    want,
                    "seed {seed}"
                );
            }
            for &b in &want.bounded {
                kinds[usize::from(b)] += 1;
            }
        }
        assert!(kinds.iter().all(|&n| n > 500), "{kinds:?}");
    }

    /// No lists, or no pixels: nothing is listed.
    #[test]
    fn empty_lists_list_nothing() {
        let none = ListedVpls::of(&LightLists::default(), 10);
        assert!(none.listed.is_empty() && none.bounded.is_empty() && none.indices.is_empty());
    }
}
