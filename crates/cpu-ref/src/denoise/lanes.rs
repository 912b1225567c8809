//! The two passes of the filter over the padded planes, in AVX2 registers where the CPU has
//! them and in plain arrays of eight lanes elsewhere (the same operations).
use super::guide::{reflectance, Guide, HORIZONTAL, VALUE};
use super::taps::{filter, Centre, Kernel};
use super::STRIP;
use glam::Vec3;
use slc_bounds::lanes::{Lanes8, F8};
use slc_core::GBuffer;

/// The horizontal pass over the padded row `row` (its guide and values filled): the
/// filtered demodulated values into its `HORIZONTAL` planes, 0 where there is no surface.
pub(super) fn horizontal(guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { horizontal_avx2(guide, kernel, row) };
    }
    horizontal_in::<F8>(guide, kernel, row);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn horizontal_avx2(guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    horizontal_in::<slc_bounds::lanes_avx::A8>(guide, kernel, row);
}

#[inline(always)]
fn horizontal_in<L: Lanes8>(guide: &Guide, kernel: &Kernel, row: &mut [f32]) {
    let (r, s) = (guide.radius, guide.stride);
    for x0 in (0..guide.width).step_by(8) {
        let centre = Centre::<L>::load(row, s, r + x0);
        // Tap k of lane i reads pixel x0 + i + k − r, at x0 + i + k in the padded row.
        let v = filter(kernel, &centre, VALUE, s, |k| (&*row, x0 + k));
        let surface = centre.depth.le(L::splat(f32::INFINITY));
        for (c, v) in v.into_iter().enumerate() {
            let at = (HORIZONTAL + c) * s + r + x0;
            row[at..at + 8].copy_from_slice(&L::select(surface, v, L::splat(0.0)).store().0);
        }
    }
}

/// The vertical pass for the image rows from `y0` on, `band` their output pixels (holding
/// the image's pixels): each pixel with a surface becomes its filtered value times its
/// reflectance.
pub(super) fn vertical(
    guide: &Guide,
    kernel: &Kernel,
    gbuffer: &GBuffer,
    y0: usize,
    band: &mut [Vec3],
) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { vertical_avx2(guide, kernel, gbuffer, y0, band) };
    }
    vertical_in::<F8>(guide, kernel, gbuffer, y0, band);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn vertical_avx2(guide: &Guide, kernel: &Kernel, gbuffer: &GBuffer, y0: usize, band: &mut [Vec3]) {
    vertical_in::<slc_bounds::lanes_avx::A8>(guide, kernel, gbuffer, y0, band);
}

#[inline(always)]
fn vertical_in<L: Lanes8>(
    guide: &Guide,
    kernel: &Kernel,
    gbuffer: &GBuffer,
    y0: usize,
    band: &mut [Vec3],
) {
    let (w, r, s) = (guide.width, guide.radius, guide.stride);
    let row_len = guide.row_len();
    let padded = |y: usize| &guide.rows[y * row_len..(y + 1) * row_len];
    for strip in (0..w).step_by(STRIP) {
        for (dy, out) in band.chunks_mut(w).enumerate() {
            let y = y0 + dy;
            let centre_row = padded(r + y);
            for x0 in (strip..(strip + STRIP).min(w)).step_by(8) {
                let centre = Centre::<L>::load(centre_row, s, r + x0);
                // Tap k reads image row y + k − r, padded row y + k.
                let v = filter(kernel, &centre, HORIZONTAL, s, |k| (padded(y + k), r + x0));
                let v = [v[0].store(), v[1].store(), v[2].store()];
                let lanes = (w - x0).min(8);
                let samples = &gbuffer.samples[y * w + x0..y * w + x0 + lanes];
                for (i, g) in samples.iter().enumerate() {
                    if let Some(g) = g {
                        out[x0 + i] = Vec3::new(v[0].0[i], v[1].0[i], v[2].0[i]) * reflectance(g);
                    }
                }
            }
        }
    }
}
