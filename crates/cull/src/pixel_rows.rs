//! The G-buffer positions as `binned`'s per-pixel tests read them, and those tests: each
//! subregion image's rows stored as chunks of eight pixels (x, y and z in lanes, structure of
//! arrays), so the pixels of one row of a bound's rectangle are a few contiguous chunks. A
//! chunk is first tested in f32, eight pixels at once, with limits moved by that
//! arithmetic's worst rounding ([`Filter`]) to the pixels that surely pass the exact f64
//! test ([`PixelTest::contains`]), those that surely fail it, and the few near the bound's
//! surface or the VPL's tangent plane that only the exact test can decide (a rectangle of a
//! few pixels takes the exact test alone, [`EXACT_PIXELS`]). So the lists are those of the
//! exact test on every pixel of the rectangle (`tests` checks both), at a fraction of its
//! cost.
use crate::cells::CellBoxes;
use crate::pair_lists::Bands;
use crate::partition::group_by;
use crate::reach::SIGN_MARGIN;
use crate::rounding::{down, up};
use crate::scatter::{Frame, PixelTest, Scattered};
use glam::Vec3;
use slc_bounds::lanes::{dot, Lanes8, F8};

/// A rectangle of at most this many pixels takes the exact test pixel by pixel
/// ([`PixelRows::test_exactly`]), without forming its VPL's f32 filter (a few f64 divisions
/// and roots, more than the tests it would spare): at 480x270 with RSM 1024, 234k of the
/// 396k VPLs placed, whose culling took 1–1.5 ms less so (2 measured alike, docs/many-vpls.md).
const EXACT_PIXELS: u32 = 4;

/// Pixels per chunk: the lanes of one test.
const LANES: usize = 8;

/// Eight pixels' positions, one plane per axis; NaN where a lane holds no sample.
type Chunk = [F8; 3];

/// The positions of a `width` x `height` image split K x K into subregion images (pixel
/// (sx + K i, sy + K j) is pixel (i, j) of subregion (sx, sy)), laid out by [`Layout`].
pub(crate) struct PixelRows {
    chunks: Vec<Chunk>,
    layout: Layout,
}

/// Where a pixel's position lies: every subregion row holds `chunks_per_row` chunks, and the
/// rows of one screen row (y = sy + K j) for sx = 0..K lie next to each other, so each screen
/// row is written on its own.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Layout {
    chunks_per_row: usize,
    width: u32,
    k: u32,
}

impl Layout {
    /// Chunks per screen row.
    fn screen_row(&self) -> usize {
        self.k as usize * self.chunks_per_row
    }

    /// Where pixel `x` of a screen row goes: (chunk of the row, lane). Pixel x is column
    /// i = x / K of subregion row sx = x mod K.
    #[cfg(test)]
    fn slot(&self, x: u32) -> (usize, usize) {
        let (sx, i) = ((x % self.k) as usize, (x / self.k) as usize);
        (sx * self.chunks_per_row + i / LANES, i % LANES)
    }

    /// The [`Self::slot`]s of pixels x = 0, 1, ... of a screen row, counted along the row
    /// instead of divided per pixel.
    pub(crate) fn slots(&self) -> impl Iterator<Item = (usize, usize)> {
        let (k, per) = (self.k as usize, self.chunks_per_row);
        let (mut sx, mut i) = (0, 0);
        std::iter::repeat_with(move || {
            let slot = (sx * per + i / LANES, i % LANES);
            sx += 1;
            if sx == k {
                sx = 0;
                i += 1;
            }
            slot
        })
    }

    /// Writes `position` into `slot` of a screen row's chunks (one item of
    /// [`PixelRows::screen_rows_mut`]).
    #[inline]
    pub(crate) fn set(screen_row: &mut [Chunk], (chunk, lane): (usize, usize), position: Vec3) {
        for (plane, v) in screen_row[chunk].iter_mut().zip(position.to_array()) {
            plane.0[lane] = v;
        }
    }
}

impl PixelRows {
    /// No sample at any pixel of a `width` x `height` image interleaved K x K.
    pub(crate) fn empty(width: u32, height: u32, k: u32) -> Self {
        let layout = Layout {
            chunks_per_row: (width.div_ceil(k) as usize).div_ceil(LANES),
            width,
            k,
        };
        Self {
            chunks: vec![[F8([f32::NAN; LANES]); 3]; height as usize * layout.screen_row()],
            layout,
        }
    }

