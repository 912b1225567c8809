//! The culling loop every bound-based strategy shares: per tile of each interleaved
//! subregion, the depth clusters of its G-buffer samples, then every bound of the subregion's
//! VPLs tested against every cluster (after an f32 pre-test of eight bounds at a time against
//! the whole tile, `bound_lanes`, that never rejects a bound the exact test keeps); tiles run
//! in parallel.
use crate::bound_lanes::{for_each_candidate, TileLanes};
use crate::depth::{depth_range, DepthSplit, Sample, MAX_CLUSTERS};
use crate::frusta::TileFrusta;
use crate::lists::{assemble, pixel_count, ListChunk};
use crate::partition::Partition;
use crate::positions::positions;
use crate::prefetch::prefetch;
use crate::refine::{block_of, Place, Refiner, RefinerMemory, Scratch, BLOCKS};
use crate::tiles::{tiles, Tile};
use crate::view::CullView;
use crate::vpl_bounds::{subregion_bounds, GlossyBound, SubregionBounds, VplBound};
use glam::{DVec2, Vec3};
use rayon::prelude::*;
use slc_core::{CullError, CullInput, LightLists, NO_LIST};
use std::fmt;

/// How a tile is divided in depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Clustering {
    /// Two clusters per tile, Modified HalfZ (section 5.1).
    HalfZ,
    /// Up to 32 clusters per tile: exponential slices of the G-buffer's depth range.
    ExponentialSlices,
}

/// The memory a bound-testing strategy's culling fills every frame, kept by a caller from
/// frame to frame ([`BoundedCuller::cull_in`](crate::BoundedCuller::cull_in)): every VPL's
/// bound, the bounds grouped by subregion with their lanes, the G-buffer's positions and the
/// `tight` strategies' tables of bounds over boxes. At a million VPLs some 200 MB (450 MB for
/// `tight`), whose page faults took about a seventh of `ellipsoid`'s culling and a third of
/// `tight`'s when it was allocated afresh every frame.
#[derive(Default)]
pub struct BoundedMemory {
    every: Vec<VplBound>,
    subregions: Vec<SubregionBounds>,
    positions: Vec<Option<Vec3>>,
    /// The `tight` strategies' refinement.
    refiner: RefinerMemory,
}

/// How much it holds, not what.
impl fmt::Debug for BoundedMemory {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BoundedMemory")
            .field("bounds", &self.every.capacity())
            .field("subregions", &self.subregions.len())
            .field("positions", &self.positions.capacity())
            .field("refiner", &self.refiner.capacity())
            .finish()
    }
}

impl BoundedMemory {
    /// Drops what is much too large for `vpls` VPLs in `subregions` subregions and `pixels`
    /// pixels (`par::too_large_to_keep`).
    fn fit(&mut self, vpls: usize, subregions: usize, pixels: usize) {
        use crate::par::too_large_to_keep;
        if too_large_to_keep(self.every.capacity(), vpls)
            || too_large_to_keep(self.subregions.len(), subregions)
        {
            self.every = Vec::new();
            self.subregions = Vec::new();
        }
        if too_large_to_keep(self.refiner.capacity(), vpls) {
            self.refiner = RefinerMemory::default();
        }
        if too_large_to_keep(self.positions.capacity(), pixels) {
            self.positions = Vec::new();
        }
    }
}

/// What every tile reads.
struct TileInputs<'a> {
    width: u32,
    /// The G-buffer's positions, packed ([`positions`]).
    positions: &'a [Option<Vec3>],
    view: CullView,
    bounds: &'a [SubregionBounds],
    split: DepthSplit,
    k: u32,
    /// The `tight` strategies' per-block refinement.
    refiner: Option<Refiner<'a>>,
}

