//! `binned`'s cells: the [`CELL`]² blocks of pixels of each subregion image whose box of
//! samples stands in for their pixels when a VPL's rectangle is large (docs/many-vpls.md,
//! "Large ranges per cell"). The boxes are stored eight cells to a chunk, one plane per
//! coordinate, so that one row of a rectangle's cells is tested eight at a time in f32 lanes
//! ([`CellTest`]). That test is conservative on its own, with a slack for its own rounding:
//! it keeps every cell holding a sample that the exact per-pixel test
//! ([`PixelTest::contains`]) passes.
use crate::pair_lists::Bands;
use crate::pixel_rows::{lanes_within, CELL};
use crate::reach::SIGN_MARGIN;
use crate::rounding::{down, up};
use crate::scatter::{Frame, PixelTest, Scattered, LIMIT};
use glam::{DVec3, Vec3};
use slc_bounds::lanes::{dot, splat_all, Lanes8, Real, F8};

/// Cells per chunk: the lanes of one test.
const LANES: usize = 8;

/// Eight cells' boxes: the lower corners' x, y and z, then the upper ones'. A cell without a
/// sample has the empty box (lower corner +∞, upper −∞), which every test rejects.
type CellChunk = [F8; 6];

/// The box of the samples of every cell of every subregion image, numbered subregion by
/// subregion and row-major within each ([`Self::id`]). Each row of cells is padded with
/// empty cells to whole chunks.
pub(crate) struct CellBoxes {
    /// Cells per row (a multiple of [`LANES`]) and per column of the largest subregion image.
    across: u32,
    down: u32,
    k: u32,
    chunks: Vec<CellChunk>,
}

impl CellBoxes {
    /// The boxes of K x K subregion images of `cells_across` x `down` cells, `box_of(subregion,
    /// cell)` giving each `[lo, hi]` (lo above hi where it has no sample).
    pub(crate) fn new(
        k: u32,
        [cells_across, down]: [u32; 2],
        box_of: impl Fn([u32; 2], [u32; 2]) -> [Vec3; 2] + Sync,
    ) -> Self {
        use rayon::prelude::*;
        let per_row = cells_across.div_ceil(LANES as u32);
        let chunks = (0..k * k * down)
            .into_par_iter()
            .flat_map_iter(|row| {
                let (sub, cy) = (row / down, row % down);
                let subregion = [sub % k, sub / k];
                let box_of = &box_of;
                (0..per_row).map(move |c| {
                    let mut chunk = [F8([f32::INFINITY; LANES]); 6];
                    for plane in &mut chunk[3..] {
                        *plane = F8([f32::NEG_INFINITY; LANES]);
                    }
                    for lane in 0..LANES {
                        let cx = c * LANES as u32 + lane as u32;
                        if cx < cells_across {
                            put(&mut chunk, lane, box_of(subregion, [cx, cy]));
                        }
                    }
                    chunk
                })
            })
            .collect();
        Self {
            across: per_row * LANES as u32,
            down,
            k,
            chunks,
        }
    }

    /// The number of cells, padding included: every [`Self::id`] is below it.
    pub(crate) fn len(&self) -> usize {
        self.chunks.len() * LANES
    }

    /// The number of cell `[cx, cy]` of subregion `[sx, sy]`.
    #[inline]
    pub(crate) fn id(&self, [sx, sy]: [u32; 2], [cx, cy]: [u32; 2]) -> usize {
        let sub = (sy * self.k + sx) as usize;
        (sub * self.down as usize + cy as usize) * self.across as usize + cx as usize
    }

