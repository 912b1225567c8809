//! The refinement of the `tight` strategies: after a tile's clusters are culled with the
//! spheroid (glossy VPLs) or section-6 sphere (diffuse ones), each cluster's list is cut per
//! block of [`BLOCK`]² pixels of the tile (in the tiled layout, each block's samples split
//! once more at their own half depth, Modified HalfZ per block), keeping a VPL only where
//! `slc_bounds::BoxBound` says p(ωo, l) of eq. (2) may exceed ξ somewhere in the box of the
//! group's receivers (docs/tight-bounds.md). 8×8 blocks measured best on Sponza: 4×4 ones
//! list fewer false positives but cost more culling than they save in shading.
use crate::depth::Sample;
use crate::frusta::Box3;
use crate::lists::ListChunk;
use crate::view::CullView;
use crate::vpl_bounds::{lobe_box_bound, SubregionBounds, ViewEllipsoid};
use crate::vpl_lanes::box_bounds;
use glam::DVec3;
use rayon::prelude::*;
use slc_bounds::{BoxBound, ReceiverBox, StochasticParams};
use slc_core::{CullError, Vpl, TILE_SIZE};

/// The side of a refinement block, in pixels of the subregion image.
pub(crate) const BLOCK: u32 = 8;

/// Blocks per tile row.
const BLOCKS_PER_ROW: u32 = TILE_SIZE / BLOCK;

/// Blocks per tile.
/// How many hits ahead [`Refiner::ahead`] asks for a record (4, 8 and 16 measured alike:
/// `tight`'s culling on Sponza at RSM 1024, 383-390 ms each).
const PREFETCH_AHEAD: usize = 8;

pub(crate) const BLOCKS: usize = (BLOCKS_PER_ROW * BLOCKS_PER_ROW) as usize;

/// Where a sample sits: its view-space position, the largest |coordinate| of its world
/// position, and its refinement block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Place {
    pub view: DVec3,
    pub extent: f32,
    pub block: u8,
}

/// Every VPL's [`BoxBound`] in the culling view with its view-space position, the
/// spheroids of the glossy ones (by VPL index), and the largest |coordinate| of the VPLs'
/// world positions.
pub(crate) struct Refiner<'a> {
    bounds: &'a [(BoxBound, DVec3)],
    spheroids: &'a [Option<ViewEllipsoid>],
    vpl_extent: f32,
    /// Whether each block's samples are split at their half depth.
    split_blocks: bool,
}

/// The memory of a [`Refiner`], kept from frame to frame with the culling's
/// ([`crate::BoundedMemory`]): at a million VPLs about 250 MB.
#[derive(Default)]
pub(crate) struct RefinerMemory {
    bounds: Vec<(BoxBound, DVec3)>,
    spheroids: Vec<Option<ViewEllipsoid>>,
}

impl RefinerMemory {
    /// The VPLs it has room for.
    pub(crate) fn capacity(&self) -> usize {
        self.bounds.capacity()
    }
}

/// The [`BoxBound`]s of `eight` (one to eight VPLs) for δ = `delta`, rotated into `view`,
/// with their view-space positions, into `out`: formed in lanes where
/// [`box_bounds`] takes a VPL, by slc-bounds one at a time for the others. Errors on a VPL
/// whose roulette (checked first, for all of them) or lobe is out of slc-bounds' domain.
fn view_bounds(
    eight: &[Vpl],
    delta: f32,
    view: &CullView,
    out: &mut [(BoxBound, DVec3)],
) -> Result<(), CullError> {
    let rotation = view.rotation().as_dmat3();
    let mut params = [StochasticParams::new(delta, eight[0].xi)?; 8];
    for (p, v) in params.iter_mut().zip(eight).skip(1) {
        *p = StochasticParams::new(delta, v.xi)?;
    }
    let refs: [&Vpl; 8] = core::array::from_fn(|k| &eight[k.min(eight.len() - 1)]);
    let (refs, params) = (&refs[..eight.len()], &params[..eight.len()]);
    let boxed = box_bounds(refs, params, u8::MAX, |k, bound| {
        out[k].0 = bound.rotated(rotation);
    });
    for (k, ((v, params), out)) in refs.iter().zip(params).zip(out).enumerate() {
        if boxed >> k & 1 == 0 {
            out.0 = lobe_box_bound(v, params)?.rotated(rotation);
        }
        out.1 = view.to_view(v.position);
    }
    Ok(())
}

