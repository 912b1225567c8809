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
use glam::DVec3;
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
        let rotation = view.rotation().as_dmat3();
        let bound_of = |v: &Vpl| -> Result<(BoxBound, DVec3), CullError> {
            let params = StochasticParams::new(delta, v.xi)?;
            let bound = lobe_box_bound(v, &params)?.rotated(rotation);
            Ok((bound, view.to_view(v.position)))
        };
        memory.bounds.clear();
        if let Some(first) = vpls.first() {
            let placeholder = bound_of(first)?;
            crate::par::try_map_into(vpls, placeholder, |_, v| bound_of(v), &mut memory.bounds)?;
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
