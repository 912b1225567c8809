//! A pre-test of eight bounds at a time against a tile, in `f32` lanes, that never rejects a
//! bound the tile's exact test (`frusta`, f64) keeps: a tile only runs the exact test on the
//! bounds this one leaves, so its lists are exactly those of the exact test alone.
//!
//! The bounds of a subregion are stored as structures of arrays ([`EllipsoidLanes`],
//! [`SphereLanes`]), eight per chunk. A lane repeats the whole-tile test of
//! `TileFrusta::ellipsoid_hits` (the unit ball at BS·c against the box of the tile frustum's
//! image under BS, section 5.2, supplemental Listing 2) or `TileFrusta::sphere_hits` (the
//! sphere against the frustum's view-space box), with every per-axis gap shrunk by an error
//! bound before it is squared:
//!
//! - every quantity of a lane's arithmetic is at most `size` = m T + |BS·c|∞ (an ellipsoid:
//!   m the largest |entry| of BS, T the tile's reach (1 + max|u| + max|v|) max(1, z1)) or
//!   |box|∞ + |c|∞ (a sphere), and about ten f32 roundings (2⁻²⁴ relative to `size` each,
//!   inputs included) separate a gap in f32 from the same gap in f64; each gap is lowered by
//!   [`MARGIN`] · size, and the sum of squares must exceed the radius² by the relative
//!   [`SUM_SLACK`] to reject, and at least [`SUM_FLOOR`] (below f32's normal range the
//!   rounding of squares and radii is absolute, up to 2⁻¹⁵⁰, which no relative slack covers);
//! - a lane whose `size` is not below [`LIMIT`] (or NaN, or infinite, say from a bound too
//!   large for f32) is always left to the exact test, so no gap overflows (a square may, to
//!   infinity, and then rejects a gap the exact test rejects too); any NaN met on the way
//!   turns a gap into 0, which keeps the lane.
use crate::frusta::TileFrusta;
use crate::rounding::up;
use crate::vpl_bounds::{ViewEllipsoid, ViewSphere};
use glam::DVec3;
use slc_bounds::lanes::{max, min, Lanes8, F8};

/// How far a gap is lowered, relative to the largest magnitude in its lane: 64 ε (2⁻¹⁷),
/// about 13 times the rounding a gap can accumulate.
const MARGIN: f32 = 64.0 * f32::EPSILON;
/// Lanes with a magnitude at or above this are left to the exact test: every number of such
/// a lane stays below f32::MAX even after its roundings.
const LIMIT: f32 = 1e37;
/// The sum of squared gaps must exceed the radius² by this much (relative) to reject: it
/// covers the rounding of the sum, of the radius² to f32 and of the product itself.
const SUM_SLACK: f32 = 1e-5;
/// ... and exceed this (2⁻¹⁰⁰: biased exponent 27), so that every square that can decide a rejection is far
/// inside f32's normal range, where rounding is relative.
const SUM_FLOOR: f32 = f32::from_bits(27 << 23);

/// The largest |coordinate| of `v` in f32, rounded up.
fn magnitude(v: DVec3) -> f32 {
    up(v.abs().max_element())
}

/// `f` of each of up to eight items, in lanes (0 past the last item).
fn chunk_of<T>(items: &[T], f: impl Fn(&T) -> f32) -> F8 {
    F8(core::array::from_fn(|k| items.get(k).map_or(0.0, &f)))
}

/// The bits of the first `len` lanes (at most eight).
fn valid_bits(len: usize) -> u8 {
    (((1u16 << len.min(8)) - 1) & 0xff) as u8
}

/// What a tile's lanes read, in f32: its image-plane rectangle and whole depth range (as the
/// exact test has them, grown), the reach T and the view-space box with its magnitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TileLanes {
    rect: [f32; 4],
    depth: [f32; 2],
    reach: f32,
    box_min: [f32; 3],
    box_max: [f32; 3],
    box_size: f32,
}

