//! The filter's working set: per padded row of the image, its guide (depth and shading
//! normal), its demodulated values, the horizontal pass's output and the reflectance the
//! vertical pass multiplies back, each a plane of `f32` (structure of arrays), so
//! neighbouring pixels are one vector load. Every row is padded with `radius` pixels on each
//! side (and the image with `radius` rows above and below) that have no surface: a tap
//! outside the image reads a pixel without a surface and weighs 0, the filter's `continue`
//! for taps past the border, without a bounds test.
use glam::Vec3;
use rayon::prelude::*;
use slc_core::{GBuffer, GSample, Image};

/// The planes of a padded row, in this order, each `stride` floats long.
pub(super) const DEPTH: usize = 0;
/// The shading normal's x, y and z.
pub(super) const NORMAL: usize = 1;
/// The demodulated values (red, green, blue).
pub(super) const VALUE: usize = 4;
/// The horizontal pass's output (red, green, blue).
pub(super) const HORIZONTAL: usize = 7;
/// The reflectance the vertical pass multiplies back (red, green, blue; NaN where there is
/// no surface), so that it does not read the G-buffer's samples again (a hundred bytes a
/// pixel, 216 MB at 1080p, where these planes are twelve).
pub(super) const REFLECTANCE: usize = 10;
/// Planes per padded row.
pub(super) const PLANES: usize = 13;
/// Lanes of the widest vectors the filter runs in (AVX-512's sixteen).
pub(super) const VECTOR: usize = 16;

/// The reflectance the filter divides out and multiplies back: kd + F(1), at least 1e-3.
#[inline]
pub(super) fn reflectance(g: &GSample) -> Vec3 {
    (g.brdf.kd + g.brdf.fresnel.eval(1.0)).max(Vec3::splat(1e-3))
}

/// The padded planes of one image size and radius, kept from frame to frame (about 52 bytes
/// per pixel: 110 MB at 1920x1080, whose first touch costs page faults).
#[derive(Debug, Default)]
pub struct Guide {
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) radius: usize,
    /// Floats per plane row: the padding, the width rounded up to whole vectors of the
    /// widest lanes ([`VECTOR`]), the padding.
    pub(super) stride: usize,
    /// `height + 2 radius` padded rows of `PLANES * stride` floats.
    pub(super) rows: Vec<f32>,
}

impl Guide {
    /// Floats per padded row (all planes).
    pub(super) fn row_len(&self) -> usize {
        PLANES * self.stride
    }

    /// Makes the planes fit a `width` x `height` image and `radius`: the padding rows
    /// without surfaces; kept as they are when the size and radius did not change.
    pub(super) fn fit(&mut self, width: usize, height: usize, radius: usize) {
        if (self.width, self.height, self.radius) == (width, height, radius)
            && !self.rows.is_empty()
        {
            return;
        }
        self.width = width;
        self.height = height;
        self.radius = radius;
        self.stride = radius + width.div_ceil(VECTOR) * VECTOR + radius;
        let row_len = self.row_len();
        self.rows = vec![0.0; row_len * (height + 2 * radius)];
        let (top, rest) = self.rows.split_at_mut(row_len * radius);
        let bottom = &mut rest[row_len * height..];
        for row in top.chunks_mut(row_len).chain(bottom.chunks_mut(row_len)) {
            row[..self.stride].fill(f32::NAN);
        }
    }

    /// Writes image row `y`'s guide, demodulated values and reflectance into its padded row
    /// `row` (depth and reflectance NaN, normal and values 0 where there is no surface, in
    /// the row's padding columns too; the padding rows above and below are `fit`'s, where the
    /// NaN depth gives every tap weight 0).
    pub(super) fn fill_row(&self, row: &mut [f32], samples: &[Option<GSample>], pixels: &[Vec3]) {
        let (r, s) = (self.radius, self.stride);
        row[..VALUE * s + s * 3].fill(0.0);
        row[DEPTH * s..DEPTH * s + s].fill(f32::NAN);
        row[REFLECTANCE * s..(REFLECTANCE + 3) * s].fill(f32::NAN);
        for (x, (g, p)) in samples.iter().zip(pixels).enumerate() {
            let Some(g) = g else {
                continue;
            };
            let i = r + x;
            // At least 1e-3 per channel (`Vec3::max` takes 1e-3 over NaN): never NaN.
            let f = reflectance(g);
            let v = *p / f;
            row[DEPTH * s + i] = g.depth;
            for c in 0..3 {
                row[(NORMAL + c) * s + i] = g.normal[c];
                row[(VALUE + c) * s + i] = v[c];
                row[(REFLECTANCE + c) * s + i] = f[c];
            }
        }
    }
}

/// Fills every padded image row in parallel and runs `then` on each right after (the row is
/// still in cache).
pub(super) fn fill_rows(
    guide: &mut Guide,
    image: &Image,
    gbuffer: &GBuffer,
    then: impl Fn(&Guide, &mut [f32]) + Sync,
) {
    let (w, r) = (guide.width, guide.radius);
    let row_len = guide.row_len();
    let mut rows = std::mem::take(&mut guide.rows);
    let guide_ref = &*guide;
    rows[row_len * r..row_len * (r + guide_ref.height)]
        .par_chunks_mut(row_len)
        .zip(gbuffer.samples.par_chunks(w.max(1)))
        .zip(image.pixels.par_chunks(w.max(1)))
        .for_each(|((row, samples), pixels)| {
            guide_ref.fill_row(row, samples, pixels);
            then(guide_ref, row);
        });
    guide.rows = rows;
}