    /// The layout, and each screen row's chunks in parallel (row y is item y), to be
    /// written with [`Layout::set`].
    pub(crate) fn screen_rows_mut(&mut self) -> (Layout, rayon::slice::ChunksMut<'_, Chunk>) {
        use rayon::slice::ParallelSliceMut;
        let layout = self.layout;
        (layout, self.chunks.par_chunks_mut(layout.screen_row()))
    }

    /// Pushes (pixel, VPL) for every pixel of every rectangle of `scattered` whose sample
    /// passes the VPL's [`PixelTest`], VPL by VPL, each rectangle row by row, or its pixels
    /// gathered into one chunk where it is small ([`Self::gathered`]; within a chunk, those
    /// that surely pass first), or pixel by pixel where it is smaller still
    /// ([`Self::test_exactly`]): the pairs the exact test gives on every pixel, each pixel's
    /// in the order of `scattered`.
    ///
    /// The VPLs are taken subregion by subregion ([`by_subregion`]), so one subregion
    /// image's rows stay in cache while its VPLs test them: in `scattered` the subregions
    /// interleave (a VPL's is a hash of its id), and taken in that order every rectangle's
    /// rows would be read from a different part of the whole image's positions.
    pub(crate) fn test(&self, scattered: &[Scattered], pairs: &mut Bands) {
        let ordered = by_subregion(scattered, self.layout.k);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe { test_avx2(self, &ordered, pairs) };
        }
        test_lanes::<F8>(self, &ordered, pairs);
    }

    /// The pixels of `s`'s rectangle, row by row: each one's chunk, its lane there and its
    /// screen pixel.
    #[inline(always)]
    fn rectangle(&self, s: &Scattered) -> impl Iterator<Item = (&Chunk, usize, u32)> + '_ {
        let Layout {
            chunks_per_row: per,
            width,
            k,
        } = self.layout;
        let [i0, j0, i1, j1] = s.pixels;
        let [sx, sy] = s.subregion;
        (j0..=j1).flat_map(move |j| {
            let y = sy + k * j;
            let first = (y as usize * k as usize + sx as usize) * per;
            (i0..=i1).map(move |i| {
                let chunk = &self.chunks[first + i as usize / LANES];
                (chunk, i as usize % LANES, y * width + sx + k * i)
            })
        })
    }

    /// Pushes the pixels of `s`'s rectangle that pass its exact test, one at a time, row by
    /// row: those the filter and the chunks would give.
    #[inline(always)]
    fn test_exactly(&self, s: &Scattered, pairs: &mut Bands) {
        for ([x, y, z], lane, pixel) in self.rectangle(s) {
            if s.test.contains(Vec3::new(x.0[lane], y.0[lane], z.0[lane])) {
                pairs.push(pixel, s.index);
            }
        }
    }

    /// The pixels of `s`'s rectangle gathered into one chunk (lanes in row order, NaN past
    /// the last), their screen pixels and the lanes they fill, where the rectangle has at
    /// most eight pixels but lies in more than one chunk: one test where its rows would take
    /// two to eight. Most rectangles are that small at a million VPLs (Sponza at 480x270 with
    /// RSM 1024: 234k of the 396k VPLs placed cover at most 4 pixels, and their rows took
    /// 625k of the 1.97M chunks tested); those of at most [`EXACT_PIXELS`] are tested pixel
    /// by pixel instead.
    #[inline(always)]
    fn gathered(&self, s: &Scattered) -> Option<(Chunk, [u32; LANES], u8)> {
        let [i0, j0, i1, j1] = s.pixels;
        let (w, h) = (i1 - i0 + 1, j1 - j0 + 1);
        let chunks = h as usize * (i1 as usize / LANES - i0 as usize / LANES + 1);
        let n = (w * h) as usize;
        if n > LANES || chunks == 1 {
            return None;
        }
        let mut chunk: Chunk = [F8([f32::NAN; LANES]); 3];
        let mut pixels = [0; LANES];
        for (at, (from, lane, pixel)) in self.rectangle(s).enumerate() {
            for (plane, from) in chunk.iter_mut().zip(from) {
                plane.0[at] = from.0[lane];
            }
            pixels[at] = pixel;
        }
        Some((chunk, pixels, (0xFFu16 >> (LANES - n)) as u8))
    }
}

/// Pixels per side of a cell of a subregion image ([`PixelRows::cell_boxes`]): half a chunk
/// wide.
pub(crate) const CELL: u32 = LANES as u32 / 2;

