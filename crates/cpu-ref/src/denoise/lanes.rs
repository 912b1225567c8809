//! The two passes of the filter over the padded planes, in AVX-512 registers (sixteen lanes)
//! or AVX2 registers (eight) where the CPU has them and in plain arrays of eight lanes
//! elsewhere (the same operations, so the same bits).
use super::guide::{Guide, HORIZONTAL, REFLECTANCE, VALUE, VECTOR};
use super::taps::{filter, Centre, Kernel, Row};
use super::STRIP;
use glam::Vec3;
use slc_bounds::lanes::F8;

/// A width of lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Width {
    /// Plain arrays of eight lanes.
    Arrays,
    /// Eight lanes in AVX2 registers.
    Avx2,
    /// Sixteen lanes in AVX-512 registers.
    Avx512,
}

impl Width {
    /// Whether this CPU has the instructions of these lanes.
    fn on_cpu(self) -> bool {
        match self {
            Width::Arrays => true,
            #[cfg(target_arch = "x86_64")]
            Width::Avx2 => std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(target_arch = "x86_64")]
            Width::Avx512 => std::arch::is_x86_feature_detected!("avx512f"),
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }
}

/// The lanes the passes run in: a [`Width`] this CPU has (its one constructor checks).
#[derive(Clone, Copy, Debug)]
pub(super) struct Lanes(Width);

impl Lanes {
    /// The widest lanes this CPU has, but no wider than `cap`.
    pub(super) fn at_most(cap: Width) -> Self {
        let widths = [Width::Avx512, Width::Avx2, Width::Arrays];
        let widest = widths.into_iter().find(|&w| w <= cap && w.on_cpu());
        Lanes(widest.unwrap_or(Width::Arrays))
    }
}

/// The horizontal pass over the padded row `row` (its guide and values filled): the
/// filtered demodulated values into its `HORIZONTAL` planes, 0 where there is no surface.
pub(super) fn horizontal(lanes: Lanes, guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    match lanes.0 {
        // SAFETY (both): `Lanes` holds a width the CPU has.
        #[cfg(target_arch = "x86_64")]
        Width::Avx512 => unsafe { horizontal_avx512(guide, kernel, row) },
        #[cfg(target_arch = "x86_64")]
        Width::Avx2 => unsafe { horizontal_avx2(guide, kernel, row) },
        _ => horizontal_in::<F8>(guide, kernel, row),
    }
}

// Every width's vectors tile the rows, which are padded to whole vectors of `VECTOR`.
const _: () = assert!(VECTOR.is_multiple_of(<F8 as Row>::N));
#[cfg(target_arch = "x86_64")]
const _: () = assert!(VECTOR.is_multiple_of(<slc_bounds::lanes_avx::A8 as Row>::N));
#[cfg(target_arch = "x86_64")]
const _: () = assert!(VECTOR.is_multiple_of(<slc_bounds::lanes_avx512::A16 as Row>::N));

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn horizontal_avx2(guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    horizontal_in::<slc_bounds::lanes_avx::A8>(guide, kernel, row);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn horizontal_avx512(guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    horizontal_in::<slc_bounds::lanes_avx512::A16>(guide, kernel, row);
}

#[inline(always)]
fn horizontal_in<L: Row>(guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    let (r, s) = (guide.radius, guide.stride);
    for x0 in (0..guide.width).step_by(L::N) {
        let centre = Centre::<L>::load(row, s, r + x0);
        // Tap k of lane i reads pixel x0 + i + k − r, at x0 + i + k in the padded row.
        let v = filter(kernel, &centre, VALUE, s, |k| (&*row, x0 + k));
        let surface = centre.depth.le(L::splat(f32::INFINITY));
        for (c, v) in v.into_iter().enumerate() {
            let at = (HORIZONTAL + c) * s + r + x0;
            L::select(surface, v, L::splat(0.0)).store(&mut row[at..]);
        }
    }
}

/// The vertical pass for the image rows from `y0` on, `band` their output pixels (holding
/// the image's pixels): each pixel with a surface becomes its filtered value times its
/// reflectance.
pub(super) fn vertical(lanes: Lanes, guide: &Guide, kernel: &Kernel, y0: usize, band: &mut [Vec3]) {
    match lanes.0 {
        // SAFETY (both): `Lanes` holds a width the CPU has.
        #[cfg(target_arch = "x86_64")]
        Width::Avx512 => unsafe { vertical_avx512(guide, kernel, y0, band) },
        #[cfg(target_arch = "x86_64")]
        Width::Avx2 => unsafe { vertical_avx2(guide, kernel, y0, band) },
        _ => vertical_in::<F8>(guide, kernel, y0, band),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn vertical_avx2(guide: &Guide, kernel: &Kernel, y0: usize, band: &mut [Vec3]) {
    vertical_in::<slc_bounds::lanes_avx::A8>(guide, kernel, y0, band);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn vertical_avx512(guide: &Guide, kernel: &Kernel, y0: usize, band: &mut [Vec3]) {
    vertical_in::<slc_bounds::lanes_avx512::A16>(guide, kernel, y0, band);
}

#[inline(always)]
fn vertical_in<L: Row>(guide: &Guide, kernel: &Kernel, y0: usize, band: &mut [Vec3]) {
    let (w, r, s) = (guide.width, guide.radius, guide.stride);
    let row_len = guide.row_len();
    let padded = |y: usize| &guide.rows[y * row_len..(y + 1) * row_len];
    for strip in (0..w).step_by(STRIP) {
        for (dy, out) in band.chunks_mut(w).enumerate() {
            let y = y0 + dy;
            let centre_row = padded(r + y);
            for x0 in (strip..(strip + STRIP).min(w)).step_by(L::N) {
                let centre = Centre::<L>::load(centre_row, s, r + x0);
                // Tap k reads image row y + k − r, padded row y + k.
                let v = filter(kernel, &centre, HORIZONTAL, s, |k| (padded(y + k), r + x0));
                let mut flat = [0.0f32; 3 * VECTOR];
                for (c, v) in v.into_iter().enumerate() {
                    v.store(&mut flat[c * L::N..]);
                }
                let reflectance =
                    |i: usize, c: usize| centre_row[(REFLECTANCE + c) * s + r + x0 + i];
                for i in 0..(w - x0).min(L::N) {
                    if !reflectance(i, 0).is_nan() {
                        let v = Vec3::new(flat[i], flat[L::N + i], flat[2 * L::N + i]);
                        let f = Vec3::new(reflectance(i, 0), reflectance(i, 1), reflectance(i, 2));
                        out[x0 + i] = v * f;
                    }
                }
            }
        }
    }
}