impl<'a> Refiner<'a> {
    /// The bounds of `vpls` for δ = `delta` in `view`, with the spheroids of `culled` (the
    /// tile culling's bounds), formed in `memory` (its old contents do not matter);
    /// `split_blocks` splits each block's samples at their half depth.
    pub(crate) fn new(
        vpls: &[Vpl],
        culled: &[SubregionBounds],
        delta: f32,
        view: &CullView,
        split_blocks: bool,
        memory: &'a mut RefinerMemory,
    ) -> Result<Self, CullError> {
        match vpls.first() {
            None => memory.bounds.clear(),
            Some(first) => {
                // Eight VPLs at a time (the plain glossy ones' bounds share lanes), in the
                // memory's last contents (the placeholder fills only slots it lacked).
                let params = StochasticParams::new(delta, first.xi)?;
                let placeholder = (lobe_box_bound(first, &params)?, DVec3::ZERO);
                memory.bounds.resize(vpls.len(), placeholder);
                memory
                    .bounds
                    .par_chunks_mut(8)
                    .zip(vpls.par_chunks(8))
                    .try_for_each(|(out, eight)| view_bounds(eight, delta, view, out))?;
            }
        }
        let vpl_extent = vpls
            .iter()
            .map(|v| v.position.abs().max_element())
            .fold(0.0, f32::max);
        memory.spheroids.clear();
        memory.spheroids.resize(vpls.len(), None);
        for e in culled.iter().flat_map(|s| &s.ellipsoids) {
            memory.spheroids[e.index as usize] = Some(*e);
        }
        Ok(Self {
            bounds: &memory.bounds,
            spheroids: &memory.spheroids,
            vpl_extent,
            split_blocks,
        })
    }

    /// Cuts the lists `spheres` and `ellipsoids` of one cluster's `samples` (ordered by
    /// block) per block, or per half of a block (its samples are reordered, near half
    /// first): each gets the merge of the VPLs whose [`BoxBound`] reaches the box of its
    /// receivers. Pushes the lists to `chunk` and the samples' (pixel, list).
    pub(crate) fn cut(
        &self,
        samples: &mut [(Sample, Place)],
        spheres: &[u32],
        ellipsoids: &[u32],
        scratch: &mut Scratch,
        chunk: &mut ListChunk,
    ) {
        let mut rest = samples;
        while let Some(first) = rest.first() {
            let block = first.1.block;
            let run = rest.iter().take_while(|s| s.1.block == block).count();
            let (block_samples, tail) = std::mem::take(&mut rest).split_at_mut(run);
            rest = tail;
            let near = if self.split_blocks {
                split_at_half_depth(block_samples)
            } else {
                0
            };
            for group in [&block_samples[..near], &block_samples[near..]] {
                if group.is_empty() {
                    continue;
                }
                let (lo, hi) = self.receivers(group);
                let receivers = ReceiverBox::new(lo, hi);
                // A sphere's own test is the box bound's first (the peak intensity against the
                // distance); a spheroid's is tested against the box first, being cheaper.
                let (center, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
                let reaches = |i: u32| self.reaches(i, &receivers);
                scratch.spheres.clear();
                scratch
                    .spheres
                    .extend(self.ahead(spheres, false).filter(|&i| reaches(i)));
                scratch.ellipsoids.clear();
                scratch
                    .ellipsoids
                    .extend(self.ahead(ellipsoids, true).filter(|&i| {
                        self.spheroids[i as usize].is_none_or(|e| spheroid_meets(&e, center, half))
                            && reaches(i)
                    }));
                let list = chunk.push_merged(&scratch.spheres, &scratch.ellipsoids);
                chunk.pixels.extend(group.iter().map(|s| (s.0.pixel, list)));
            }
        }
    }

    /// The box of `samples`' view positions, grown to contain the offsets x − q the shader
    /// forms in f32 from world positions: rounding at most ε max|coordinate| per axis, and
    /// the f64 view rotation's departure from a rotation (about 1e-7 |x − q|), with
    /// |x − q| <= 2 max|coordinate|: 8 ε max|coordinate| over these samples and every VPL.
    fn receivers(&self, samples: &[(Sample, Place)]) -> (DVec3, DVec3) {
        let (lo, hi, extent) = samples.iter().fold(
            (
                DVec3::splat(f64::INFINITY),
                DVec3::splat(f64::NEG_INFINITY),
                self.vpl_extent,
            ),
            |(lo, hi, e), (_, p)| (lo.min(p.view), hi.max(p.view), e.max(p.extent)),
        );
        let pad = 8.0 * f64::from(f32::EPSILON) * f64::from(extent);
        (lo - pad, hi + pad)
    }

    /// The VPLs `hits`, each with the records of the VPL [`PREFETCH_AHEAD`] places on asked
    /// for (its bound over boxes, and its spheroid where `spheroids`): the hits lie scattered
    /// over tables of some 150 MB at a million VPLs.
    fn ahead<'h>(&'h self, hits: &'h [u32], spheroids: bool) -> impl Iterator<Item = u32> + 'h {
        hits.iter().enumerate().map(move |(k, &i)| {
            if let Some(&next) = hits.get(k + PREFETCH_AHEAD) {
                crate::prefetch::prefetch(&self.bounds[next as usize]);
                if spheroids {
                    crate::prefetch::prefetch(&self.spheroids[next as usize]);
                }
            }
            i
        })
    }

    /// Whether VPL `i`'s box bound reaches `receivers`.
    #[inline]
    fn reaches(&self, i: u32, receivers: &ReceiverBox) -> bool {
        let (bound, q) = &self.bounds[i as usize];
        bound.may_exceed_xi(receivers, *q)
    }
}

/// Whether the spheroid `e` (the unit ball around BS·c in its test space, eq. 16-17) meets
/// the box `center ± half`.
#[inline]
fn spheroid_meets(e: &ViewEllipsoid, center: DVec3, half: DVec3) -> bool {
    Box3::in_test_space(e, center, half).meets_ball(e.center, 1.0)
}

/// Moves the samples nearer than the middle of their depth range to the front (Modified
/// HalfZ) and returns how many there are.
fn split_at_half_depth(samples: &mut [(Sample, Place)]) -> usize {
    let (lo, hi) = samples
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s.0.z), hi.max(s.0.z))
        });
    let half_z = 0.5 * (lo + hi);
    let mut near = 0;
    for i in 0..samples.len() {
        if samples[i].0.z < half_z {
            samples.swap(i, near);
            near += 1;
        }
    }
    near
}