impl PixelRows {
    /// The box of each cell's positions: a cell is [`CELL`] lanes of a chunk in [`CELL`]
    /// consecutive subregion rows.
    pub(crate) fn cell_boxes(&self) -> CellBoxes {
        let Layout {
            chunks_per_row: per,
            k,
            ..
        } = self.layout;
        let height = (self.chunks.len() / self.layout.screen_row()) as u32;
        let cells_per_chunk = LANES / CELL as usize;
        let across = (per * cells_per_chunk) as u32;
        let down = height.div_ceil(k).div_ceil(CELL);
        CellBoxes::new(k, [across, down], |[sx, sy], [cx, cy]| {
            let (c, first) = (
                cx as usize / cells_per_chunk,
                cx as usize % cells_per_chunk * CELL as usize,
            );
            let mut b = [Vec3::INFINITY, Vec3::NEG_INFINITY];
            for j in cy * CELL..(cy + 1) * CELL {
                let y = sy + k * j;
                if y >= height {
                    break;
                }
                let chunk = &self.chunks[(y as usize * k as usize + sx as usize) * per + c];
                for lane in first..first + CELL as usize {
                    let x = Vec3::new(chunk[0].0[lane], chunk[1].0[lane], chunk[2].0[lane]);
                    // A lane without a sample is NaN throughout.
                    if !x.x.is_nan() {
                        b = [b[0].min(x), b[1].max(x)];
                    }
                }
            }
            b
        })
    }
}