/// Culls `input` with `glossy` bounds for glossy VPLs (the section-6 sphere for diffuse ones)
/// and the given depth clustering. Each existing cluster gets one list (ascending VPL
/// indices, `NO_LIST` when empty); each pixel with a sample the list of its cluster. The
/// bounds and positions are formed in `memory` (its old contents do not matter).
pub(crate) fn cull(
    input: &CullInput,
    glossy: GlossyBound,
    clustering: Clustering,
    memory: &mut BoundedMemory,
) -> Result<LightLists, CullError> {
    let pixels = pixel_count(input.gbuffer)?;
    let partition = Partition::new(input.vpls, input.interleaving)?;
    let (width, height) = (input.gbuffer.width, input.gbuffer.height);
    if pixels == 0 {
        return assemble(Vec::new(), 0);
    }
    let view = CullView::new(input.camera, width, height)?;
    memory.fit(input.vpls.len(), partition.subregions(), pixels);
    let BoundedMemory {
        every,
        subregions: bounds,
        positions: packed,
        refiner,
    } = memory;
    subregion_bounds(
        input.vpls,
        &partition,
        input.delta,
        &view,
        glossy,
        every,
        bounds,
    )?;
    let refiner = match glossy {
        GlossyBound::Tight => Some(Refiner::new(
            input.vpls,
            bounds,
            input.delta,
            &view,
            clustering == Clustering::HalfZ,
            refiner,
        )?),
        _ => None,
    };
    positions(input.gbuffer, packed);
    let split = match clustering {
        Clustering::HalfZ => DepthSplit::HalfZ,
        Clustering::ExponentialSlices => depth_range(packed, &view)
            .map_or(DepthSplit::HalfZ, |(lo, hi)| DepthSplit::slices(lo, hi)),
    };
    let frame = TileInputs {
        width,
        positions: packed,
        view,
        bounds,
        split,
        k: input.interleaving.k,
        refiner,
    };
    let chunks = tiles(width, height, frame.k)
        .par_iter()
        .try_fold(Worker::default, |mut worker, tile| {
            worker.cull_tile(tile, &frame)?;
            Ok::<_, CullError>(worker)
        })
        .map(|worker| worker.map(|w| w.chunk))
        .collect::<Result<Vec<_>, _>>()?;
    assemble(chunks, pixels)
}

/// One piece of the parallel loop: its lists so far and scratch reused from tile to tile.
#[derive(Default)]
struct Worker {
    chunk: ListChunk,
    samples: Vec<Sample>,
    /// Per sample: where it sits, for the refinement (`tight` only).
    places: Vec<Place>,
    /// The samples with their places ordered by cluster and block, and where each
    /// (cluster, block) starts (`tight` only).
    ordered: Vec<(Sample, Place)>,
    key_starts: Vec<usize>,
    key_next: Vec<usize>,
    scratch: Scratch,
    ranges: Vec<[f64; 2]>,
    frusta: TileFrusta,
    /// Per chunk of eight bounds, those the f32 pre-test leaves to the exact test.
    candidates: Vec<u8>,
    /// Per cluster, the spheres and the ellipsoids that touch it (ascending VPL indices).
    sphere_hits: [Vec<u32>; MAX_CLUSTERS],
    ellipsoid_hits: [Vec<u32>; MAX_CLUSTERS],
}

impl Worker {
    fn cull_tile(&mut self, tile: &Tile, frame: &TileInputs) -> Result<(), CullError> {
        let Some((lo, hi)) = self.gather(tile, frame)? else {
            return Ok(());
        };
        frame.split.split(&mut self.samples, &mut self.ranges);
        self.frusta.set(lo, hi, &self.ranges);
        let clusters = self.ranges.len();
        for hits in self.sphere_hits[..clusters]
            .iter_mut()
            .chain(&mut self.ellipsoid_hits[..clusters])
        {
            hits.clear();
        }
        let bounds = &frame.bounds[tile.subregion(frame.k) as usize];
        let lanes = TileLanes::new(&self.frusta);
        bounds.sphere_lanes.candidates(&lanes, &mut self.candidates);
        for_each_candidate(&self.candidates, |k| {
            let s = &bounds.spheres[k];
            scatter(self.frusta.sphere_hits(s), s.index, &mut self.sphere_hits);
        });
        bounds
            .ellipsoid_lanes
            .candidates(&lanes, &mut self.candidates);
        for_each_candidate(&self.candidates, |k| {
            let e = &bounds.ellipsoids[k];
            scatter(
                self.frusta.ellipsoid_hits(e),
                e.index,
                &mut self.ellipsoid_hits,
            );
        });
        if let Some(refiner) = &frame.refiner {
            self.refine(refiner, clusters);
            return Ok(());
        }
        let mut list_of = [NO_LIST; MAX_CLUSTERS];
        for (c, list) in list_of[..clusters].iter_mut().enumerate() {
            *list = self
                .chunk
                .push_merged(&self.sphere_hits[c], &self.ellipsoid_hits[c]);
        }
        self.chunk.pixels.extend(
            self.samples
                .iter()
                .map(|s| (s.pixel, list_of[s.cluster as usize])),
        );
        Ok(())
    }