impl TileLanes {
    pub(crate) fn new(frusta: &TileFrusta) -> Self {
        let ([lo, hi], [z0, z1], (box_min, box_max)) = frusta.whole();
        let reach = (1.0 + lo.x.abs().max(hi.x.abs()) + lo.y.abs().max(hi.y.abs())) * z1.max(1.0);
        Self {
            rect: [lo.x as f32, hi.x as f32, lo.y as f32, hi.y as f32],
            depth: [z0 as f32, z1 as f32],
            reach: up(reach),
            box_min: box_min.as_vec3().to_array(),
            box_max: box_max.as_vec3().to_array(),
            box_size: magnitude(box_min).max(magnitude(box_max)),
        }
    }
}

/// Eight ellipsoids' test spaces: BS by column and coordinate, BS·c, and per lane the
/// largest |entry| of BS (`scale`) and of BS·c (`offset`).
#[derive(Clone, Debug, PartialEq)]
struct EllipsoidChunk {
    columns: [[F8; 3]; 3],
    center: [F8; 3],
    scale: F8,
    offset: F8,
    valid: u8,
}

/// A subregion's ellipsoids in chunks of eight, in the order given.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct EllipsoidLanes(Vec<EllipsoidChunk>);

impl EllipsoidLanes {
    /// The chunks of `ellipsoids`, in place of this one's (in its memory).
    pub(crate) fn refill(&mut self, ellipsoids: &[ViewEllipsoid]) {
        self.0.clear();
        self.0.extend(ellipsoids.chunks(8).map(|e| EllipsoidChunk {
            columns: core::array::from_fn(|j| {
                core::array::from_fn(|i| chunk_of(e, |e| e.columns[j][i] as f32))
            }),
            center: core::array::from_fn(|i| chunk_of(e, |e| e.center[i] as f32)),
            scale: chunk_of(e, |e| {
                e.columns.iter().map(|&c| magnitude(c)).fold(0.0, f32::max)
            }),
            offset: chunk_of(e, |e| magnitude(e.center)),
            valid: valid_bits(e.len()),
        }));
    }

    /// Per chunk, the bits of the ellipsoids the tile's exact test may keep (pushed to
    /// `out`, which is cleared first).
    pub(crate) fn candidates(&self, tile: &TileLanes, out: &mut Vec<u8>) {
        candidates(self.0.as_slice(), tile, out);
    }
}

/// Chunks of bounds tested against a tile in lanes of any [`Lanes8`].
trait Chunks {
    fn test<L: Lanes8>(&self, tile: &TileLanes, out: &mut Vec<u8>);
}

impl Chunks for [EllipsoidChunk] {
    #[inline(always)]
    fn test<L: Lanes8>(&self, tile: &TileLanes, out: &mut Vec<u8>) {
        ellipsoids_in::<L>(self, tile, out);
    }
}

impl Chunks for [SphereChunk] {
    #[inline(always)]
    fn test<L: Lanes8>(&self, tile: &TileLanes, out: &mut Vec<u8>) {
        spheres_in::<L>(self, tile, out);
    }
}

