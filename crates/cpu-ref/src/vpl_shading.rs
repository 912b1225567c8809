//! Shading with every VPL (no culling): the exact VPL sum, or the stochastic estimate of
//! paper eq. (3) where each VPL is kept at a pixel only if p(ωo, l) > ξ.
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::stochastic::{scalar_intensity, StochasticParams};
use slc_bounds::BoundsError;
use slc_core::{CullError, CullInput, GBuffer, GSample, Image, LightLists, Vpl, NO_LIST};
use slc_cull::receiver_chunks::Passing;
use slc_cull::tiles::{Tile, TileOrder};
use slc_cull::{ReceiverChunks, VplReach};

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
/// is tested with a shadow ray. `progress` is called with the number of pixels finished.
/// Fails only when δ or a VPL's ξ is out of its domain.
pub fn shade_vpls(
    tracer: &Tracer,
    gbuffer: &GBuffer,
    vpls: &[Vpl],
    estimator: VplEstimator,
    visibility: bool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Image, BoundsError> {
    let roulette = match estimator {
        VplEstimator::Exact => None,
        VplEstimator::Stochastic { delta } => Some(
            vpls.iter()
                .map(|v| StochasticParams::new(delta, v.xi))
                .collect::<Result<Vec<_>, _>>()?,
        ),
    };
    let mut image = Image::new(gbuffer.width, gbuffer.height);
    let w = gbuffer.width as usize;
    image
        .pixels
        .par_chunks_mut(w)
        .zip(gbuffer.samples.par_chunks(w))
        .for_each(|(out, row)| {
            for (o, g) in out.iter_mut().zip(row) {
                let Some(g) = g else { continue };
                let from = tracer.lift(g.position, g.geometric_normal);
                for (k, vpl) in vpls.iter().enumerate() {
                    let c = vpl_contribution(g, vpl, roulette.as_ref().map(|r| &r[k]));
                    if c != Vec3::ZERO
                        && (!visibility
                            || tracer
                                .unoccluded(from, tracer.lift(vpl.position, vpl.geometric_normal)))
                    {
                        *o += c;
                    }
                }
            }
            progress(w as u64);
        });
    Ok(image)
}

/// Indirect radiance from culled light lists (paper eq. 3 with interleaved sampling): each
/// pixel sums the VPLs of its list with weight K²/p when p > ξ. Unbiased as long as the lists
/// miss no VPL with p > ξ at the pixel. Fails when δ, a ξ, K or a VPL is out of the domain
/// of slc-bounds and slc-cull, or when the lists, the G-buffer and its size disagree (or the
/// image has 2³² pixels or more). Pairs that [`VplReach`] rejects (outside the VPL's own
/// bound, facing away at either end, or not accepted by the roulette) are skipped before the
/// receiver's BRDF: their contribution is exactly 0, so the image is the same bit for bit.
/// The pixels are shaded tile by tile in the deinterleaved order of [`TileOrder`] (the
/// culling's tiles), each tile's pixels grouped by list. The pixels of a list are shaded VPL
/// by VPL, each VPL tested against eight of them at a time ([`ReceiverChunks`]), and where
/// those lanes accepted a pair with the shader's own operations their ωo, l² and I(ωo) are
/// used as they are ([`received`]); a list of a single pixel is shaded with the scalar tests.
/// Every pixel sums its VPLs in the list's order either way.
pub fn shade_lists(
    tracer: &Tracer,
    input: &CullInput,
    lists: &LightLists,
    visibility: bool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Image, CullError> {
    let (gbuffer, vpls) = (input.gbuffer, input.vpls);
    let (w, h, k) = (gbuffer.width, gbuffer.height, input.interleaving.k);
    let order = TileOrder::new(w, h, k)?;
    if lists.pixel_list.len() != gbuffer.samples.len()
        || gbuffer.samples.len() as u64 != u64::from(w) * u64::from(h)
    {
        return Err(CullError::Input(format!(
            "{} list entries for a {w}x{h} G-buffer of {} samples",
            lists.pixel_list.len(),
            gbuffer.samples.len()
        )));
    }
    let roulette = vpls
        .iter()
        .map(|v| StochasticParams::new(input.delta, v.xi))
        .collect::<Result<Vec<_>, _>>()?;
    let reach = vpls
        .par_iter()
        .zip(&roulette)
        .map(|(v, r)| VplReach::new(v, r))
        .collect::<Result<Vec<_>, _>>()?;
    let shading = ListShading {
        tracer,
        gbuffer,
        lists,
        vpls,
        roulette: &roulette,
        reach: &reach,
        scale: input.interleaving.scale(),
        visibility,
    };
    // One slot per pixel in tile order, cut into each tile's run.
    let mut shaded = vec![Vec3::ZERO; gbuffer.samples.len()];
    let mut runs = Vec::with_capacity(order.tiles().len());
    let mut rest = shaded.as_mut_slice();
    for len in order.run_lengths() {
        let (mine, tail) = rest.split_at_mut(len);
        runs.push(mine);
        rest = tail;
    }
    order.tiles().par_iter().zip(runs).for_each_init(
        TileScratch::default,
        |scratch, (tile, out)| {
            shading.tile(tile, k, out, scratch);
            progress(out.len() as u64);
        },
    );
    let mut image = Image::new(w, h);
    image
        .pixels
        .par_chunks_mut(w.max(1) as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, o) in row.iter_mut().enumerate() {
                *o = shaded[order.slot(x as u32, y as u32)];
            }
        });
    Ok(image)
}

/// What [`shade_lists`] shades every pixel with.
struct ListShading<'a> {
    tracer: &'a Tracer,
    gbuffer: &'a GBuffer,
    lists: &'a LightLists,
    vpls: &'a [Vpl],
    roulette: &'a [StochasticParams],
    reach: &'a [VplReach],
    scale: f32,
    visibility: bool,
}

