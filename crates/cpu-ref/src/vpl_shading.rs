//! Shading with every VPL (no culling): the exact VPL sum, or the stochastic estimate of
//! paper eq. (3) where each VPL is kept at a pixel only if p(ωo, l) > ξ.
use crate::frame_images::{black_image, shade_rows};
use crate::list_ranks::ListRanks;
use crate::listed_vpls::ListedVpls;
use crate::received_lanes::{received_lanes, ReceiverBrdfs};
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::lanes::F8;
use slc_bounds::stochastic::{scalar_intensity, StochasticParams};
use slc_bounds::BoundsError;
use slc_core::{CullError, CullInput, GBuffer, GSample, Image, LightLists, Progress, Vpl, NO_LIST};
use slc_cull::prefetch::prefetch;
use slc_cull::receiver_chunks::{Passing, MAX_SETS};
use slc_cull::tiles::{Band, Tile, TileOrder};
use slc_cull::{ListedReach, ReceiverChunks, VplReach};

/// How each VPL's contribution is weighted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VplEstimator {
    /// Every VPL contributes fully (p = 1): the all-VPL reference.
    Exact,
    /// Russian roulette with the VPL's ξ: contribution / p where p(ωo, l) = min(I/(δ l²), 1) > ξ
    /// (paper eq. 2-3), zero otherwise. Unbiased with respect to [`VplEstimator::Exact`].
    Stochastic { delta: f32 },
}

/// The contribution of one VPL to the radiance leaving `g` towards the camera:
/// `f(x; ωl, ωo) I(ω) / l² cos θx`, with I the VPL's intensity towards x (paper eq. 1, 4),
/// weighted by the estimator of eq. (3) when `roulette` holds the VPL's (δ, ξ); without visibility.
#[inline]
pub fn vpl_contribution(g: &GSample, vpl: &Vpl, roulette: Option<&StochasticParams>) -> Vec3 {
    let d = g.position - vpl.position;
    let l2 = d.length_squared();
    if l2 <= 0.0 {
        return Vec3::ZERO;
    }
    let omega = d / l2.sqrt(); // from the VPL to x
    received(g, omega, l2, || vpl.intensity(omega), roulette)
}

/// The tail of [`vpl_contribution`] from the unit direction `omega` from the VPL to `g`, the
/// squared distance `l2` and the VPL's intensity towards `g` (called only where cos θx > 0):
/// what `vpl_contribution` returns when those are its own values.
#[inline]
pub fn received(
    g: &GSample,
    omega: Vec3,
    l2: f32,
    intensity: impl FnOnce() -> Vec3,
    roulette: Option<&StochasticParams>,
) -> Vec3 {
    let cos_x = -g.normal.dot(omega);
    if cos_x <= 0.0 {
        return Vec3::ZERO;
    }
    let intensity = intensity();
    let weight = match roulette {
        None => 1.0,
        Some(r) => r.estimator_weight(r.probability(scalar_intensity(intensity), l2)),
    };
    if weight == 0.0 {
        return Vec3::ZERO;
    }
    g.brdf.eval(g.normal, -omega, g.omega_o) * intensity * (weight * cos_x / l2)
}

/// Indirect radiance at every pixel from every VPL; with `visibility`, each VPL-pixel pair
/// is tested with a shadow ray. `progress` is told the number of pixels finished; once it is
/// cancelled the rows not yet begun are left black (the caller checks `progress`). Fails
/// only when δ or a VPL's ξ is out of its domain.
pub fn shade_vpls(
    tracer: &Tracer,
    gbuffer: &GBuffer,
    vpls: &[Vpl],
    estimator: VplEstimator,
    visibility: bool,
    progress: Progress,
) -> Result<Image, BoundsError> {
    let roulette = match estimator {
        VplEstimator::Exact => None,
        VplEstimator::Stochastic { delta } => Some(
            vpls.iter()
                .map(|v| StochasticParams::new(delta, v.xi))
                .collect::<Result<Vec<_>, _>>()?,
        ),
    };
    shade_rows(gbuffer, progress, |g, o| {
        let from = tracer.lift(g.position, g.geometric_normal);
        for (k, vpl) in vpls.iter().enumerate() {
            let c = vpl_contribution(g, vpl, roulette.as_ref().map(|r| &r[k]));
            if c != Vec3::ZERO
                && (!visibility
                    || tracer.unoccluded(from, tracer.lift(vpl.position, vpl.geometric_normal)))
            {
                *o += c;
            }
        }
        Ok(())
    })
}

