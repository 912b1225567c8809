//! Shading with every VPL (no culling): the exact VPL sum, or the stochastic estimate of
//! paper eq. (3) where each VPL is kept at a pixel only if p(ωo, l) > ξ.
use crate::tracer::Tracer;
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::stochastic::{scalar_intensity, StochasticParams};
use slc_bounds::BoundsError;
use slc_core::{CullError, CullInput, GBuffer, GSample, Image, LightLists, Vpl, NO_LIST};
use slc_cull::{ReachChunks, VplReach};

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
    let cos_x = -g.normal.dot(omega);
    if cos_x <= 0.0 {
        return Vec3::ZERO;
    }
    let intensity = vpl.intensity(omega);
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
                            || tracer.unoccluded(from, tracer.lift(vpl.position, vpl.normal)))
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
/// miss no VPL with p > ξ at the pixel. Fails only when δ, a ξ or a VPL is out of the domain
/// of slc-bounds. Pairs that [`VplReach`] rejects (outside the VPL's own bound, facing away
/// at either end; tested eight per list at a time by [`ReachChunks`]) are skipped before the
/// BRDFs: their contribution is exactly 0, so the image is the same bit for bit. The pixels
/// are shaded list by list, each list's VPLs packed once into chunks of eight, or in image
/// order when the lists are too short-lived for packing to pay (fewer than 4 pixels a list).
pub fn shade_lists(
    tracer: &Tracer,
    input: &CullInput,
    lists: &LightLists,
    visibility: bool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Image, CullError> {
    let (gbuffer, vpls) = (input.gbuffer, input.vpls);
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
        vpls,
        roulette: &roulette,
        reach: &reach,
        scale: input.interleaving.scale(),
        visibility,
    };
    let pixels = pixels_by_list(lists);
    Ok(if pixels.indices.len() >= PACK_MIN_PIXELS * lists.len() {
        shading.by_list(gbuffer, lists, &pixels, progress)
    } else {
        shading.by_row(gbuffer, lists, progress)
    })
}

/// What [`shade_lists`] shades every pixel with.
struct ListShading<'a> {
    tracer: &'a Tracer,
    vpls: &'a [Vpl],
    roulette: &'a [StochasticParams],
    reach: &'a [VplReach],
    scale: f32,
    visibility: bool,
}

impl ListShading<'_> {
    /// The estimate at `g` from the VPLs of `list` (packed in `chunks` when given) that pass
    /// the early exits, in the list's order.
    fn pixel(&self, g: &GSample, list: &[u32], chunks: Option<&ReachChunks>) -> Vec3 {
        let from = self.tracer.lift(g.position, g.geometric_normal);
        let mut o = Vec3::ZERO;
        let mut shade = |k: u32| {
            let vpl = &self.vpls[k as usize];
            let c = vpl_contribution(g, vpl, Some(&self.roulette[k as usize]));
            if c != Vec3::ZERO
                && (!self.visibility
                    || self
                        .tracer
                        .unoccluded(from, self.tracer.lift(vpl.position, vpl.normal)))
            {
                o += c * self.scale;
            }
        };
        match chunks {
            Some(chunks) => chunks.for_each_passing(0, g.position, Some(g.normal), &mut shade),
            None => {
                for &k in list {
                    let d = g.position - self.vpls[k as usize].position;
                    if self.reach[k as usize].may_contribute(d, g.normal) {
                        shade(k);
                    }
                }
            }
        }
        o
    }

    /// List by list, each list's VPLs packed into chunks of eight once for all its pixels.
    fn by_list(
        &self,
        gbuffer: &GBuffer,
        lists: &LightLists,
        pixels: &PixelsByList,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Image {
        // One slot per listed pixel, in list order, cut into each list's slots.
        let mut shaded = vec![Vec3::ZERO; pixels.indices.len()];
        let mut slots = Vec::with_capacity(lists.len());
        let mut rest = shaded.as_mut_slice();
        for w in pixels.offsets.windows(2) {
            let (mine, tail) = rest.split_at_mut((w[1] - w[0]) as usize);
            slots.push(mine);
            rest = tail;
        }
        slots.into_par_iter().enumerate().for_each_init(
            ReachChunks::default,
            |chunks, (l, out)| {
                let list = &lists.indices[lists.offsets[l] as usize..lists.offsets[l + 1] as usize];
                let mine =
                    &pixels.indices[pixels.offsets[l] as usize..pixels.offsets[l + 1] as usize];
                chunks.refill(self.vpls, self.reach, [list]);
                for (o, &p) in out.iter_mut().zip(mine) {
                    if let Some(g) = &gbuffer.samples[p as usize] {
                        *o = self.pixel(g, list, Some(chunks));
                    }
                }
                progress(mine.len() as u64);
            },
        );
        let mut image = Image::new(gbuffer.width, gbuffer.height);
        for (&p, o) in pixels.indices.iter().zip(shaded) {
            image.pixels[p as usize] = o;
        }
        progress(pixels.unlisted);
        image
    }

    /// Row by row in image order (sequential G-buffer reads), each pair tested on its own.
    fn by_row(
        &self,
        gbuffer: &GBuffer,
        lists: &LightLists,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Image {
        let mut image = Image::new(gbuffer.width, gbuffer.height);
        let w = gbuffer.width as usize;
        image
            .pixels
            .par_chunks_mut(w)
            .zip(gbuffer.samples.par_chunks(w))
            .enumerate()
            .for_each(|(y, (out, row))| {
                for (x, (o, g)) in out.iter_mut().zip(row).enumerate() {
                    if let Some(g) = g {
                        *o = self.pixel(g, lists.for_pixel(y * w + x), None);
                    }
                }
                progress(w as u64);
            });
        image
    }
}

/// When the lists shade fewer pixels than this on average, packing them into chunks of eight
/// costs more than it saves (and list order scatters the G-buffer reads): the pixels are then
/// shaded in image order with the scalar exits ([`VplReach`]), which pass the same pairs.
const PACK_MIN_PIXELS: usize = 4;

/// The pixels of each light list (a counting sort of `LightLists::pixel_list`), in the same
/// compressed rows as the lists, and the number of pixels without a list.
struct PixelsByList {
    offsets: Vec<u32>,
    indices: Vec<u32>,
    unlisted: u64,
}

fn pixels_by_list(lists: &LightLists) -> PixelsByList {
    let mut offsets = vec![0u32; lists.len() + 1];
    let mut unlisted = 0;
    for &l in &lists.pixel_list {
        match l {
            NO_LIST => unlisted += 1,
            l => offsets[l as usize + 1] += 1,
        }
    }
    for k in 1..offsets.len() {
        offsets[k] += offsets[k - 1];
    }
    let mut next = offsets.clone();
    let mut indices = vec![0u32; offsets[lists.len()] as usize];
    for (p, &l) in lists.pixel_list.iter().enumerate() {
        if l != NO_LIST {
            indices[next[l as usize] as usize] = p as u32;
            next[l as usize] += 1;
        }
    }
    PixelsByList {
        offsets,
        indices,
        unlisted,
    }
}