/// Scratch reused from tile to tile: the tile's distinct lists, the (rank of the list, slot,
/// pixel) triples of its pixels with a list, those grouped by list, where each group starts
/// and the next free place while grouping, and the receivers of a list shaded VPL by VPL
/// (pixels in lanes) with their samples, sums and the chunks where one VPL passes.
#[derive(Default)]
struct TileScratch<'a> {
    lists: Vec<u32>,
    pixels: Vec<(u32, u32, u32)>,
    grouped: Vec<(u32, u32, u32)>,
    starts: Vec<usize>,
    next: Vec<usize>,
    receivers: ReceiverChunks,
    samples: Vec<(u32, &'a GSample)>,
    sums: Vec<Vec3>,
    passing: Vec<Passing>,
}

impl<'a> ListShading<'a> {
    /// Shades the pixels of `tile` into `out` (its run in tile order), list by list.
    fn tile(&self, tile: &Tile, k: u32, out: &mut [Vec3], scratch: &mut TileScratch<'a>) {
        let width = self.gbuffer.width;
        // The tile's pixels with a list as (rank of the list among the tile's lists, slot,
        // pixel), then grouped by rank with a counting sort, each group in slot order.
        scratch.lists.clear();
        scratch.pixels.clear();
        for (slot, [x, y]) in tile.pixels(k).enumerate() {
            let p = y * width + x;
            let l = self.lists.pixel_list[p as usize];
            if l == NO_LIST {
                continue;
            }
            let rank = match scratch.lists.iter().rposition(|&m| m == l) {
                Some(rank) => rank,
                None => {
                    scratch.lists.push(l);
                    scratch.lists.len() - 1
                }
            };
            scratch.pixels.push((rank as u32, slot as u32, p));
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
        for (r, &l) in lists.iter().enumerate() {
            let run = &grouped[scratch.starts[r]..scratch.starts[r + 1]];
            let l = l as usize;
            let list = &self.lists.indices
                [self.lists.offsets[l] as usize..self.lists.offsets[l + 1] as usize];
            if run.len() >= RECEIVER_LANES_MIN_PIXELS {
                self.run_by_vpl(list, run, out, scratch);
                continue;
            }
            for &(_, slot, p) in run {
                if let Some(g) = &self.gbuffer.samples[p as usize] {
                    out[slot as usize] = self.pixel(g, list);
                }
            }
        }
        scratch.grouped = grouped;
        scratch.lists = lists;
    }

    /// Shades the pixels `run` (rank, slot, pixel) that share `list`, VPL by VPL in the list's
    /// order, each VPL tested against eight of the pixels at a time ([`ReceiverChunks`]).
    /// Every pixel still sums its VPLs in the list's order, so its estimate is the same bit
    /// for bit as [`Self::pixel`]'s.
    fn run_by_vpl(
        &self,
        list: &[u32],
        run: &[(u32, u32, u32)],
        out: &mut [Vec3],
        scratch: &mut TileScratch<'a>,
    ) {
        let samples = &mut scratch.samples;
        samples.clear();
        samples.extend(run.iter().filter_map(|&(_, slot, p)| {
            self.gbuffer.samples[p as usize].as_ref().map(|g| (slot, g))
        }));
        scratch
            .receivers
            .refill(samples.iter().map(|(_, g)| (g.position, g.normal)));
        scratch.sums.clear();
        scratch.sums.resize(samples.len(), Vec3::ZERO);
        scratch
            .receivers
            .passing(self.reach, list, true, &mut scratch.passing);
        for chunk in &scratch.passing {
            let k = chunk.vpl as usize;
            let (vpl, roulette) = (&self.vpls[k], Some(&self.roulette[k]));
            let mut bits = chunk.bits;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let i = chunk.chunk * 8 + lane;
                let g = samples[i].1;
                let c = match chunk.exact(lane) {
                    // The lanes' own ωo, l² and I(ωo) are the shader's, bit for bit.
                    Some((omega, l2, intensity)) => received(g, omega, l2, || intensity, roulette),
                    None => vpl_contribution(g, vpl, roulette),
                };
                if let Some(v) = self.visible(g, vpl, c) {
                    scratch.sums[i] += v;
                }
            }
        }
        for (&(slot, _), &sum) in samples.iter().zip(&scratch.sums) {
            out[slot as usize] = sum;
        }
    }

    /// The weighted contribution of VPL `k` at `g` (eq. 3 with the interleaving's K²), `None`
    /// where it is 0 or, with visibility, occluded.
    #[inline]
    fn contribution(&self, g: &GSample, k: u32) -> Option<Vec3> {
        let vpl = &self.vpls[k as usize];
        let c = vpl_contribution(g, vpl, Some(&self.roulette[k as usize]));
        self.visible(g, vpl, c)
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

    /// The estimate at `g` from the VPLs of `list` that pass the scalar bound and sign tests
    /// ([`VplReach::may_reach`]; `vpl_contribution` forms the roulette itself), in the list's
    /// order.
    fn pixel(&self, g: &GSample, list: &[u32]) -> Vec3 {
        let mut o = Vec3::ZERO;
        for &k in list {
            let d = g.position - self.vpls[k as usize].position;
            if self.reach[k as usize].may_reach(d, g.normal) {
                if let Some(v) = self.contribution(g, k) {
                    o += v;
                }
            }
        }
        o
    }
}

/// When a list shades at least this many pixels of a tile, they are shaded VPL by VPL with the
/// pixels in lanes ([`ReceiverChunks`]); a single pixel is shaded with the scalar tests.
pub const RECEIVER_LANES_MIN_PIXELS: usize = 2;
