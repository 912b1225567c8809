//! The rectangles of eight VPLs' footprints at once: [`Screen::subregion_pixels`] of each
//! lane, the same f64 operations in AVX lanes where the CPU has them. At a million VPLs the
//! scatter forms half a million rectangles a frame, each a chain of f64 subtractions, a
//! division by K, clamps and roundings per side: one VPL at a time that chain took a third
//! of the scatter (Sponza at 480x270 with RSM 1024: 10 of 31 ms of CPU time,
//! docs/many-vpls.md), four lanes share it.
use crate::scatter::Screen;
use slc_bounds::lanes::F8;

/// Eight rectangles `[i0, j0, i1, j1]` of subregion pixels, and the lanes where one is not
/// empty (bit k: lane k).
pub(crate) type Rectangles = ([[u32; 4]; 8], u8);

/// Eight footprints (lane k: `[lo, hi]` of each axis) and the subregion of each, with its
/// image's size.
pub(crate) struct Footprints {
    pub lo: [F8; 2],
    pub hi: [F8; 2],
    pub subregions: [[u32; 2]; 8],
    pub sizes: [[u32; 2]; 8],
}

impl Screen {
    /// Lane k's rectangle is [`Screen::subregion_pixels`] of footprint k in its subregion,
    /// bit for bit; where it is empty, its entry is unspecified (read it only under the
    /// mask). The lanes convert the sides to i32: a subregion image wider or taller than that
    /// (over 2³¹ pixels) takes the scalar code.
    pub(crate) fn rectangles(&self, f: &Footprints) -> Rectangles {
        let fit = f.sizes.iter().flatten().all(|&n| n <= i32::MAX as u32);
        #[cfg(target_arch = "x86_64")]
        if fit && std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (and so AVX), checked just above.
            return unsafe { self.rectangles_avx(f) };
        }
        let mut out = ([[0; 4]; 8], 0);
        for k in 0..8 {
            let lane = |v: &F8| v.0[k];
            let footprint = [f.lo.each_ref().map(lane), f.hi.each_ref().map(lane)];
            if let Some(pixels) = self.subregion_pixels(footprint, f.subregions[k], f.sizes[k]) {
                out.0[k] = pixels;
                out.1 |= 1 << k;
            }
        }
        out
    }

    /// [`Self::rectangles`] in AVX lanes of four f64: each side as `subregion_pixels` forms
    /// it, its clamps as `max` and `min` with the side as the first operand (a NaN first
    /// operand yields the second: 0 for the first pixel, as `f64::clamp` then `as` give) and
    /// its rounding as `ceil` or `floor` of the clamped value, which the scalar code forms
    /// from the truncation. Every side must fit an i32.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn rectangles_avx(&self, f: &Footprints) -> Rectangles {
        use core::arch::x86_64::*;
        use slc_core::PerK;
        let per_k = self.subregions.per_k_operation();
        let stray = _mm256_set1_pd(self.stray);
        let (one, zero, minus_one) = (
            _mm256_set1_pd(1.0),
            _mm256_setzero_pd(),
            _mm256_set1_pd(-1.0),
        );
        let per_k = |x: __m256d| match per_k {
            PerK::Times(inv) => _mm256_mul_pd(x, _mm256_set1_pd(inv)),
            PerK::Over(k) => _mm256_div_pd(x, _mm256_set1_pd(k)),
        };
        let mut out = ([[0; 4]; 8], 0);
        for half in 0..2 {
            let lanes = 4 * half..4 * half + 4;
            let of = |values: [u32; 4]| {
                let [a, b, c, d] = values.map(f64::from);
                _mm256_set_pd(d, c, b, a)
            };
            // Per axis: the first and last pixel (as integral f64 values).
            let mut ends = [[zero; 2]; 2];
            for (axis, ends) in ends.iter_mut().enumerate() {
                let s = of(core::array::from_fn(|k| f.subregions[4 * half + k][axis]));
                let n = of(core::array::from_fn(|k| f.sizes[4 * half + k][axis]));
                let (lo, hi) = (&f.lo[axis].0[lanes.clone()], &f.hi[axis].0[lanes.clone()]);
                // SAFETY: each slice holds the four f32 read.
                let (a, b) = unsafe { (_mm_loadu_ps(lo.as_ptr()), _mm_loadu_ps(hi.as_ptr())) };
                let (a, b) = (_mm256_cvtps_pd(a), _mm256_cvtps_pd(b));
                // ⌈(X0 − stray − 1 − s)/K⌉ clamped to [0, n] (NaN: 0).
                let first = per_k(_mm256_sub_pd(
                    _mm256_sub_pd(_mm256_sub_pd(a, stray), one),
                    s,
                ));
                let first = _mm256_min_pd(_mm256_max_pd(first, zero), n);
                // ⌊(X1 + stray − s)/K⌋ clamped to [−1, n − 1] (NaN: n − 1).
                let last_pixel = _mm256_sub_pd(n, one);
                let last = per_k(_mm256_sub_pd(_mm256_add_pd(b, stray), s));
                let nan = _mm256_cmp_pd::<_CMP_UNORD_Q>(last, last);
                let last = _mm256_blendv_pd(last, last_pixel, nan);
                let last = _mm256_min_pd(_mm256_max_pd(last, minus_one), last_pixel);
                *ends = [_mm256_ceil_pd(first), _mm256_floor_pd(last)];
            }
            let [[i0, i1], [j0, j1]] = ends;
            let filled = _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_LE_OQ>(i0, i1),
                _mm256_cmp_pd::<_CMP_LE_OQ>(j0, j1),
            );
            out.1 |= (_mm256_movemask_pd(filled) as u8) << (4 * half);
            let mut sides = [[0i32; 4]; 4];
            for (side, value) in sides.iter_mut().zip([i0, j0, i1, j1]) {
                // SAFETY: `side` holds the four i32 written.
                unsafe { _mm_storeu_si128(side.as_mut_ptr().cast(), _mm256_cvttpd_epi32(value)) };
            }
            for k in 0..4 {
                out.0[4 * half + k] = sides.map(|side| side[k] as u32);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::Footprints;
    use crate::scatter::Screen;
    use crate::test_rng::Rng;
    use crate::view::CullView;
    use glam::Vec3;
    use slc_bounds::lanes::F8;
    use slc_core::{Camera, Interleaving, Subregions};

    /// A whole number below `n` (at least 1).
    fn below(rng: &mut Rng, n: u32) -> u32 {
        ((rng.f64() * f64::from(n)) as u32).min(n - 1)
    }

    /// One end of a footprint along an image side of `n` pixels split K times: anywhere in
    /// and around the side, NaN, infinite, ±0, huge, or on a subregion pixel's edge (as
    /// `subregion_pixels` forms its sides with `stray`) to within two ulps.
    fn end(rng: &mut Rng, n: u32, k: u32, stray: f64) -> f32 {
        match below(rng, 12) {
            0 => f32::NAN,
            1 => f32::INFINITY,
            2 => f32::NEG_INFINITY,
            3 => 0.0,
            4 => -0.0,
            5 => rng.range(-1e30, 1e30),
            6 | 7 => {
                let edge = (below(rng, n / k + 3) * k + below(rng, k)) as f32 - stray as f32;
                let ulps = below(rng, 5) as i32 - 2;
                f32::from_bits((edge.to_bits() as i32 + ulps) as u32)
            }
            _ => rng.range(-0.2 * n as f32, 1.2 * n as f32),
        }
    }

    /// Every lane's rectangle is `subregion_pixels`' own, or empty where it is: footprints
    /// of every size and place (inside the image, beyond its edges, NaN, infinite, ±0, on a
    /// subregion pixel's edge to the ulp), strays from −0.5 to 1e6, K a power of two and
    /// not, subregion images of every size (0 included, and one wider than an i32).
    #[test]
    fn lanes_give_the_scalar_rectangles() {
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 1.2).unwrap();
        let mut rng = Rng(0x5EC7);
        let (mut filled, mut empty) = (0, 0);
        for case in 0..4000u32 {
            let k = [1, 2, 3, 7, 8, 13, 64][case as usize % 7];
            // Now and then an image wider than an i32 (the scalar code's, then).
            let (w, h) = match case % 50 {
                0 => (3_000_000_000, 1),
                _ => (1 + (case * 37) % 600, 1 + (case * 11) % 300),
            };
            let view = CullView::new(&cam, w, h).unwrap();
            let stray = [-0.5, -0.499_999_9, 0.0, 0.3, 3.0, 1e6][case as usize % 6];
            let il = Interleaving { k, seed: case };
            let screen = Screen::new(&view, w, h, il, stray, 0.05).unwrap();
            let subregions = Subregions::new(il, w, h).unwrap();
            let subs: [[u32; 2]; 8] =
                core::array::from_fn(|_| subregions.of_vpl(below(&mut rng, u32::MAX)));
            let sizes = subs.map(|s| subregions.size(s));
            let (mut lo, mut hi) = ([F8([0.0; 8]); 2], [F8([0.0; 8]); 2]);
            for lane in 0..8 {
                for (axis, n) in [w, h].into_iter().enumerate() {
                    let a = end(&mut rng, n, k, stray);
                    lo[axis].0[lane] = a;
                    hi[axis].0[lane] = match below(&mut rng, 3) {
                        0 => end(&mut rng, n, k, stray),
                        _ => a + rng.range(0.0, 3.0 * k as f32),
                    };
                }
            }
            let footprints = Footprints {
                lo,
                hi,
                subregions: subs,
                sizes,
            };
            let (rects, lanes) = screen.rectangles(&footprints);
            for lane in 0..8 {
                let footprint = [
                    [lo[0].0[lane], lo[1].0[lane]],
                    [hi[0].0[lane], hi[1].0[lane]],
                ];
                let want = screen.subregion_pixels(footprint, subs[lane], sizes[lane]);
                let got = (lanes >> lane & 1 == 1).then_some(rects[lane]);
                assert_eq!(got, want, "case {case}, lane {lane}: {footprint:?}, K {k}");
                match want {
                    Some(_) => filled += 1,
                    None => empty += 1,
                }
            }
        }
        assert!(
            filled > 5000 && empty > 5000,
            "{filled} filled, {empty} empty"
        );
    }
}