/// `chunks` tested in AVX registers where the CPU has AVX2, else in plain lanes.
fn candidates<C: Chunks + ?Sized>(chunks: &C, tile: &TileLanes, out: &mut Vec<u8>) {
    out.clear();
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { candidates_avx2(chunks, tile, out) };
    }
    chunks.test::<F8>(tile, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn candidates_avx2<C: Chunks + ?Sized>(chunks: &C, tile: &TileLanes, out: &mut Vec<u8>) {
    chunks.test::<slc_bounds::lanes_avx::A8>(tile, out);
}

/// The lowered gap of one axis: the distance from `c` to [lo, hi], less `e`, at least 0.
#[inline(always)]
fn lowered_gap<L: Lanes8>(lo: L, hi: L, c: L, e: L) -> L {
    let zero = L::splat(0.0);
    max(max(max(lo - c, c - hi), zero) - e, zero)
}

#[inline(always)]
fn ellipsoids_in<L: Lanes8>(chunks: &[EllipsoidChunk], tile: &TileLanes, out: &mut Vec<u8>) {
    let [lx, hx, ly, hy] = [0, 1, 2, 3].map(|k| L::splat(tile.rect[k]));
    let [z0, z1] = [L::splat(tile.depth[0]), L::splat(tile.depth[1])];
    let reach = L::splat(tile.reach);
    let limit = L::splat(LIMIT);
    let threshold = L::splat(1.0 + SUM_SLACK);
    for chunk in chunks {
        let size = L::load(&chunk.scale) * reach + L::load(&chunk.offset);
        let e = size * L::splat(MARGIN);
        let mut sum = L::splat(0.0);
        for i in 0..3 {
            let cu = L::load(&chunk.columns[0][i]);
            let cv = L::load(&chunk.columns[1][i]);
            let cz = L::load(&chunk.columns[2][i]);
            let (u0, u1, v0, v1) = (cu * lx, cu * hx, cv * ly, cv * hy);
            let image_lo = cz + min(u0, u1) + min(v0, v1);
            let image_hi = cz + max(u0, u1) + max(v0, v1);
            let g = lowered_gap(
                min(image_lo * z0, image_lo * z1),
                max(image_hi * z0, image_hi * z1),
                L::load(&chunk.center[i]),
                e,
            );
            sum = sum + g * g;
        }
        let rejected = L::bits(size.le(limit) & sum.gt(threshold));
        out.push(!rejected & chunk.valid);
    }
}

/// Eight spheres: centres, radii² (f32, nearest) and the largest |coordinate| of each centre.
#[derive(Clone, Debug, PartialEq)]
struct SphereChunk {
    center: [F8; 3],
    radius_sq: F8,
    offset: F8,
    valid: u8,
}

/// A subregion's spheres in chunks of eight, in the order given.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct SphereLanes(Vec<SphereChunk>);

impl SphereLanes {
    /// The chunks of `spheres`, in place of this one's (in its memory).
    pub(crate) fn refill(&mut self, spheres: &[ViewSphere]) {
        self.0.clear();
        self.0.extend(spheres.chunks(8).map(|s| SphereChunk {
            center: core::array::from_fn(|i| chunk_of(s, |s| s.center[i] as f32)),
            radius_sq: chunk_of(s, |s| s.radius_sq as f32),
            offset: chunk_of(s, |s| magnitude(s.center)),
            valid: valid_bits(s.len()),
        }));
    }

    /// Per chunk, the bits of the spheres the tile's exact test may keep (pushed to `out`,
    /// which is cleared first).
    pub(crate) fn candidates(&self, tile: &TileLanes, out: &mut Vec<u8>) {
        candidates(self.0.as_slice(), tile, out);
    }
}

#[inline(always)]
fn spheres_in<L: Lanes8>(chunks: &[SphereChunk], tile: &TileLanes, out: &mut Vec<u8>) {
    let box_min = [0, 1, 2].map(|i| L::splat(tile.box_min[i]));
    let box_max = [0, 1, 2].map(|i| L::splat(tile.box_max[i]));
    let box_size = L::splat(tile.box_size);
    let limit = L::splat(LIMIT);
    let slack = L::splat(1.0 + SUM_SLACK);
    let floor = L::splat(SUM_FLOOR);
    for chunk in chunks {
        let size = box_size + L::load(&chunk.offset);
        let e = size * L::splat(MARGIN);
        let mut sum = L::splat(0.0);
        for i in 0..3 {
            let g = lowered_gap(box_min[i], box_max[i], L::load(&chunk.center[i]), e);
            sum = sum + g * g;
        }
        let threshold = max(L::load(&chunk.radius_sq) * slack, floor);
        let rejected = L::bits(size.le(limit) & sum.gt(threshold));
        out.push(!rejected & chunk.valid);
    }
}

/// Calls `f` with the index of every candidate in `bits` (one byte per chunk of eight), in
/// ascending order.
#[inline]
pub(crate) fn for_each_candidate(bits: &[u8], mut f: impl FnMut(usize)) {
    for (chunk, &b) in bits.iter().enumerate() {
        let mut b = b;
        while b != 0 {
            f(chunk * 8 + b.trailing_zeros() as usize);
            b &= b - 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use core::fmt::Debug;
    use glam::DVec2;

    fn ellipsoid_lanes(ellipsoids: &[ViewEllipsoid]) -> EllipsoidLanes {
        let mut lanes = EllipsoidLanes::default();
        lanes.refill(ellipsoids);
        lanes
    }

    fn sphere_lanes(spheres: &[ViewSphere]) -> SphereLanes {
        let mut lanes = SphereLanes::default();
        lanes.refill(spheres);
        lanes
    }

    /// 10^x for x uniform in [lo, hi].
    fn log_uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
        10f64.powf(rng.range64(lo, hi))
    }

    fn vector(rng: &mut Rng, magnitude: f64) -> DVec3 {
        DVec3::new(
            rng.range64(-1.0, 1.0),
            rng.range64(-1.0, 1.0),
            rng.range64(-1.0, 1.0),
        ) * magnitude
    }

    fn below(rng: &mut Rng, n: usize) -> usize {
        (rng.f64() * n as f64) as usize % n
    }

    /// A tile: a rectangle in [-3, 3]², a depth range from 1e-4 to 1e6 (or around 1e-20,
    /// where squares leave f32's normal range, or below it) split into 1 to 5 clusters.
    fn tile(rng: &mut Rng) -> TileFrusta {
        let (a, b) = (
            DVec2::new(rng.range64(-3.0, 3.0), rng.range64(-3.0, 3.0)),
            DVec2::new(rng.range64(-3.0, 3.0), rng.range64(-3.0, 3.0)),
        );
        let z0 = match below(rng, 8) {
            0 => log_uniform(rng, -42.0, -36.0),
            1 => log_uniform(rng, -22.0, -18.0),
            _ => log_uniform(rng, -4.0, 4.0),
        };
        let z1 = z0 * (1.0 + log_uniform(rng, -6.0, 2.0));
        let n = 1 + below(rng, 5);
        let cuts: Vec<f64> = (0..=n)
            .map(|k| z0 + (z1 - z0) * k as f64 / n as f64)
            .collect();
        let ranges: Vec<[f64; 2]> = cuts.windows(2).map(|w| [w[0], w[1]]).collect();
        let mut f = TileFrusta::default();
        f.set(a.min(b), a.max(b), &ranges);
        f
    }

    /// The whole tile's box under the test space `columns` (as `TileFrusta::ellipsoid_hits`
    /// forms it).
    fn image_box(f: &TileFrusta, columns: [DVec3; 3]) -> (DVec3, DVec3) {
        let ([lo, hi], [z0, z1], _) = f.whole();
        let [cu, cv, cz] = columns;
        let (u0, u1) = (cu * lo.x, cu * hi.x);
        let (v0, v1) = (cv * lo.y, cv * hi.y);
        let image_lo = cz + u0.min(u1) + v0.min(v1);
        let image_hi = cz + u0.max(u1) + v0.max(v1);
        (
            (image_lo * z0).min(image_lo * z1),
            (image_hi * z0).max(image_hi * z1),
        )
    }

    /// A point at distance about `d` from the box `[lo, hi]`: outside one face, an edge or a
    /// corner, or inside (d = 0).
    fn near_box(rng: &mut Rng, (lo, hi): (DVec3, DVec3), d: f64) -> DVec3 {
        let inside = DVec3::new(
            rng.range64(lo.x, hi.x),
            rng.range64(lo.y, hi.y),
            rng.range64(lo.z, hi.z),
        );
        let axes = 1 + below(rng, 3);
        let mut p = inside;
        for _ in 0..axes {
            let i = below(rng, 3);
            let out = d / (axes as f64).sqrt();
            p[i] = if rng.f64() < 0.5 {
                lo[i] - out
            } else {
                hi[i] + out
            };
        }
        p
    }

    /// A distance to put a bound at: mostly within a millionth of tangent, else anywhere.
    fn distance(rng: &mut Rng, radius: f64) -> f64 {
        match below(rng, 4) {
            0 => 0.0,
            1 => rng.range64(0.0, 4.0 * radius),
            _ => radius * (1.0 + rng.range64(-1e-6, 1e-6)),
        }
    }

    /// Magnitudes from tiny (below f32's normal range) to beyond f32's range.
    fn magnitude_scale(rng: &mut Rng) -> f64 {
        match below(rng, 8) {
            0 => log_uniform(rng, -45.0, -30.0),
            1 => log_uniform(rng, 30.0, 45.0),
            2 => log_uniform(rng, -22.0, -18.0),
            _ => log_uniform(rng, -4.0, 8.0),
        }
    }

    fn plain_and_wide<T>(
        chunks: &T,
        tile: &TileLanes,
        plain: impl Fn(&T, &TileLanes, &mut Vec<u8>),
        public: impl Fn(&T, &TileLanes, &mut Vec<u8>),
    ) -> Vec<u8> {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        plain(chunks, tile, &mut a);
        public(chunks, tile, &mut b);
        assert_eq!(a, b, "the AVX lanes differ from the plain ones");
        a
    }

    /// What the property tests of the pre-test count: bounds the exact test keeps (each must
    /// be a candidate), bounds the pre-test rejects, and bounds clearly outside (each must be
    /// rejected); enough of each, or the random cases missed the regime.
    #[derive(Default)]
    struct Tally {
        kept: u32,
        rejected: u32,
        far: u32,
    }

    impl Tally {
        /// Bound `k` of the candidate bits `bits`, kept by the exact test where `hit`.
        fn record(&mut self, bits: &[u8], k: usize, hit: bool, outside: bool, what: &dyn Debug) {
            let candidate = bits[k / 8] & (1 << (k % 8)) != 0;
            if hit {
                assert!(candidate, "kept by the exact test, rejected: {what:?}");
                self.kept += 1;
            } else if !candidate {
                self.rejected += 1;
            }
            if outside {
                self.far += 1;
                assert!(!candidate, "clearly outside, kept: {what:?}");
            }
        }

        fn check(&self) {
            let Self {
                kept,
                rejected,
                far,
            } = self;
            assert!(
                *kept > 5_000 && *rejected > 2_000 && *far > 2_000,
                "{kept} {rejected} {far}"
            );
        }
    }

    /// No ellipsoid that the exact test keeps (for any cluster) is rejected, over tiles and
    /// test spaces whose magnitudes run from 1e-45 to 1e45, most of them within a millionth
    /// of tangent; and the pre-test does reject most of the bounds clearly outside.
    #[test]
    fn ellipsoids_the_exact_test_keeps_are_candidates() {
        let mut rng = Rng(0x5eed_1234_abcd_9876);
        let mut tally = Tally::default();
        for _ in 0..3000 {
            let f = tile(&mut rng);
            let scale = magnitude_scale(&mut rng);
            let ellipsoids: Vec<ViewEllipsoid> = (0..1 + below(&mut rng, 20))
                .map(|index| {
                    let columns = [0; 3].map(|_| {
                        let m = scale * log_uniform(&mut rng, -2.0, 0.0);
                        vector(&mut rng, m)
                    });
                    let d = distance(&mut rng, 1.0);
                    ViewEllipsoid {
                        columns,
                        center: near_box(&mut rng, image_box(&f, columns), d),
                        index: index as u32,
                    }
                })
                .collect();
            let lanes = ellipsoid_lanes(&ellipsoids);
            let t = TileLanes::new(&f);
            let bits = plain_and_wide(
                &lanes,
                &t,
                |l, t, out| {
                    out.clear();
                    ellipsoids_in::<F8>(&l.0, t, out)
                },
                EllipsoidLanes::candidates,
            );
            for (k, e) in ellipsoids.iter().enumerate() {
                // Clearly outside: beyond the radius by more than the margin can grow it.
                let ([lo, hi], [_, z1], _) = f.whole();
                let reach =
                    (1.0 + lo.x.abs().max(hi.x.abs()) + lo.y.abs().max(hi.y.abs())) * z1.max(1.0);
                let m = e
                    .columns
                    .iter()
                    .map(|c| c.abs().max_element())
                    .fold(0.0, f64::max);
                let size = m * reach + e.center.abs().max_element();
                let (lo, hi) = image_box(&f, e.columns);
                let gap = (lo - e.center).max(e.center - hi).max(DVec3::ZERO);
                let outside = gap.length() > 1.0 + 1e-4 * size && size < 1e30 && size > 1e-30;
                tally.record(&bits, k, f.ellipsoid_hits(e) != 0, outside, &(e, &f));
            }
        }
        tally.check();
    }

    /// The same for spheres against the tile's view-space box.
    #[test]
    fn spheres_the_exact_test_keeps_are_candidates() {
        let mut rng = Rng(0x0dd_ba11_cafe_f00d);
        let mut tally = Tally::default();
        for _ in 0..3000 {
            let f = tile(&mut rng);
            let (_, _, whole_box) = f.whole();
            let scale = magnitude_scale(&mut rng);
            let spheres: Vec<ViewSphere> = (0..1 + below(&mut rng, 20))
                .map(|index| {
                    let radius = scale * log_uniform(&mut rng, -3.0, 0.0);
                    let d = distance(&mut rng, radius);
                    ViewSphere {
                        center: near_box(&mut rng, whole_box, d),
                        radius_sq: radius * radius,
                        index: index as u32,
                    }
                })
                .collect();
            let lanes = sphere_lanes(&spheres);
            let bits = plain_and_wide(
                &lanes,
                &TileLanes::new(&f),
                |l, t, out| {
                    out.clear();
                    spheres_in::<F8>(&l.0, t, out)
                },
                SphereLanes::candidates,
            );
            for (k, s) in spheres.iter().enumerate() {
                let (lo, hi) = whole_box;
                let size = lo.abs().max(hi.abs()).max_element() + s.center.abs().max_element();
                let gap = (lo - s.center).max(s.center - hi).max(DVec3::ZERO);
                // (Squared gaps near the floor are left to the exact test.)
                let outside = gap.length() > s.radius_sq.sqrt() + 1e-4 * size
                    && gap.length_squared() > 1e-28
                    && size < 1e30
                    && s.radius_sq < 1e37;
                tally.record(&bits, k, f.sphere_hits(s) != 0, outside, &(s, &f));
            }
        }
        tally.check();
    }

    /// A sphere and a tile far below f32's normal range: the squared gaps and the radius²
    /// round to multiples of 2⁻¹⁴⁹, where a relative slack covers nothing (the floor does).
    #[test]
    fn spheres_below_the_normal_range_are_kept() {
        let mut f = TileFrusta::default();
        f.set(
            DVec2::splat(-1.0),
            DVec2::ONE,
            &[[2f64.powi(-70), 2f64.powi(-69)]],
        );
        let (_, _, (_, box_max)) = f.whole();
        let d = 1.15 * 2f64.powi(-75);
        let sphere = ViewSphere {
            center: DVec3::new(box_max.x + d, 0.0, box_max.z + d),
            radius_sq: 1.4 * 2f64.powi(-149),
            index: 0,
        };
        assert_ne!(f.sphere_hits(&sphere), 0, "the exact test keeps it");
        let mut bits = Vec::new();
        sphere_lanes(&[sphere]).candidates(&TileLanes::new(&f), &mut bits);
        assert_eq!(bits, [1]);
    }

    /// Lanes past the last bound are never candidates, and the indices come out ascending.
    #[test]
    fn only_real_bounds_are_candidates_in_order() {
        let far = ViewSphere {
            center: DVec3::ZERO,
            radius_sq: f64::INFINITY,
            index: 0,
        };
        let mut f = TileFrusta::default();
        f.set(DVec2::splat(-1.0), DVec2::ONE, &[[1.0, 2.0]]);
        for n in [1, 7, 8, 9, 17] {
            let lanes = sphere_lanes(&vec![far; n]);
            let mut bits = Vec::new();
            lanes.candidates(&TileLanes::new(&f), &mut bits);
            let mut seen = Vec::new();
            for_each_candidate(&bits, |k| seen.push(k));
            assert_eq!(seen, (0..n).collect::<Vec<_>>());
        }
    }
}