    /// The `tight` strategies' lists: each cluster's hits cut per block ([`Refiner::cut`]).
    fn refine(&mut self, refiner: &Refiner, clusters: usize) {
        // The tile's samples ordered by (cluster, block): a counting sort on that key.
        let key = |s: &Sample, p: &Place| usize::from(s.cluster) * BLOCKS + usize::from(p.block);
        self.key_starts.clear();
        self.key_starts.resize(clusters * BLOCKS + 1, 0);
        for (s, p) in self.samples.iter().zip(&self.places) {
            self.key_starts[key(s, p) + 1] += 1;
        }
        for k in 1..self.key_starts.len() {
            self.key_starts[k] += self.key_starts[k - 1];
        }
        let (Some(&s0), Some(&p0)) = (self.samples.first(), self.places.first()) else {
            return;
        };
        self.ordered.clear();
        self.ordered.resize(self.samples.len(), (s0, p0));
        self.key_next.clone_from(&self.key_starts);
        for (s, p) in self.samples.iter().zip(&self.places) {
            let slot = &mut self.key_next[key(s, p)];
            self.ordered[*slot] = (*s, *p);
            *slot += 1;
        }
        for c in 0..clusters {
            let range = self.key_starts[c * BLOCKS]..self.key_starts[(c + 1) * BLOCKS];
            refiner.cut(
                &mut self.ordered[range],
                &self.sphere_hits[c],
                &self.ellipsoid_hits[c],
                &mut self.scratch,
                &mut self.chunk,
            );
        }
    }

    /// Collects the tile's samples with their view depths and returns the tile's image-plane
    /// rectangle: the bounding rectangle of its pixels' footprints, grown to contain every
    /// sample's own projection (so a G-buffer made with another pixel convention is still
    /// covered); `None` if no pixel has a sample. Errors on a sample not in front of the
    /// camera. The depth is the sample's `GSample::depth` recomputed from its position in the
    /// culling view (f64), so the tile frusta and the VPL bounds see the same geometry.
    fn gather(
        &mut self,
        tile: &Tile,
        frame: &TileInputs,
    ) -> Result<Option<(DVec2, DVec2)>, CullError> {
        let [x0, y0, x1, y1] = tile.screen_rect(frame.k);
        let (mut lo, mut hi) = frame.view.image_rect(x0, y0, x1, y1);
        self.samples.clear();
        self.places.clear();
        let width = frame.width;
        let columns = tile.columns();
        // The position a row of the tile ahead is asked for while this one is read: the
        // pixels lie K apart (at K >= 4 each on a cache line of its own), and the loop waited
        // on each read (docs/cpu-frame.md, "The tiles' positions read a row ahead"). A hint
        // only.
        let ahead = tile
            .pixels(frame.k)
            .skip(columns as usize)
            .map(Some)
            .chain(std::iter::repeat(None));
        for ((i, [x, y]), next) in tile.pixels(frame.k).enumerate().zip(ahead) {
            if let Some(position) =
                next.and_then(|[x, y]| frame.positions.get((y * width + x) as usize))
            {
                prefetch(position);
            }
            let pixel = y * width + x;
            let Some(position) = frame.positions[pixel as usize] else {
                continue;
            };
            let p = frame.view.to_view(position);
            if !(p.z > 0.0 && p.is_finite()) {
                return Err(CullError::Input(format!(
                    "G-buffer sample of pixel ({x}, {y}) is not in front of the camera \
                     (view depth {})",
                    p.z
                )));
            }
            let uv = DVec2::new(p.x, p.y) / p.z;
            lo = lo.min(uv);
            hi = hi.max(uv);
            self.samples.push(Sample {
                pixel,
                z: p.z,
                cluster: 0,
            });
            if frame.refiner.is_some() {
                let i = i as u32;
                self.places.push(Place {
                    view: p,
                    extent: position.abs().max_element(),
                    block: block_of(i % columns, i / columns),
                });
            }
        }
        Ok((!self.samples.is_empty()).then_some((lo, hi)))
    }
}

/// Appends `index` to the hit list of every cluster in `mask`.
#[inline]
fn scatter(mut mask: u32, index: u32, hits: &mut [Vec<u32>; MAX_CLUSTERS]) {
    while mask != 0 {
        hits[mask.trailing_zeros() as usize].push(index);
        mask &= mask - 1;
    }
}