/// Indirect radiance from culled light lists (paper eq. 3 with interleaved sampling): each
/// pixel sums the VPLs of its list ([`LightLists::for_pixel`]: with a shared list, the union
/// of both, ascending) with weight K²/p when p > ξ. Unbiased as long as the lists miss no VPL
/// with p > ξ at the pixel. Fails when δ, a ξ, K or a listed VPL is out of the domain of
/// slc-bounds and slc-cull, when the lists are malformed ([`LightLists::check`]) or do not
/// fit the G-buffer, or when the image has 2³² pixels or more. Pairs that [`VplReach`]
/// rejects (outside the VPL's own bound, facing away at either end, or not accepted by the
/// roulette) are skipped before the receiver's BRDF: their contribution is exactly 0, so the
/// image is the same bit for bit. A VPL's bounds (its own and over boxes) are formed only
/// where its lists cover enough pixels to earn them back (`listed_vpls::BOUNDED_PIXELS`);
/// the others are tested by their signs and the roulette alone. The pixels are shaded tile
/// by tile (the culling's tiles), band by band of [`TileOrder::bands`] in parallel, the K
/// tiles at one place of a row of subregions one after another (they share the G-buffer's
/// cache lines), each tile's pixels grouped by their lists (own and shared) in Z order and
/// written in place. The pixels of a
/// list are shaded VPL by VPL, each VPL first tested against the box of the pixels (its
/// bound of p over boxes, eight VPLs at a time: [`VplReach::box_may_exceed_xi`]), then
/// against eight of them at a time ([`ReceiverChunks`]), the short lists of a tile sharing
/// their chunks ([`SHARED_WINDOW_PIXELS`]). Where those lanes accepted a pair with the
/// shader's own operations, their ωo, l² and I(ωo) are used as they are, and the receiver's
/// BRDF is formed eight receivers at a time as well (`received_lanes`, else [`received`]).
/// Every pixel sums its VPLs in the order of `for_pixel` either way. `progress` is told the
/// pixels of each tile shaded; once it is cancelled the tiles not yet begun are left
/// unshaded (the caller checks `progress`).
pub fn shade_lists(
    tracer: &Tracer,
    input: &CullInput,
    lists: &LightLists,
    visibility: bool,
    progress: Progress,
) -> Result<Image, CullError> {
    let mut exits = ListedReach::default();
    shade_lists_into(tracer, input, lists, visibility, progress, None, &mut exits)
}

/// [`shade_lists`] written into `spare`, an image the caller is done with (a previous frame),
/// where it has the G-buffer's size: every pixel is written (0 where a pixel has no list or no
/// surface), so its old values do not matter and its buffer is neither allocated nor cleared
/// again. Any other `spare` is dropped and a new image made. The listed VPLs' exits are formed
/// in `exits`, a table the caller keeps from frame to frame ([`ListedReach::form`]); its old
/// entries do not matter either.
pub fn shade_lists_into(
    tracer: &Tracer,
    input: &CullInput,
    lists: &LightLists,
    visibility: bool,
    progress: Progress,
    spare: Option<Image>,
    exits: &mut ListedReach,
) -> Result<Image, CullError> {
    let (gbuffer, vpls) = (input.gbuffer, input.vpls);
    let (w, h, k) = (gbuffer.width, gbuffer.height, input.interleaving.k);
    let order = TileOrder::new(w, h, k)?;
    if gbuffer.samples.len() as u64 != u64::from(w) * u64::from(h) {
        return Err(CullError::Input(format!(
            "{} samples in a {w}x{h} G-buffer",
            gbuffer.samples.len()
        )));
    }
    lists.check(gbuffer.samples.len(), vpls.len())?;
    // Only the listed VPLs' exits are formed, in a compact table: the listed VPLs in
    // ascending order (`listed`), the lists' entries renumbered to their place in it (an
    // order-preserving map, so every pixel still sums its VPLs in its list's order); each
    // with its bounds only where its lists cover enough pixels to earn them back.
    let ListedVpls {
        listed,
        bounded,
        indices,
    } = ListedVpls::of(lists, vpls.len());
    exits.form(vpls, input.delta, &listed, |j| bounded[j])?;
    let shading = ListShading {
        tracer,
        gbuffer,
        lists,
        indices: &indices,
        listed: &listed,
        vpls,
        roulette: &exits.roulette,
        reach: &exits.reach,
        scale: input.interleaving.scale(),
        visibility,
    };
    let mut image = match spare {
        Some(image)
            if (image.width, image.height, image.pixels.len()) == (w, h, gbuffer.samples.len()) =>
        {
            image
        }
        _ => black_image(w, h),
    };
    order
        .bands(&mut image.pixels, 1)?
        .into_par_iter()
        .for_each_init(
            || (TileScratch::default(), Vec::new()),
            |(scratch, out), band| {
                let Band { tiles, mut rows } = band;
                for tile in tiles {
                    if progress.cancelled() {
                        return;
                    }
                    out.clear();
                    out.resize(tile.pixel_count(), Vec3::ZERO);
                    shading.tile(tile, k, out, scratch);
                    rows.put(tile, out);
                    progress.advance(out.len() as u64);
                }
            },
        );
    Ok(image)
}