    /// The cells of the pixels x = 0, 1, ... of screen row `y`: pixel x is in column x / K of
    /// subregion x mod K, cell column x / K / [`CELL`] (and y likewise), counted along the row
    /// instead of divided per pixel.
    pub(crate) fn of_row(&self, y: u32) -> impl Iterator<Item = usize> + '_ {
        let k = self.k;
        let (sy, cy) = (y % k, y / k / CELL);
        // Pixel x is column q = x / k of subregion sx = x % k.
        let (mut sx, mut q) = (0, 0);
        std::iter::repeat_with(move || {
            let cell = self.id([sx, sy], [q / CELL, cy]);
            sx += 1;
            if sx == k {
                sx = 0;
                q += 1;
            }
            cell
        })
    }

    /// The cell of screen pixel (x, y), as [`Self::of_row`] counts them along a row (the
    /// tests' reference).
    #[cfg(test)]
    pub(crate) fn of_pixel(&self, x: u32, y: u32) -> usize {
        let k = self.k;
        self.id([x % k, y % k], [x / k / CELL, y / k / CELL])
    }

    /// The box `[lo, hi]` of cell `id`.
    #[cfg(test)]
    pub(crate) fn box_of(&self, id: usize) -> [Vec3; 2] {
        let (chunk, lane) = (&self.chunks[id / LANES], id % LANES);
        let at = |a: usize| Vec3::new(chunk[a].0[lane], chunk[a + 1].0[lane], chunk[a + 2].0[lane]);
        [at(0), at(3)]
    }

    /// Takes out of `scattered` (keeping the others' order) every VPL whose rectangle covers
    /// more than `shared_above` pixels, pushing (cell, VPL) onto `shared` for every cell of
    /// its rectangle that [`CellTest`] keeps, row by row. A pixel whose sample passes the
    /// VPL's [`PixelTest`] lies in the rectangle, so its cell is pushed.
    pub(crate) fn take_large(
        &self,
        scattered: &mut Vec<Scattered>,
        shared_above: u64,
        shared: &mut Bands,
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe { take_large_avx2(self, scattered, shared_above, shared) };
        }
        self.take_large_lanes::<F8>(scattered, shared_above, shared);
    }

    /// [`Self::take_large`] in lanes `L` (no closures: each would be a function without the
    /// kernel's target features).
    #[inline(always)]
    fn take_large_lanes<L: Lanes8>(
        &self,
        scattered: &mut Vec<Scattered>,
        shared_above: u64,
        shared: &mut Bands,
    ) {
        let mut kept = 0;
        for i in 0..scattered.len() {
            let s = scattered[i];
            let [i0, j0, i1, j1] = s.pixels;
            if u64::from(i1 - i0 + 1) * u64::from(j1 - j0 + 1) <= shared_above {
                scattered[kept] = s;
                kept += 1;
                continue;
            }
            let test = CellTest::of(&s.test).lanes::<L>();
            let (x0, x1) = (i0 / CELL, i1 / CELL);
            for cy in j0 / CELL..=j1 / CELL {
                let row = self.id(s.subregion, [0, cy]);
                let (c0, c1) = (x0 as usize / LANES, x1 as usize / LANES);
                let chunks = &self.chunks[row / LANES + c0..=row / LANES + c1];
                for (c, chunk) in (c0..).zip(chunks) {
                    let mut keep = test.keeps(chunk) & lanes_within(c, x0, x1);
                    while keep != 0 {
                        let lane = keep.trailing_zeros() as usize;
                        keep &= keep - 1;
                        shared.push((row + c * LANES + lane) as u32, s.index);
                    }
                }
            }
        }
        scattered.truncate(kept);
    }
}

