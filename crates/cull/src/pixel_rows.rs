//! The G-buffer positions as `binned`'s per-pixel tests read them, and those tests: each
//! subregion image's rows stored as chunks of eight pixels (x, y and z in lanes, structure of
//! arrays), so the pixels of one row of a bound's rectangle are a few contiguous chunks. A
//! chunk is first tested against the bound in f32, eight pixels at once, with a limit grown
//! by that arithmetic's worst rounding ([`Filter`]); only the pixels it passes take the exact
//! f64 test ([`PixelTest::contains`]), which alone decides. So the lists are those of the
//! exact test on every pixel of the rectangle (`tests` checks both), at a fraction of its
//! cost where rectangles are wider than a few pixels.
use crate::pair_lists::Bands;
use crate::scatter::{PixelTest, Scattered};
use glam::Vec3;
use slc_bounds::lanes::{dot, Lanes8, F8};

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

    /// Writes `position` for pixel `x` into its screen row's chunks (one item of
    /// [`PixelRows::screen_rows_mut`]).
    #[inline]
    pub(crate) fn set(&self, screen_row: &mut [Chunk], x: u32, position: Vec3) {
        let (sx, i) = ((x % self.k) as usize, (x / self.k) as usize);
        let chunk = &mut screen_row[sx * self.chunks_per_row + i / LANES];
        for (plane, v) in chunk.iter_mut().zip(position.to_array()) {
            plane.0[i % LANES] = v;
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
    /// passes the VPL's [`PixelTest`], VPL by VPL, each rectangle row by row, left to right:
    /// the pairs the exact test gives on every pixel, in the same order.
    pub(crate) fn test(&self, scattered: &[Option<Scattered>], pairs: &mut Bands) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe { test_avx2(self, scattered, pairs) };
        }
        test_lanes::<F8>(self, scattered, pairs);
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn test_avx2(rows: &PixelRows, scattered: &[Option<Scattered>], pairs: &mut Bands) {
    test_lanes::<slc_bounds::lanes_avx::A8>(rows, scattered, pairs);
}

/// [`PixelRows::test`] in lanes `L`.
#[inline(always)]
fn test_lanes<L: Lanes8>(rows: &PixelRows, scattered: &[Option<Scattered>], pairs: &mut Bands) {
    let Layout {
        chunks_per_row: per,
        width,
        k,
    } = rows.layout;
    for s in scattered.iter().flatten() {
        let filter = Filter::of(&s.test).map(|f| f.lanes::<L>());
        let [i0, j0, i1, j1] = s.pixels;
        let [sx, sy] = s.subregion;
        let (c0, c1) = (i0 as usize / LANES, i1 as usize / LANES);
        for j in j0..=j1 {
            let y = sy + k * j;
            let first = (y as usize * k as usize + sx as usize) * per;
            let pixel_row = y * width + sx;
            for (c, chunk) in rows.chunks[first + c0..=first + c1].iter().enumerate() {
                let c = c0 + c;
                let mut bits = lanes_within(c, i0, i1);
                if let Some(f) = &filter {
                    bits &= f.passes(chunk);
                }
                while bits != 0 {
                    let lane = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let x = Vec3::new(chunk[0].0[lane], chunk[1].0[lane], chunk[2].0[lane]);
                    if s.test.contains(x) {
                        let i = (c * LANES + lane) as u32;
                        pairs.push(pixel_row + k * i, s.index);
                    }
                }
            }
        }
    }
}

/// The lanes of chunk `c` (pixels 8c..8c+7 of a row) within `[i0, i1]`, as bits.
#[inline(always)]
fn lanes_within(c: usize, i0: u32, i1: u32) -> u8 {
    let base = c * LANES;
    let lo = (i0 as usize).saturating_sub(base);
    let hi = (i1 as usize - base).min(LANES - 1);
    ((0xFFu16 << lo) & (0xFFu16 >> (LANES - 1 - hi))) as u8
}

/// A [`PixelTest`]'s bound in f32, with a limit that passes every pixel the exact test finds
/// inside the bound (the sign test is left to the exact test).
///
/// With d = x − q (q the VPL's position, both f32: the subtraction rounds by at most u|d|,
/// u = 2⁻²⁴), e = d − c (c rounded to f32: at most u|c| more, and u|e| for the
/// subtraction), t = e·ω_u and the quadric Q = |e − t ω_u|²/r² + t²/r_u² of the exact test:
/// for a pixel inside (Q ≤ `LIMIT`, |e| ≤ R = max(r_u, r)), |d| ≤ |e| + |c|, so the error of
/// e is at most 2u(R + |c|)(1 + u); rounding ω_u, forming t and the perpendicular part adds
/// at most about 10u R; and √Q, a norm with the smallest semi-axis r_min as its smallest
/// scale, moves by at most (error of e)/r_min, plus a few u relative from the products, the
/// rounded reciprocals and the sums. [`Filter::of`] takes twice that:
/// √Q_f32 ≤ √LIMIT + 32u(R + |c|)/r_min + 8u. Where an input is so extreme that f32 could
/// overflow or lose the bound (semi-axes outside [1e-18, 1e18]), there is no filter and
/// every pixel takes the exact test.
#[derive(Clone, Copy, Debug)]
struct Filter {
    q: [f32; 3],
    center: [f32; 3],
    axis: [f32; 3],
    inv_along_sq: f32,
    inv_across_sq: f32,
    limit: f32,
}

impl Filter {
    fn of(test: &PixelTest) -> Option<Self> {
        let (along, across) = (
            test.inv_along_sq.recip().sqrt(),
            test.inv_across_sq.recip().sqrt(),
        );
        let (r_max, r_min) = (along.max(across), along.min(across));
        let c = test.center.length();
        let domain = 1e-18..=1e18;
        if !(domain.contains(&r_min) && domain.contains(&r_max) && c <= 1e18) {
            return None;
        }
        let u = f64::from(f32::EPSILON) / 2.0;
        let slack = 32.0 * u * (r_max + c) / r_min + 8.0 * u;
        let limit = (crate::scatter::LIMIT.sqrt() + slack).powi(2);
        Some(Self {
            q: test.position.as_vec3().to_array(),
            center: test.center.as_vec3().to_array(),
            axis: test.axis.as_vec3().to_array(),
            inv_along_sq: test.inv_along_sq as f32,
            inv_across_sq: test.inv_across_sq as f32,
            // Rounded up.
            limit: (limit as f32).next_up(),
        })
    }

    #[inline(always)]
    fn lanes<L: Lanes8>(&self) -> FilterLanes<L> {
        FilterLanes {
            q: splat3(self.q),
            center: splat3(self.center),
            axis: splat3(self.axis),
            inv_along_sq: L::splat(self.inv_along_sq),
            inv_across_sq: L::splat(self.inv_across_sq),
            limit: L::splat(self.limit),
        }
    }
}

/// `v` in every lane.
#[inline(always)]
fn splat3<L: Lanes8>(v: [f32; 3]) -> [L; 3] {
    [L::splat(v[0]), L::splat(v[1]), L::splat(v[2])]
}

/// A [`Filter`]'s values in every lane.
struct FilterLanes<L> {
    q: [L; 3],
    center: [L; 3],
    axis: [L; 3],
    inv_along_sq: L,
    inv_across_sq: L,
    limit: L,
}

impl<L: Lanes8> FilterLanes<L> {
    /// Bit k set where lane k of `chunk` may lie inside the bound (never where it is NaN).
    #[inline(always)]
    fn passes(&self, chunk: &Chunk) -> u8 {
        // No closures: each would be a function without AVX2, calling every intrinsic.
        let [q, c, a] = [&self.q, &self.center, &self.axis];
        let e = [
            (L::load(&chunk[0]) - q[0]) - c[0],
            (L::load(&chunk[1]) - q[1]) - c[1],
            (L::load(&chunk[2]) - q[2]) - c[2],
        ];
        let t = dot(e, *a);
        let perp = [e[0] - t * a[0], e[1] - t * a[1], e[2] - t * a[2]];
        let quadric = dot(perp, perp) * self.inv_across_sq + t * t * self.inv_along_sq;
        L::bits(quadric.le(self.limit))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pair_lists::lists;
    use crate::test_rng::Rng;
    use glam::DVec3;
    use rayon::prelude::*;

    fn unit(rng: &mut Rng) -> DVec3 {
        loop {
            let v = DVec3::new(
                rng.range64(-1.0, 1.0),
                rng.range64(-1.0, 1.0),
                rng.range64(-1.0, 1.0),
            );
            if (0.01..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }

    /// A random bound: semi-axes from 1e-6 to 1e6 with eccentricities up to 10^`ecc` (either
    /// way), the VPL up to 10^`far` times the larger semi-axis from the origin and the centre
    /// off the VPL; the normal zero so that only the bound decides.
    fn bound(rng: &mut Rng, ecc: f64, far: f64) -> PixelTest {
        let along = 10f64.powf(rng.range64(-6.0, 6.0));
        let across = along * 10f64.powf(rng.range64(-ecc, ecc));
        let axis = unit(rng);
        PixelTest {
            position: (unit(rng) * along.max(across) * 10f64.powf(rng.range64(-1.0, far)))
                .as_vec3()
                .as_dvec3(),
            normal: DVec3::ZERO,
            center: axis * along * rng.range64(-1.5, 1.5),
            axis,
            inv_along_sq: (along * along).recip(),
            inv_across_sq: (across * across).recip(),
        }
    }

    /// The f32 point `w` of the unit ball maps to in `test`'s bound.
    fn point(test: &PixelTest, w: DVec3) -> Vec3 {
        let (along, across) = (
            test.inv_along_sq.recip().sqrt(),
            test.inv_across_sq.recip().sqrt(),
        );
        let any = if test.axis.x.abs() < 0.9 {
            DVec3::X
        } else {
            DVec3::Y
        };
        let b1 = test.axis.cross(any).normalize();
        let b2 = test.axis.cross(b1);
        let e = test.axis * (w.x * along) + (b1 * w.y + b2 * w.z) * across;
        (test.position + test.center + e).as_vec3()
    }

    /// Eight points near the surface of `test`'s bound (the unit sphere's points scaled by
    /// 1 + [-`off`, `off`]) as a chunk, and the lanes the exact test passes.
    fn near_surface(rng: &mut Rng, test: &PixelTest, off: f64) -> (Chunk, u8) {
        let mut chunk: Chunk = [F8([0.0; 8]); 3];
        let mut exact = 0u8;
        for lane in 0..8 {
            let x = point(test, unit(rng) * (1.0 + rng.range64(-off, off)));
            for (a, plane) in chunk.iter_mut().enumerate() {
                plane.0[lane] = x[a];
            }
            exact |= u8::from(test.contains(x)) << lane;
        }
        (chunk, exact)
    }

    /// The filter's lanes for `chunk`, plain and (where the CPU has it) AVX2, which agree.
    fn filtered(filter: &Filter, chunk: &Chunk) -> u8 {
        let plain = filter.lanes::<F8>().passes(chunk);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            assert_eq!(unsafe { passes_avx2(filter, chunk) }, plain, "{filter:?}");
        }
        plain
    }

    /// Every f32 point the exact test finds inside passes the filter, in plain and AVX2
    /// lanes: points on and near the surfaces of bounds from 1e-6 to 1e6 with
    /// eccentricities up to 1e5, from VPLs up to 1e4 times their size from the origin.
    #[test]
    fn the_filter_passes_every_point_the_exact_test_passes() {
        let mut rng = Rng(7);
        let mut inside = 0;
        for _ in 0..20_000 {
            let test = bound(&mut rng, 5.0, 4.0);
            let filter = Filter::of(&test).expect("within the filter's domain");
            let (chunk, exact) = near_surface(&mut rng, &test, 1e-4);
            let passed = filtered(&filter, &chunk);
            assert_eq!(
                exact & !passed,
                0,
                "{test:?}: exact {exact:08b}, filter {passed:08b}"
            );
            inside += exact.count_ones();
        }
        assert!(inside > 30_000, "{inside}");
    }

    /// For bounds of eccentricity up to 10 near the origin, the filter rejects points 1e-3
    /// outside the surface: it is only as loose as its rounding needs.
    #[test]
    fn the_filter_is_tight_for_round_bounds() {
        let mut rng = Rng(5);
        for _ in 0..5_000 {
            let test = bound(&mut rng, 1.0, 1.0);
            let filter = Filter::of(&test).expect("within the filter's domain");
            let mut chunk: Chunk = [F8([0.0; 8]); 3];
            for lane in 0..8 {
                let x = point(&test, unit(&mut rng) * 1.001);
                for (a, plane) in chunk.iter_mut().enumerate() {
                    plane.0[lane] = x[a];
                }
            }
            assert_eq!(filtered(&filter, &chunk), 0, "{test:?}");
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn passes_avx2(filter: &Filter, chunk: &Chunk) -> u8 {
        filter.lanes::<slc_bounds::lanes_avx::A8>().passes(chunk)
    }

    /// Bounds beyond the filter's domain take the exact test at every pixel.
    #[test]
    fn extreme_semi_axes_have_no_filter() {
        let mut rng = Rng(3);
        for inv_sq in [1e37, 1e-37, f64::INFINITY] {
            let mut test = bound(&mut rng, 1.0, 1.0);
            test.inv_across_sq = inv_sq;
            assert!(Filter::of(&test).is_none(), "{inv_sq}");
        }
    }

    /// The lists of the rows' tests equal those of the exact test on every pixel of every
    /// rectangle, at interleavings 1, 3 and 8 with rectangles of every width (partial
    /// chunks at both ends, one pixel, the whole row), samples missing and extreme bounds.
    #[test]
    fn rows_give_the_exact_tests_lists() {
        let mut rng = Rng(11);
        for (k, width, height) in [(1, 37, 5), (3, 50, 13), (8, 203, 40)] {
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
                        layout.set(row, x, p);
                    }
                }
            });
            let mut scattered = Vec::new();
            for index in 0..300u32 {
                let subregion = [index % k, (index / k) % k];
                let [sw, sh] =
                    slc_core::Interleaving { k, seed: 0 }.subregion_size(width, height, subregion);
                let mut test = bound(&mut rng, 1.0, 1.0);
                test.position = (unit(&mut rng) * rng.range64(0.0, 2.0))
                    .as_vec3()
                    .as_dvec3();
                let r = rng.range64(0.05, 3.0);
                test.inv_along_sq = (r * r).recip();
                test.inv_across_sq = (r * r * rng.range64(0.01, 1.0)).recip();
                test.center = test.axis * r * rng.range64(-0.5, 0.5);
                test.normal = unit(&mut rng);
                if index % 50 == 0 {
                    test.inv_across_sq = 1e40;
                }
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
            let pixels = (width * height) as usize;
            let mut got = Bands::new(pixels);
            let scattered: Vec<Option<Scattered>> = scattered.into_iter().map(Some).collect();
            rows.test(&scattered, &mut got);
            let mut plain = Bands::new(pixels);
            test_lanes::<F8>(&rows, &scattered, &mut plain);
            let mut want = Bands::new(pixels);
            for s in scattered.iter().flatten() {
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