/// What [`shade_lists`] shades every pixel with. The VPLs of `indices` (the lists' entries)
/// are places in `listed`, whose entries index `vpls`; `roulette` and `reach` are per place.
struct ListShading<'a> {
    tracer: &'a Tracer,
    gbuffer: &'a GBuffer,
    lists: &'a LightLists,
    indices: &'a [u32],
    listed: &'a [u32],
    vpls: &'a [Vpl],
    roulette: &'a [StochasticParams],
    reach: &'a [VplReach],
    scale: f32,
    visibility: bool,
}

/// Scratch reused from tile to tile: the tile's distinct lists (a pixel's own and shared
/// list as one [`key`]) and their ranks, the (rank of the list, slot, pixel) triples of its
/// pixels with a list, those grouped by list, where each group starts and the next free
/// place while grouping; for the lists shaded together, their VPLs (each with the lists that
/// hold it), their distinct shared lists with the sets that hold each, and per VPL a stamp
/// of those lists while merging; the receivers in lanes, the BRDF lanes of their chunks
/// (formed only for a chunk where a pair passes, which `formed` marks), their samples and
/// sets, sums and the chunks where one VPL passes.
#[derive(Default)]
struct TileScratch<'a> {
    lists: Vec<u64>,
    ranks: ListRanks,
    pixels: Vec<(u32, u32, u32)>,
    grouped: Vec<(u32, u32, u32)>,
    starts: Vec<usize>,
    next: Vec<usize>,
    members: Vec<(u32, u32)>,
    shared: Vec<(u32, u32)>,
    union: Vec<u32>,
    stamps: Vec<u32>,
    receivers: ReceiverChunks,
    brdfs: Vec<ReceiverBrdfs>,
    formed: Vec<bool>,
    samples: Vec<(u32, &'a GSample, u8)>,
    sums: Vec<Vec3>,
    passing: Vec<Passing>,
}

impl<'a> ListShading<'a> {
    /// Shades the pixels of `tile` into `out` (in the order of `Tile::pixels`, zero where a
    /// pixel has no list or sample): its pixels grouped by list, then up to [`MAX_SETS`]
    /// consecutive lists at a time ([`Self::lists_window`]).
    fn tile(&self, tile: &Tile, k: u32, out: &mut [Vec3], scratch: &mut TileScratch<'a>) {
        let width = self.gbuffer.width;
        // The tile's pixels with a list as (rank of the list among the tile's lists, slot,
        // pixel), then grouped by rank with a counting sort, each group in Z order (compact
        // chunks of eight receivers).
        scratch.lists.clear();
        scratch.ranks.start(tile.pixel_count());
        scratch.pixels.clear();
        // Neighbours in Z order mostly share a list: the last one found is tried first.
        let mut last = (NO_KEY, 0);
        let shared = &self.lists.shared_list;
        for (slot, [x, y]) in tile.pixels_z_order(k) {
            let p = y * width + x;
            // Read below, once the tile's pixels are grouped.
            prefetch(&self.gbuffer.samples[p as usize]);
            let own = self.lists.pixel_list[p as usize];
            let l = key(own, shared.get(p as usize).copied().unwrap_or(NO_LIST));
            if l == NO_KEY {
                continue;
            }
            if l != last.0 {
                last = (l, scratch.ranks.rank(l, &mut scratch.lists));
            }
            scratch.pixels.push((last.1, slot as u32, p));
        }
        let ranks = scratch.lists.len();
        scratch.starts.clear();
        scratch.starts.resize(ranks + 1, 0);
        for &(rank, _, _) in &scratch.pixels {
            scratch.starts[rank as usize + 1] += 1;
        }
        for r in 0..ranks {
            scratch.starts[r + 1] += scratch.starts[r];
        }
        let mut grouped = core::mem::take(&mut scratch.grouped);
        grouped.clear();
        grouped.resize(scratch.pixels.len(), (0, 0, 0));
        scratch.next.clear();
        scratch.next.extend_from_slice(&scratch.starts[..ranks]);
        for &pixel in &scratch.pixels {
            let at = &mut scratch.next[pixel.0 as usize];
            grouped[*at] = pixel;
            *at += 1;
        }
        let lists = core::mem::take(&mut scratch.lists);
        // A list shares its window only when it has few pixels and is strictly ascending
        // (the union of such lists in ascending order is each one's own order; beside
        // shared lists every list is).
        let starts = core::mem::take(&mut scratch.starts);
        let shares = |r: usize| {
            let [own, shared] = key_lists(lists[r]);
            starts[r + 1] - starts[r] < SHARED_WINDOW_PIXELS
                && (shared != NO_LIST || self.list(own).windows(2).all(|w| w[0] < w[1]))
        };
        let mut first = 0;
        while first < ranks {
            let mut end = first + 1;
            if shares(first) {
                while end < ranks && end - first < MAX_SETS && shares(end) {
                    end += 1;
                }
            }
            let run = &grouped[starts[first]..starts[end]];
            self.lists_window(&lists[first..end], first as u32, run, out, scratch);
            first = end;
        }
        scratch.grouped = grouped;
        scratch.lists = lists;
        scratch.starts = starts;
    }