/// Writes the box `[lo, hi]` into lane `lane` of `chunk`.
fn put(chunk: &mut CellChunk, lane: usize, [lo, hi]: [Vec3; 2]) {
    for (a, v) in lo.to_array().into_iter().chain(hi.to_array()).enumerate() {
        chunk[a].0[lane] = v;
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn take_large_avx2(
    cells: &CellBoxes,
    scattered: &mut Vec<Scattered>,
    shared_above: u64,
    shared: &mut Bands,
) {
    cells.take_large_lanes::<slc_bounds::lanes_avx::A8>(scattered, shared_above, shared);
}

/// A [`PixelTest`] against boxes of samples, in f32, eight boxes at a time: a box is
/// rejected only where no point of it passes the pixel test.
///
/// **The box.** The bound's box (its spheroid's half extents per world axis, grown for
/// `LIMIT`, formed in f64 and rounded outwards to f32) must meet the cell's box.
///
/// **The bound.** With m and h the middle and the half extents of the cell's box, every x
/// of the box lies within |h| of m, so with e = m − q − c (q the VPL, c the bound's centre
/// relative to it, ω_u its axis): x's offset along ω_u from the centre is at least
/// |e·ω_u| − h·|ω_u| and its distance from the axis at least |e − (e·ω_u) ω_u| − |h|. The
/// quadric Q of the pixel test (the spheroid of the GGX paper's eq. 12-15, or the sphere)
/// grows with both, so Q over the box is at least Q of those two lower bounds, and the box is
/// rejected where that exceeds `LIMIT`.
///
/// **The sign.** At every x of the box n·(x − q) ≤ n·(m − q) + |n|·h and |x − q| ≤ |m − q| +
/// |h|; where n·(m − q) + |n|·h < −μ(|m − q| + |h|) (μ the pixel test's margin, the root of
/// the f32 square of `SIGN_MARGIN`), every x lies behind the VPL by more than the margin and
/// the box is rejected.
///
/// **The rounding.** Every quantity above is a sum of products of coordinates, of the
/// rounded unit vectors ω_u and n and of the box, each rounded in f32: its absolute error
/// is at most some 30u (u = 2⁻²⁴) times B = ‖m‖₁ + ‖h‖₁ + ‖q‖₁ + ‖c‖₁. Both lower bounds
/// (along and across the axis) are lowered by ε = 2⁻¹⁵ B, 16 times that, and the sign
/// test's by 2ε (its right side by ε μ at most); the relative rounding of Q (its products
/// and the rounded reciprocals of the semi-axes, some 10u) and of the pixel test's own f64
/// arithmetic is covered by comparing Q with `LIMIT` (1 + 10⁻⁶) rounded up, and μ is taken
/// as μ(1 + 10⁻⁶) rounded up. So ε is some 2 mm in a scene of metres 20 m from its origin.
///
/// Where the bound is beyond f32 (semi-axes outside [1e-18, 1e18] or the centre more than
/// 1e18 from the VPL, as for the pixel test's filter) the quadric rejects nothing; the box
/// and the sign still do. Where B exceeds 2⁶² (a square could overflow) the cell is kept. A
/// cell's box holds no NaN (`PixelRows::cell_boxes` passes over lanes without a sample); an
/// empty box never meets the bound's, which stays within f32's finite range.
#[derive(Clone, Copy, Debug)]
struct CellTest<R = f32> {
    /// The bound's box, rounded outwards.
    lo: [R; 3],
    hi: [R; 3],
    /// The VPL and the bound (its centre 0 where the quadric rejects nothing).
    frame: Frame<R>,
    abs_normal: [R; 3],
    abs_axis: [R; 3],
    /// 1/r_u and 1/r (0 where the quadric rejects nothing).
    inv_along: R,
    inv_across: R,
    /// ‖q‖₁ + ‖c‖₁: the part of B that does not depend on the cell.
    norms: R,
    limit: R,
    margin: R,
}

/// ε / B (see [`CellTest`]).
const SLACK: f32 = 1.0 / 32768.0;

/// B beyond which a cell is kept untested: every length the test squares is at most B, so
/// below 2⁶² no square overflows f32 (whose largest value is near 2¹²⁸).
const HUGE: f32 = (1u64 << 62) as f32;

impl CellTest {
    fn of(test: &PixelTest) -> Self {
        let [along, across] = test.semi_axes();
        let quadric = test.fits_f32();
        // The spheroid's half extents per world axis, grown for `LIMIT` and for the f64
        // rounding of the pixel test, which forms x − q and e − c at the scale of q and c.
        let center = test.position + test.center;
        let a2 = test.axis * test.axis;
        let scale = test.position.abs().max_element() + test.center.abs().max_element();
        let extent = (a2 * (along * along) + (1.0 - a2) * (across * across)).map(f64::sqrt)
            * (LIMIT * (1.0 + 1e-9))
            + DVec3::splat(1e-12 * scale);
        let (lo, hi) = (center - extent, center + extent);
        let mut frame = Frame::of(test);
        let (c, inv) = match quadric {
            true => (test.center, [along.recip() as f32, across.recip() as f32]),
            false => (DVec3::ZERO, [0.0; 2]),
        };
        frame.center = c.as_vec3().to_array();
        Self {
            // Within f32's finite range, so that an empty cell (+∞ below −∞) never meets it;
            // where f64 overflowed (an unbounded extent), the box does not limit.
            lo: lo.to_array().map(|v| match v.is_nan() {
                true => f32::MIN,
                false => down(v).max(f32::MIN),
            }),
            hi: hi.to_array().map(|v| match v.is_nan() {
                true => f32::MAX,
                false => up(v).min(f32::MAX),
            }),
            frame,
            abs_normal: frame.normal.map(f32::abs),
            abs_axis: frame.axis.map(f32::abs),
            inv_along: inv[0],
            inv_across: inv[1],
            norms: (test.position.abs().element_sum() + c.abs().element_sum()) as f32,
            limit: up(LIMIT * (1.0 + 1e-6)),
            margin: up(f64::from(SIGN_MARGIN * SIGN_MARGIN).sqrt() * (1.0 + 1e-6)),
        }
    }

    #[inline(always)]
    fn lanes<L: Lanes8>(&self) -> CellTest<L> {
        CellTest {
            lo: splat_all(&self.lo),
            hi: splat_all(&self.hi),
            frame: self.frame.lanes(),
            abs_normal: splat_all(&self.abs_normal),
            abs_axis: splat_all(&self.abs_axis),
            inv_along: L::splat(self.inv_along),
            inv_across: L::splat(self.inv_across),
            norms: L::splat(self.norms),
            limit: L::splat(self.limit),
            margin: L::splat(self.margin),
        }
    }
}

/// |v|, and max(v, 0), in lanes (NaN stays NaN in the first, becomes 0 in the second).
#[inline(always)]
fn abs<L: Real>(v: L) -> L {
    L::select(v.gt(L::splat(0.0)), v, -v)
}

#[inline(always)]
fn positive<L: Real>(v: L) -> L {
    L::select(v.gt(L::splat(0.0)), v, L::splat(0.0))
}

impl<L: Lanes8> CellTest<L> {
    /// The cells of `chunk` kept (bit k for lane k).
    #[inline(always)]
    fn keeps(&self, chunk: &CellChunk) -> u8 {
        // Written out per axis: no closures inside the lanes' kernels.
        let lo = [L::load(&chunk[0]), L::load(&chunk[1]), L::load(&chunk[2])];
        let hi = [L::load(&chunk[3]), L::load(&chunk[4]), L::load(&chunk[5])];
        let meets = lo[0].le(self.hi[0])
            & lo[1].le(self.hi[1])
            & lo[2].le(self.hi[2])
            & self.lo[0].le(hi[0])
            & self.lo[1].le(hi[1])
            & self.lo[2].le(hi[2]);
        let half_of = L::splat(0.5);
        let m = [
            (lo[0] + hi[0]) * half_of,
            (lo[1] + hi[1]) * half_of,
            (lo[2] + hi[2]) * half_of,
        ];
        let h = [
            (hi[0] - lo[0]) * half_of,
            (hi[1] - lo[1]) * half_of,
            (hi[2] - lo[2]) * half_of,
        ];
        let b = self.norms + abs(m[0]) + abs(m[1]) + abs(m[2]) + h[0] + h[1] + h[2];
        let eps = b * L::splat(SLACK);
        let h_len = dot(h, h).sqrt();
        let f = &self.frame;
        let d = [m[0] - f.q[0], m[1] - f.q[1], m[2] - f.q[2]];
        let c = &f.center;
        let e = [d[0] - c[0], d[1] - c[1], d[2] - c[2]];
        let a = &f.axis;
        let t = dot(e, *a);
        let perp = [e[0] - t * a[0], e[1] - t * a[1], e[2] - t * a[2]];
        let on_axis = positive(abs(t) - dot(h, self.abs_axis) - eps) * self.inv_along;
        let off_axis = positive(dot(perp, perp).sqrt() - h_len - eps) * self.inv_across;
        let reached = (on_axis * on_axis + off_axis * off_axis).le(self.limit);
        let front = dot(f.normal, d) + dot(self.abs_normal, h);
        let reach = dot(d, d).sqrt() + h_len;
        let behind = (-(self.margin * reach)).gt(front + eps + eps);
        // Where B passes 2⁶², a square of a length up to B may overflow (and 0 × ∞ make a
        // NaN where the quadric rejects nothing): kept.
        let huge = b.gt(L::splat(HUGE));
        L::bits(meets & ((reached & !behind) | huge))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{bound, point, unit, varied_bound, Rng};

    /// The cells of `boxes` (as a chunk) kept, in plain and (where the CPU has them) AVX2
    /// lanes, which agree.
    fn kept(test: &PixelTest, boxes: [[Vec3; 2]; 8]) -> u8 {
        let mut chunk: CellChunk = [F8([0.0; 8]); 6];
        for (lane, cell) in boxes.into_iter().enumerate() {
            put(&mut chunk, lane, cell);
        }
        let cell_test = CellTest::of(test);
        let plain = cell_test.lanes::<F8>().keeps(&chunk);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            let avx = unsafe { keeps_avx2(&cell_test, &chunk) };
            assert_eq!(avx, plain, "{test:?}");
        }
        plain
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn keeps_avx2(test: &CellTest, chunk: &CellChunk) -> u8 {
        test.lanes::<slc_bounds::lanes_avx::A8>().keeps(chunk)
    }

    /// A box around `x` reaching up to `size` from it on each side, and points of it: its
    /// corners, `x` and random points inside.
    fn box_around(rng: &mut Rng, x: Vec3, size: f64) -> ([Vec3; 2], Vec<Vec3>) {
        let [below, above] = [(); 2].map(|_| {
            Vec3::new(
                rng.range64(0.0, size) as f32,
                rng.range64(0.0, size) as f32,
                rng.range64(0.0, size) as f32,
            )
        });
        let (lo, hi) = (x - below, x + above);
        let mut points = vec![x];
        for corner in 0..8 {
            let pick = |bit: u32, a: f32, b: f32| if corner & (1 << bit) == 0 { a } else { b };
            points.push(Vec3::new(
                pick(0, lo.x, hi.x),
                pick(1, lo.y, hi.y),
                pick(2, lo.z, hi.z),
            ));
        }
        for _ in 0..8 {
            let t = Vec3::new(rng.f32(), rng.f32(), rng.f32());
            points.push((lo + (hi - lo) * t).clamp(lo, hi));
        }
        ([lo, hi], points)
    }

    /// Every cell holding a point the pixel test passes is kept, in plain and AVX2 lanes:
    /// boxes from single points to the bound's size around points near the surfaces of
    /// bounds from 1e-6 to 1e6 with eccentricities up to 1e5 (needles with far centres one
    /// time in four), from VPLs up to 1e4 times their size from the origin, and boxes near
    /// the VPL's tangent plane, with a normal or without one; bounds beyond the quadric's
    /// domain too. Most of the cells holding no such point are rejected.
    #[test]
    fn keeps_every_cell_holding_a_point_the_pixel_test_passes() {
        let mut rng = Rng(11);
        let (mut holding, mut rejected, mut cells) = (0u32, 0u32, 0u32);
        for round in 0..20_000 {
            let mut test = varied_bound(&mut rng, round);
            if round % 97 == 0 {
                let [along, _] = test.semi_axes();
                test = PixelTest::new(
                    test.position,
                    test.normal,
                    test.center,
                    test.axis,
                    along,
                    [1e-19, 1e19, 0.0][(round / 97) as usize % 3],
                );
            }
            let r = test.semi_axes()[0].max(test.semi_axes()[1]).min(1e6);
            let n = test.normal.normalize_or(DVec3::Z);
            let mut boxes = [[Vec3::ZERO; 2]; 8];
            let mut passing = 0u8;
            for (lane, b) in boxes.iter_mut().enumerate() {
                let x = match lane % 2 {
                    0 => point(&test, unit(&mut rng) * (1.0 + rng.range64(-1e-3, 1e-3))),
                    _ => {
                        let along = unit(&mut rng)
                            .reject_from(n)
                            .normalize_or(n.any_orthonormal_vector());
                        let cos = 1e-5 * rng.range64(-1.1, 1.1);
                        let d = (along * (1.0 - cos * cos).sqrt() + n * cos) * r * rng.f64();
                        (test.position + d).as_vec3()
                    }
                };
                let size = r * 10f64.powf(rng.range64(-9.0, 0.0)) * f64::from(lane > 1);
                let (cell, points) = box_around(&mut rng, x, size);
                *b = cell;
                if points.iter().any(|&p| test.contains(p)) {
                    passing |= 1 << lane;
                }
            }
            let keep = kept(&test, boxes);
            assert_eq!(
                passing & !keep,
                0,
                "{test:?} {boxes:?}: passing {passing:08b}, kept {keep:08b}"
            );
            holding += passing.count_ones();
            rejected += (!keep).count_ones();
            cells += 8;
        }
        assert!(
            holding > 20_000 && rejected * 2 > cells - holding,
            "{holding} {rejected} {cells}"
        );
    }

    /// For bounds of eccentricity up to 10 near the origin, a box of a thousandth of the
    /// bound's size around a point 1.05 times as far from the centre as the surface is
    /// rejected (the slack is only as large as the rounding needs), and so is one inside the
    /// bound but behind the VPL, which is kept in front of it; the empty box never is.
    #[test]
    fn rejects_cells_clearly_outside() {
        let mut rng = Rng(5);
        for _ in 0..5_000 {
            let mut test = bound(&mut rng, 1.0, 1.0);
            let r = test.semi_axes()[0].min(test.semi_axes()[1]);
            let mut boxes = [[Vec3::INFINITY, Vec3::NEG_INFINITY]; 8];
            for b in &mut boxes[..6] {
                let x = point(&test, unit(&mut rng) * 1.05);
                *b = box_around(&mut rng, x, r * 1e-3).0;
            }
            assert_eq!(kept(&test, boxes), 0, "{test:?}");
            // Inside the bound and behind the VPL: the normal pointing away from the box.
            let x = point(&test, unit(&mut rng) * 0.5);
            let away = test.position - x.as_dvec3();
            if away.length() < 0.1 * r {
                continue;
            }
            test.normal = away.normalize();
            let mut behind = [[Vec3::INFINITY, Vec3::NEG_INFINITY]; 8];
            for b in &mut behind[..6] {
                *b = box_around(&mut rng, x, r * 1e-3).0;
            }
            assert_eq!(kept(&test, behind), 0, "{test:?}");
            test.normal = -test.normal;
            assert_eq!(kept(&test, behind), 0b11_1111, "{test:?}");
        }
    }

    /// Cells at the edges of f32, each holding a point the pixel test passes, are kept: a
    /// sphere as large as a range saturated at `f32::MAX` (beyond the quadric's domain) and
    /// a point 2e19 away, whose squares overflow; a centre 2e19 from the VPL and a spheroid
    /// 2e19 across (beyond the domain too); a sphere of 1e18 (within it) and a cell 3.7e19
    /// long, whose half extent's square is just below f32's largest value; a sphere whose VPL and centre lie 2^40 on either side of it, where the pixel
    /// test rounds x − q at the scale of q. The empty cell is rejected even beside the
    /// saturated sphere, whose box is unbounded.
    #[test]
    fn keeps_cells_at_the_edges_of_f32() {
        let (zero, x, y) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let saturated = f64::from(f32::MAX) * (1.0 + 1e-6);
        let far = Vec3::new(0.0, 2e19, 0.0);
        let on_x = |v: f32| Vec3::new(v, 0.0, 0.0);
        let cases = [
            (
                PixelTest::new(zero, y, zero, x, saturated, saturated),
                [far, far],
            ),
            (
                PixelTest::new(zero, y, far.as_dvec3(), x, 1e3, 1e3),
                [far, far],
            ),
            (
                PixelTest::new(zero, y, zero, x, 1e3, 2e19),
                [far * 0.95, far * 0.95],
            ),
            (
                PixelTest::new(zero, y, zero, x, 1e18, 1e18),
                [Vec3::new(0.0, 1e18, 0.0), Vec3::new(0.0, 3.7892e19, 0.0)],
            ),
            (
                PixelTest::new(-x * 2f64.powi(40), x, x * 2f64.powi(40), x, 1.0, 1.0),
                [on_x(1.00005), on_x(1.00005)],
            ),
        ];
        let empty = [Vec3::INFINITY, Vec3::NEG_INFINITY];
        for (test, cell) in cases {
            assert!(test.contains(cell[0]), "{test:?} {cell:?}");
            let mut boxes = [empty; 8];
            boxes[0] = cell;
            assert_eq!(kept(&test, boxes), 1, "{test:?} {cell:?}");
        }
    }
}