/// The block of the tile pixel at column `a`, row `b` of the tile.
#[inline]
pub(crate) fn block_of(a: u32, b: u32) -> u8 {
    ((b / BLOCK) * BLOCKS_PER_ROW + a / BLOCK) as u8
}

/// Lists reused from block to block.
#[derive(Default)]
pub(crate) struct Scratch {
    spheres: Vec<u32>,
    ellipsoids: Vec<u32>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{random_vpl, Rng};
    use glam::Vec3;
    use slc_core::Camera;

    /// Eight at a time, every VPL's bound is slc-bounds' own rotated into the view, bit for
    /// bit, whichever formed it (the lanes or slc-bounds one at a time: diffuse VPLs, a tilted
    /// normal).
    #[test]
    fn view_bounds_are_slc_bounds_rotated() {
        let mut rng = Rng(0x7E57_B0C5);
        let camera = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 1.0).unwrap();
        let view = CullView::new(&camera, 64, 48).unwrap();
        let rotation = view.rotation().as_dmat3();
        for case in 0..500u32 {
            let n = 1 + case as usize % 8;
            let vpls: Vec<Vpl> = (0..n)
                .map(|k| {
                    let mut v = random_vpl(&mut rng, 8 * case + k as u32);
                    if rng.f32() < 0.2 {
                        v.geometric_normal =
                            (v.normal + 0.01 * v.normal.any_orthonormal_vector()).normalize();
                    }
                    v
                })
                .collect();
            let delta = 10f32.powf(rng.range(-9.0, 3.0));
            let first = StochasticParams::new(delta, vpls[0].xi).unwrap();
            let placeholder = (lobe_box_bound(&vpls[0], &first).unwrap(), DVec3::NAN);
            let mut out = vec![placeholder; n];
            view_bounds(&vpls, delta, &view, &mut out).unwrap();
            for (v, got) in vpls.iter().zip(&out) {
                let params = StochasticParams::new(delta, v.xi).unwrap();
                let bound = lobe_box_bound(v, &params).unwrap().rotated(rotation);
                let expected = (bound, view.to_view(v.position));
                assert_eq!(format!("{got:?}"), format!("{expected:?}"), "case {case}");
            }
        }
    }
}