    /// The entries of list `l`: places in `listed` (none for `NO_LIST`).
    #[inline]
    fn list(&self, l: u32) -> &'a [u32] {
        if l == NO_LIST {
            return &[];
        }
        let l = l as usize;
        &self.indices[self.lists.offsets[l] as usize..self.lists.offsets[l + 1] as usize]
    }

    /// Shades the pixels `run` (rank, slot, pixel) whose lists are `lists` (ranks `first..`,
    /// at most [`MAX_SETS`], strictly ascending unless there is one), VPL by VPL in ascending
    /// order (one list alone: in its order), each VPL tested against eight of the pixels at a
    /// time, only those of the lists that hold it ([`ReceiverChunks::passing_sets`]). Where
    /// the lanes accepted a pair with the shader's own operations, their ωo, l² and I(ωo) are
    /// used as they are, with the receivers' BRDF formed eight at a time where the lanes model
    /// it ([`received_lanes`]), else by [`received`]. Every pixel sums its VPLs in its list's
    /// order, so its estimate is the same bit for bit as summing its list one VPL at a time.
    fn lists_window(
        &self,
        lists: &[u64],
        first: u32,
        run: &[(u32, u32, u32)],
        out: &mut [Vec3],
        scratch: &mut TileScratch<'a>,
    ) {
        self.members(lists, scratch);
        // Each VPL's exits are read after the receivers are gathered.
        for &(v, _) in &scratch.members {
            prefetch(&self.reach[v as usize]);
        }
        let samples = &mut scratch.samples;
        samples.clear();
        samples.extend(run.iter().filter_map(|&(rank, slot, p)| {
            let set = (rank - first) as u8;
            self.gbuffer.samples[p as usize]
                .as_ref()
                .map(|g| (slot, g, set))
        }));
        scratch.receivers.refill_sets(
            samples
                .iter()
                .map(|(_, g, set)| (g.position, g.normal, *set)),
        );
        scratch.sums.clear();
        scratch.sums.resize(samples.len(), Vec3::ZERO);
        scratch
            .receivers
            .passing_sets(self.reach, &scratch.members, true, &mut scratch.passing);
        // The receivers' BRDF lanes are formed for the chunks where a pair passes only.
        let chunks = samples.len().div_ceil(8);
        if scratch.brdfs.len() < chunks {
            scratch.brdfs.resize(chunks, ReceiverBrdfs::of_chunk([]));
        }
        scratch.formed.clear();
        scratch.formed.resize(chunks, false);
        let mut values = [F8([0.0; 8]); 3];
        for chunk in &scratch.passing {
            let k = chunk.vpl as usize;
            let (vpl, params) = (&self.vpls[self.listed[k] as usize], &self.roulette[k]);
            if !scratch.formed[chunk.chunk] {
                let receivers = samples[chunk.chunk * 8..].iter().take(8).map(|s| s.1);
                scratch.brdfs[chunk.chunk] = ReceiverBrdfs::of_chunk(receivers);
                scratch.formed[chunk.chunk] = true;
            }
            let formed = received_lanes(&scratch.brdfs[chunk.chunk], chunk, params, &mut values);
            let mut bits = chunk.bits;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let i = chunk.chunk * 8 + lane;
                let g = samples[i].1;
                let c = if formed & (1 << lane) != 0 {
                    Vec3::new(values[0].0[lane], values[1].0[lane], values[2].0[lane])
                } else {
                    match chunk.exact(lane) {
                        // The lanes' own ωo, l² and I(ωo) are the shader's, bit for bit.
                        Some((omega, l2, intensity)) => {
                            received(g, omega, l2, || intensity, Some(params))
                        }
                        None => vpl_contribution(g, vpl, Some(params)),
                    }
                };
                if let Some(v) = self.visible(g, vpl, c) {
                    scratch.sums[i] += v;
                }
            }
        }
        for (&(slot, _, _), &sum) in samples.iter().zip(&scratch.sums) {
            out[slot as usize] = sum;
        }
    }

    /// Fills `scratch.members` with the VPLs of `lists` (each a [`key`]) and, per VPL, the
    /// lists that hold it (bit s: `lists[s]`, its own list or its shared one): one list
    /// without a shared one as it is, otherwise merged in ascending order, each VPL once. A
    /// shared list held by several sets is stamped once, with all of them.
    fn members(&self, lists: &[u64], scratch: &mut TileScratch<'a>) {
        scratch.members.clear();
        if let [l] = *lists {
            if let [own, NO_LIST] = key_lists(l) {
                scratch
                    .members
                    .extend(self.list(own).iter().map(|&v| (v, 1)));
                return;
            }
        }
        scratch.stamps.resize(self.listed.len(), 0);
        scratch.union.clear();
        scratch.shared.clear();
        let stamp = |v: u32, sets: u32, scratch: &mut TileScratch<'a>| {
            let stamp = &mut scratch.stamps[v as usize];
            if *stamp == 0 {
                scratch.union.push(v);
            }
            *stamp |= sets;
        };
        for (s, &l) in lists.iter().enumerate() {
            let [own, shared] = key_lists(l);
            for &v in self.list(own) {
                stamp(v, 1 << s, scratch);
            }
            if shared != NO_LIST {
                match scratch.shared.iter_mut().find(|(l, _)| *l == shared) {
                    Some((_, sets)) => *sets |= 1 << s,
                    None => scratch.shared.push((shared, 1 << s)),
                }
            }
        }
        for i in 0..scratch.shared.len() {
            let (shared, sets) = scratch.shared[i];
            for &v in self.list(shared) {
                stamp(v, sets, scratch);
            }
        }
        scratch.union.sort_unstable();
        let stamps = &mut scratch.stamps;
        scratch.members.extend(
            scratch
                .union
                .iter()
                .map(|&v| (v, core::mem::take(&mut stamps[v as usize]))),
        );
    }

    /// The contribution `c` of `vpl` at `g` times K², `None` where it is 0 or, with
    /// visibility, occluded.
    #[inline]
    fn visible(&self, g: &GSample, vpl: &Vpl, c: Vec3) -> Option<Vec3> {
        let visible = c != Vec3::ZERO
            && (!self.visibility
                || self.tracer.unoccluded(
                    self.tracer.lift(g.position, g.geometric_normal),
                    self.tracer.lift(vpl.position, vpl.geometric_normal),
                ));
        visible.then(|| c * self.scale)
    }
}

/// A pixel's own list and its shared list ([`LightLists::shared_list`]) as one key: the
/// pixels of a tile are grouped by both.
#[inline]
fn key(own: u32, shared: u32) -> u64 {
    u64::from(own) << 32 | u64::from(shared)
}

/// The key of a pixel with neither list.
const NO_KEY: u64 = u64::MAX;

/// The own and shared list of a [`key`].
#[inline]
fn key_lists(key: u64) -> [u32; 2] {
    [(key >> 32) as u32, key as u32]
}

/// A list of a tile with fewer pixels than this shares its chunks of receivers with the
/// tile's other such lists (up to [`MAX_SETS`]), so that short lists (the depth slices of
/// clustered shading) still test eight receivers at a time; a longer list fills its own
/// chunks and is tested against its own receivers' box.
pub const SHARED_WINDOW_PIXELS: usize = 32;