/// The entries of `scattered` subregion by subregion, each subregion's in their order
/// ([`group_by`], as [`crate::partition::Partition`] groups VPLs). Every pixel lies in one
/// subregion, so its pairs keep the order of `scattered`. With more subregions than entries
/// there is less than one entry per subregion, nothing to gather, and the counters would
/// outweigh the entries (K² + 1 of them, 4 MiB at K = 1024): the order is kept as it is.
fn by_subregion(scattered: &[Scattered], k: u32) -> Vec<&Scattered> {
    let subregions = k as usize * k as usize;
    if subregions > scattered.len() {
        return scattered.iter().collect();
    }
    let keys: Vec<u32> = scattered
        .iter()
        .map(|s| s.subregion[1] * k + s.subregion[0])
        .collect();
    let (_, order) = group_by(&keys, subregions);
    order.iter().map(|&i| &scattered[i as usize]).collect()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn test_avx2(rows: &PixelRows, scattered: &[&Scattered], pairs: &mut Bands) {
    test_lanes::<slc_bounds::lanes_avx::A8>(rows, scattered, pairs);
}

/// [`PixelRows::test`] in lanes `L`, the VPLs in the order of `scattered`.
#[inline(always)]
fn test_lanes<L: Lanes8>(rows: &PixelRows, scattered: &[&Scattered], pairs: &mut Bands) {
    let Layout {
        chunks_per_row: per,
        width,
        k,
    } = rows.layout;
    for s in scattered {
        let [i0, j0, i1, j1] = s.pixels;
        if (i1 - i0 + 1) * (j1 - j0 + 1) <= EXACT_PIXELS {
            rows.test_exactly(s, pairs);
            continue;
        }
        let filter = Filter::of(&s.test).map(|f| f.lanes::<L>());
        if let Some((chunk, pixels, within)) = rows.gathered(s) {
            decide(
                &filter,
                s,
                &chunk,
                within,
                |lane| pixels[lane as usize],
                pairs,
            );
            continue;
        }
        let [sx, sy] = s.subregion;
        let (c0, c1) = (i0 as usize / LANES, i1 as usize / LANES);
        for j in j0..=j1 {
            let y = sy + k * j;
            let first = (y as usize * k as usize + sx as usize) * per;
            let pixel_row = y * width + sx;
            for (c, chunk) in rows.chunks[first + c0..=first + c1].iter().enumerate() {
                let c = c0 + c;
                let within = lanes_within(c, i0, i1);
                let pixel = |lane: u32| pixel_row + k * (c as u32 * LANES as u32 + lane);
                decide(&filter, s, chunk, within, pixel, pairs);
            }
        }
    }
}

/// Pushes the pixels of `chunk`'s lanes `within` that pass `s`'s test (lane k is pixel
/// `pixel(k)`): those the filter surely passes first, then those only the exact test can
/// decide.
#[inline(always)]
fn decide<L: Lanes8>(
    filter: &Option<Filter<L>>,
    s: &Scattered,
    chunk: &Chunk,
    within: u8,
    pixel: impl Fn(u32) -> u32,
    pairs: &mut Bands,
) {
    let (mut sure, mut undecided) = match filter {
        Some(f) => {
            let (maybe, sure) = f.classify(chunk);
            (sure & within, maybe & !sure & within)
        }
        None => (0, within),
    };
    while sure != 0 {
        let lane = sure.trailing_zeros();
        sure &= sure - 1;
        pairs.push(pixel(lane), s.index);
    }
    while undecided != 0 {
        let lane = undecided.trailing_zeros();
        undecided &= undecided - 1;
        let at = |plane: &F8| plane.0[lane as usize];
        if s.test
            .contains(Vec3::new(at(&chunk[0]), at(&chunk[1]), at(&chunk[2])))
        {
            pairs.push(pixel(lane), s.index);
        }
    }
}

/// The lanes of chunk `c` (pixels 8c..8c+7 of a row) within `[i0, i1]`, as bits.
#[inline(always)]
pub(crate) fn lanes_within(c: usize, i0: u32, i1: u32) -> u8 {
    let base = c * LANES;
    let lo = (i0 as usize).saturating_sub(base);
    let hi = (i1 as usize - base).min(LANES - 1);
    ((0xFFu16 << lo) & (0xFFu16 >> (LANES - 1 - hi))) as u8
}

/// A [`PixelTest`] in f32, eight pixels at a time, with limits that keep every pixel the
/// exact test passes ("maybe") and pass only pixels it passes ("sure"); the exact test
/// decides the rest.
///
/// **The bound.** With d = x − q (q the VPL's position, both f32: the subtraction rounds by
/// at most u|d|, u = 2⁻²⁴), e = d − c (c rounded to f32: at most u|c| more, and u|e| for
/// the subtraction), t = e·ω_u and the quadric Q = |e − t ω_u|²/r² + t²/r_u² of the exact
/// test: near the bound (|e| ≤ R = max(r_u, r)), |d| ≤ |e| + |c|, so the error of e is at
/// most 2u(R + |c|)(1 + u); rounding ω_u, forming t and the perpendicular part adds at most
/// about 10u R; and √Q, a norm with the smallest semi-axis r_min as its smallest scale,
/// moves by at most (error of e)/r_min, plus a few u relative from the products, the rounded
/// reciprocals and the sums. [`Filter::of`] takes twice that as its slack s =
/// 32u(R + |c|)/r_min + 8u: √Q_f32 ≤ √`LIMIT` + s may be inside, √Q_f32 ≤ √`LIMIT` − s is
/// inside.
///
/// **The sign.** The exact test rejects a pixel behind the VPL: ωo·n < 0 and
/// (ωo·n)² > m²|d|² (m² the f32 square of `SIGN_MARGIN`, 1e-5). In f32, n·d is off by at
/// most 5u|d| (n is the VPL's own f32 unit normal) and |d|² by 5u relative, so with margins
/// of 16u: n·d < 0 and (n·d)² > (m + 16u)²(1 + 16u)|d|² is surely behind, and n·d ≥ 0 or
/// (n·d)² < (m − 16u)²(1 − 16u)|d|² is surely not, both only where |d|² exceeds
/// [`SMALLEST_D_SQ`] (else the exact test decides).
///
/// The VPL's position q and normal n are f32 values (as `Vpl`'s are), so the filter takes
/// them exactly. Where the slack reaches √`LIMIT` no lane is sure. Where an input is so
/// extreme that f32 could overflow or lose the bound (semi-axes outside [1e-18, 1e18], or
/// the centre more than 1e18 from the VPL), there is no filter and every pixel takes the
/// exact test. A NaN position (no sample) is neither maybe nor sure.
///
/// `Filter<f32>` holds one VPL's values, `Filter<L>` the same in every lane of `L`.
#[derive(Clone, Copy, Debug)]
struct Filter<R = f32> {
    frame: Frame<R>,
    inv_along_sq: R,
    inv_across_sq: R,
    /// Q at most this: may be inside; at most `inside`: inside.
    maybe_inside: R,
    inside: R,
    /// (n·d)² above `behind` |d|², with n·d < 0: behind; below `front` |d|²: not behind.
    behind: R,
    front: R,
}

/// The smallest |d|² for which the f32 sign test decides: below it the cosine's products may
/// underflow (to a zero of either sign). Above it the products compared may still be
/// subnormal, but rounding is monotone, so the comparisons keep their margins.
const SMALLEST_D_SQ: f32 = 1e-30;

impl Filter {
    fn of(test: &PixelTest) -> Option<Self> {
        debug_assert_eq!(
            test.position.as_vec3().as_dvec3(),
            test.position,
            "the VPL's position is an f32 point"
        );
        let [along, across] = test.semi_axes();
        let (r_max, r_min) = (along.max(across), along.min(across));
        let c = test.center.length();
        if !test.fits_f32() {
            return None;
        }
        let u = f64::from(f32::EPSILON) / 2.0;
        let slack = 32.0 * u * (r_max + c) / r_min + 8.0 * u;
        let [inv_along_sq, inv_across_sq] = test.inverse_squares();
        let root = crate::scatter::LIMIT.sqrt();
        let m = f64::from(SIGN_MARGIN * SIGN_MARGIN).sqrt();
        Some(Self {
            frame: Frame::of(test),
            inv_along_sq: inv_along_sq as f32,
            inv_across_sq: inv_across_sq as f32,
            maybe_inside: up((root + slack).powi(2)),
            // No lane is sure where the slack reaches the bound's own size.
            inside: match slack < root {
                true => down((root - slack).powi(2)),
                false => -1.0,
            },
            behind: up((m + 16.0 * u).powi(2) * (1.0 + 16.0 * u)),
            front: down((m - 16.0 * u).powi(2) * (1.0 - 16.0 * u)),
        })
    }

    #[inline(always)]
    fn lanes<L: Lanes8>(&self) -> Filter<L> {
        Filter {
            frame: self.frame.lanes(),
            inv_along_sq: L::splat(self.inv_along_sq),
            inv_across_sq: L::splat(self.inv_across_sq),
            maybe_inside: L::splat(self.maybe_inside),
            inside: L::splat(self.inside),
            behind: L::splat(self.behind),
            front: L::splat(self.front),
        }
    }
}

impl<L: Lanes8> Filter<L> {
    /// The lanes of `chunk` that may pass the exact test (bit k for lane k; never a NaN
    /// lane), and those that surely pass it.
    #[inline(always)]
    fn classify(&self, chunk: &Chunk) -> (u8, u8) {
        // No closures: each would be a function without AVX2, calling every intrinsic.
        let f = &self.frame;
        let [q, c, a, n] = [&f.q, &f.center, &f.axis, &f.normal];
        let d = [
            L::load(&chunk[0]) - q[0],
            L::load(&chunk[1]) - q[1],
            L::load(&chunk[2]) - q[2],
        ];
        let e = [d[0] - c[0], d[1] - c[1], d[2] - c[2]];
        let t = dot(e, *a);
        let perp = [e[0] - t * a[0], e[1] - t * a[1], e[2] - t * a[2]];
        let quadric = dot(perp, perp) * self.inv_across_sq + t * t * self.inv_along_sq;
        let maybe_in = quadric.le(self.maybe_inside);
        // Most chunks end here: 85% of the VPLs placed at RSM 1024 pass no pixel, and outside
        // the bound no lane may pass whatever the sign (docs/many-vpls.md).
        if !L::any(maybe_in) {
            return (0, 0);
        }
        let cos = dot(*n, d);
        let (cos_sq, d_sq) = (cos * cos, dot(d, d));
        let negative = L::splat(0.0).gt(cos);
        // Below it, the products of the cosine may underflow to a zero of either sign.
        let decided = d_sq.gt(L::splat(SMALLEST_D_SQ));
        let behind = negative & cos_sq.gt(self.behind * d_sq) & decided;
        let front = (!negative | (self.front * d_sq).gt(cos_sq)) & decided;
        let maybe = maybe_in & !behind;
        let sure = quadric.le(self.inside) & front;
        (L::bits(maybe), L::bits(sure))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pair_lists::lists;
    use crate::test_rng::{bound, point, unit, varied_bound, Rng};
    use glam::DVec3;
    use rayon::prelude::*;

    /// The lanes of `points` (as a chunk) the exact test passes, those the filter may pass
    /// and those it surely passes, in plain and (where the CPU has them) AVX2 lanes, which
    /// agree.
    fn classified(filter: &Filter, test: &PixelTest, points: [Vec3; 8]) -> (u8, u8, u8) {
        let mut chunk: Chunk = [F8([0.0; 8]); 3];
        let mut exact = 0u8;
        for (lane, x) in points.into_iter().enumerate() {
            for (a, plane) in chunk.iter_mut().enumerate() {
                plane.0[lane] = x[a];
            }
            exact |= u8::from(test.contains(x)) << lane;
        }
        let (maybe, sure) = filter.lanes::<F8>().classify(&chunk);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            let avx = unsafe { classify_avx2(filter, &chunk) };
            assert_eq!(avx, (maybe, sure), "{filter:?}");
        }
        (exact, maybe, sure)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn classify_avx2(filter: &Filter, chunk: &Chunk) -> (u8, u8) {
        filter.lanes::<slc_bounds::lanes_avx::A8>().classify(chunk)
    }

    /// The filter may pass every f32 point the exact test passes and surely passes only
    /// such points, in plain and AVX2 lanes: points near the surfaces of bounds from 1e-6
    /// to 1e6 with eccentricities up to 1e5, from VPLs up to 1e4 times their size from the
    /// origin, and points near the VPL's tangent plane (where the sign test decides), with
    /// the VPL's normal or without one.
    #[test]
    fn the_filter_keeps_every_pixel_the_exact_test_passes_and_passes_only_those() {
        let mut rng = Rng(7);
        let (mut inside, mut sure_inside, mut plane_passed, mut plane_sure) = (0, 0, 0, 0);
        for round in 0..40_000 {
            let test = varied_bound(&mut rng, round);
            let filter = Filter::of(&test).expect("within the filter's domain");
            let near_surface =
                [(); 8].map(|_| point(&test, unit(&mut rng) * (1.0 + rng.range64(-1e-4, 1e-4))));
            // Offsets d from the VPL within the bound's size whose cosine to the normal is
            // near ±SIGN_MARGIN, 0 or far from it.
            let r = test.semi_axes()[0].max(test.semi_axes()[1]);
            let near_plane = [(); 8].map(|_| {
                let n = test.normal.normalize_or(DVec3::Z);
                let along = unit(&mut rng)
                    .reject_from(n)
                    .normalize_or(n.any_orthonormal_vector());
                let cos = match rng.range64(0.0, 4.0) as u32 {
                    0 => 0.0,
                    1 => 1e-5 * rng.range64(-1.01, -0.99),
                    2 => 1e-5 * rng.range64(0.99, 1.01),
                    _ => rng.range64(-1.0, 1.0),
                };
                let d = (along * (1.0 - cos * cos).sqrt() + n * cos) * r * rng.range64(0.0, 1.0);
                (test.position + d).as_vec3()
            });
            for (points, at_plane) in [(near_surface, false), (near_plane, true)] {
                let (exact, maybe, sure) = classified(&filter, &test, points);
                assert_eq!(
                    exact & !maybe,
                    0,
                    "{test:?} {points:?}: exact {exact:08b}, maybe {maybe:08b}"
                );
                assert_eq!(
                    sure & !exact,
                    0,
                    "{test:?} {points:?}: exact {exact:08b}, sure {sure:08b}"
                );
                if at_plane {
                    plane_passed += exact.count_ones();
                    plane_sure += sure.count_ones();
                } else {
                    inside += exact.count_ones();
                    sure_inside += sure.count_ones();
                }
            }
        }
        // Both sides of the surface and of the plane were tried, and most pixels that pass
        // are decided without the exact test.
        assert!(inside > 15_000 && sure_inside > 0, "{inside} {sure_inside}");
        assert!(
            plane_passed > 15_000 && plane_sure * 2 > plane_passed,
            "{plane_passed} {plane_sure}"
        );
    }

    /// Cases at the edges of the f32 arithmetic, where only the exact test may pass a pixel:
    /// a slack beyond the bound's size (a point exactly at the f32 centre of a needle 1e-9
    /// wide whose f64 centre it misses), and an offset so small that the f32 cosine
    /// underflows to −0 (behind the VPL in f64).
    #[test]
    fn edge_cases_are_left_to_the_exact_test() {
        let c = DVec3::new(0.0, 0.1, 0.0);
        let needle = PixelTest::new(DVec3::ZERO, DVec3::ZERO, c, DVec3::X, 1.0, 1e-9);
        let filter = Filter::of(&needle).expect("within the filter's domain");
        let (exact, maybe, sure) = classified(&filter, &needle, [c.as_vec3(); 8]);
        assert_eq!((exact, maybe, sure), (0, 255, 0));
        let n = Vec3::new(0.3, 0.9539, 0.0).normalize().as_dvec3();
        let sphere = PixelTest::new(DVec3::ZERO, n, DVec3::ZERO, DVec3::X, 1.0, 1.0);
        let filter = Filter::of(&sphere).expect("within the filter's domain");
        let tiny = Vec3::new(-f32::from_bits(1), 0.0, 0.0);
        let (exact, maybe, sure) = classified(&filter, &sphere, [tiny; 8]);
        assert_eq!((exact, maybe, sure), (0, 255, 0));
    }

    /// For bounds of eccentricity up to 10 near the origin, the filter passes no point 1e-3
    /// outside the surface and surely passes every point 1e-3 inside: it is only as loose
    /// as its rounding needs.
    #[test]
    fn the_filter_is_tight_for_round_bounds() {
        let mut rng = Rng(5);
        for _ in 0..5_000 {
            let test = bound(&mut rng, 1.0, 1.0);
            let filter = Filter::of(&test).expect("within the filter's domain");
            let outside = [(); 8].map(|_| point(&test, unit(&mut rng) * 1.001));
            assert_eq!(classified(&filter, &test, outside), (0, 0, 0), "{test:?}");
            let inside = [(); 8].map(|_| point(&test, unit(&mut rng) * 0.999));
            assert_eq!(
                classified(&filter, &test, inside),
                (255, 255, 255),
                "{test:?}"
            );
        }
    }

    /// Bounds beyond the filter's domain take the exact test at every pixel.
    #[test]
    fn extreme_semi_axes_have_no_filter() {
        let mut rng = Rng(3);
        for across in [1e-19, 1e19, f64::INFINITY, 0.0] {
            let b = bound(&mut rng, 1.0, 1.0);
            let along = b.semi_axes()[0];
            let test = PixelTest::new(b.position, b.normal, b.center, b.axis, along, across);
            assert!(Filter::of(&test).is_none(), "{across}");
        }
    }

    /// The slots counted along a row are those of each pixel divided out, and distinct: K
    /// from 1 to 9, widths not multiples of K or of a chunk.
    #[test]
    fn slots_along_a_row_are_each_pixels_own() {
        for (k, width) in [(1, 37), (3, 50), (8, 960), (9, 203)] {
            let layout = PixelRows::empty(width, 1, k).layout;
            let along: Vec<_> = layout.slots().take(width as usize).collect();
            let each: Vec<_> = (0..width).map(|x| layout.slot(x)).collect();
            assert_eq!(along, each, "K {k}, width {width}");
            let distinct: std::collections::HashSet<_> = each.iter().collect();
            assert_eq!(distinct.len(), width as usize, "K {k}, width {width}");
            assert!(each.iter().all(|&(c, _)| c < layout.screen_row()));
        }
    }

    /// Each cell's box is the box of exactly the samples of the pixels in it
    /// ([`CellBoxes::of_pixel`], and [`CellBoxes::of_row`] the same cells), empty where none
    /// has one, and the numbers of the cells of every subregion's image ([`CellBoxes::id`])
    /// are distinct and within the boxes: images whose sides are not multiples of K or of a
    /// cell, K from 1 to 9.
    #[test]
    fn cell_boxes_hold_their_pixels_samples() {
        let mut rng = Rng(13);
        for (k, width, height) in [(1, 37, 5), (3, 50, 13), (4, 33, 31), (9, 203, 40)] {
            let mut rows = PixelRows::empty(width, height, k);
            let mut positions = vec![None; (width * height) as usize];
            let (layout, screen_rows) = rows.screen_rows_mut();
            let rows_of: Vec<_> = screen_rows.collect();
            for (y, row) in rows_of.into_iter().enumerate() {
                for x in 0..width {
                    if rng.range64(0.0, 1.0) < 0.8 {
                        let p = Vec3::new(
                            rng.range64(-2.0, 2.0) as f32,
                            rng.range64(-2.0, 2.0) as f32,
                            rng.range64(-2.0, 2.0) as f32,
                        );
                        Layout::set(row, layout.slot(x), p);
                        positions[y * width as usize + x as usize] = Some(p);
                    }
                }
            }
            let cells = rows.cell_boxes();
            let mut want = vec![[Vec3::INFINITY, Vec3::NEG_INFINITY]; cells.len()];
            for y in 0..height {
                for x in 0..width {
                    if let Some(p) = positions[(y * width + x) as usize] {
                        let b = &mut want[cells.of_pixel(x, y)];
                        *b = [b[0].min(p), b[1].max(p)];
                    }
                }
            }
            let boxes: Vec<[Vec3; 2]> = (0..cells.len()).map(|id| cells.box_of(id)).collect();
            assert_eq!(boxes, want, "K {k}, {width}x{height}");
            for y in 0..height {
                let along: Vec<usize> = cells.of_row(y).take(width as usize).collect();
                let each: Vec<usize> = (0..width).map(|x| cells.of_pixel(x, y)).collect();
                assert_eq!(along, each, "K {k}, {width}x{height}, row {y}");
            }
            let mut ids = std::collections::HashSet::new();
            let il = slc_core::Interleaving { k, seed: 0 };
            for (sx, sy) in (0..k).flat_map(|sy| (0..k).map(move |sx| (sx, sy))) {
                let [w, h] = il.subregion_size(width, height, [sx, sy]);
                for (cx, cy) in (0..h.div_ceil(CELL))
                    .flat_map(|cy| (0..w.div_ceil(CELL)).map(move |cx| (cx, cy)))
                {
                    let id = cells.id([sx, sy], [cx, cy]);
                    assert!(id < cells.len() && ids.insert(id), "K {k}: cell {id}");
                }
            }
        }
    }

    /// The lists of the rows' tests equal those of the exact test on every pixel of every
    /// rectangle, at interleavings 1, 3 and 8 (the VPLs gathered by subregion) and 20 (more
    /// subregions than VPLs: taken as given) with rectangles of every width (partial chunks
    /// at both ends, one pixel, the whole row), samples missing and extreme bounds. The
    /// VPLs lie in random subregions and come in no order of their indices, so each pixel's
    /// list must keep the order of `scattered` itself.
    #[test]
    fn rows_give_the_exact_tests_lists() {
        let mut rng = Rng(11);
        for (k, width, height) in [(1, 37, 5), (3, 50, 13), (8, 203, 40), (20, 400, 90)] {
            let mut positions = vec![None; (width * height) as usize];
            for p in positions.iter_mut() {
                if rng.range64(0.0, 1.0) < 0.9 {
                    *p = Some(Vec3::new(
                        rng.range64(-2.0, 2.0) as f32,
                        rng.range64(-2.0, 2.0) as f32,
                        rng.range64(-2.0, 2.0) as f32,
                    ));
                }
            }
            let mut rows = PixelRows::empty(width, height, k);
            let (layout, screen_rows) = rows.screen_rows_mut();
            screen_rows.enumerate().for_each(|(y, row)| {
                for x in 0..width {
                    if let Some(p) = positions[y * width as usize + x as usize] {
                        Layout::set(row, layout.slot(x), p);
                    }
                }
            });
            let mut scattered = Vec::new();
            for index in 0..300u32 {
                // At random (some subregions left empty), as a VPL's is a hash of its id.
                let mut any = || (rng.range64(0.0, f64::from(k)) as u32).min(k - 1);
                let subregion = [any(), any()];
                let [sw, sh] =
                    slc_core::Interleaving { k, seed: 0 }.subregion_size(width, height, subregion);
                let axis = unit(&mut rng);
                let r = rng.range64(0.05, 3.0);
                let across = match index % 50 {
                    0 => 1e-20,
                    _ => r * rng.range64(0.1, 1.0),
                };
                let test = PixelTest::new(
                    (unit(&mut rng) * rng.range64(0.0, 2.0))
                        .as_vec3()
                        .as_dvec3(),
                    unit(&mut rng),
                    axis * r * rng.range64(-0.5, 0.5),
                    axis,
                    r,
                    across,
                );
                let (i0, j0) = (
                    (rng.range64(0.0, 1.0) * f64::from(sw)) as u32,
                    (rng.range64(0.0, 1.0) * f64::from(sh)) as u32,
                );
                let (i1, j1) = match index % 4 {
                    0 => (i0, j0),
                    1 => (sw - 1, sh - 1),
                    _ => (
                        (i0 + (rng.range64(0.0, 20.0) as u32)).min(sw - 1),
                        (j0 + (rng.range64(0.0, 5.0) as u32)).min(sh - 1),
                    ),
                };
                let [i0, j0] = if index % 7 == 0 { [0, 0] } else { [i0, j0] };
                scattered.push(Scattered {
                    index,
                    subregion,
                    test,
                    pixels: [i0, j0, i1, j1],
                });
            }
            // In no order of their indices: each pixel's list keeps the order of `scattered`.
            for i in (1..scattered.len()).rev() {
                let j = (rng.range64(0.0, (i + 1) as f64) as usize).min(i);
                scattered.swap(i, j);
            }
            let pixels = (width * height) as usize;
            let mut got = Bands::new(pixels);
            rows.test(&scattered, &mut got);
            // The portable lanes, the VPLs in their own order (subregions interleaved).
            let mut plain = Bands::new(pixels);
            let in_order: Vec<&Scattered> = scattered.iter().collect();
            test_lanes::<F8>(&rows, &in_order, &mut plain);
            let mut want = Bands::new(pixels);
            for s in &scattered {
                let [i0, j0, i1, j1] = s.pixels;
                for j in j0..=j1 {
                    for i in i0..=i1 {
                        let p = (s.subregion[1] + k * j) * width + s.subregion[0] + k * i;
                        let x = positions[p as usize].unwrap_or(Vec3::NAN);
                        if s.test.contains(x) {
                            want.push(p, s.index);
                        }
                    }
                }
            }
            let want = lists(&[want], pixels).unwrap();
            assert!(want.indices.len() > 100, "{}", want.indices.len());
            assert_eq!(lists(&[got], pixels).unwrap(), want, "k {k}");
            assert_eq!(lists(&[plain], pixels).unwrap(), want, "k {k}");
        }
    }
}
