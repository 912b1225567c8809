//! The cross bilateral filter that removes the noise of interleaved sampling (paper section 6,
//! after Petschnigg et al. 2004 and Eisemann and Durand 2004): a spatial Gaussian weighted by
//! how alike the neighbours' depth and normal are (the G-buffer guides the filter).
//!
//! The filter works on demodulated radiance: indirect light divided by the pixel's reflectance
//! (kd + F(1), clamped away from zero), and multiplies it back afterwards, so texture detail
//! is not blurred.
mod guide;
mod lanes;
mod taps;

use guide::{fill_rows, Guide};
use lanes::{Lanes, Width};
use rayon::prelude::*;
pub use slc_core::frame::BilateralParams;
use slc_core::{GBuffer, Image};
use taps::Kernel;

/// An image whose size is not the G-buffer's.
#[derive(Debug, thiserror::Error)]
#[error("the filter's image is {image_width}x{image_height} but its G-buffer {width}x{height}")]
pub struct SizeMismatch {
    pub image_width: u32,
    pub image_height: u32,
    pub width: u32,
    pub height: u32,
}

/// Filters `image` guided by `gbuffer`; pixels without a surface stay as they are.
///
/// The kernel is applied separably, a horizontal pass then a vertical one, each weighting its
/// 2r + 1 taps by the spatial Gaussian, the relative depth difference and the normals: 4r + 2
/// taps per pixel instead of (2r + 1)², the usual real-time approximation of the 2-D filter.
/// [`CrossBilateral`] does the same and keeps its working set for the next frame.
pub fn cross_bilateral(
    image: &Image,
    gbuffer: &GBuffer,
    params: BilateralParams,
) -> Result<Image, SizeMismatch> {
    CrossBilateral::default().filter(image, gbuffer, params)
}

/// The cross bilateral filter with its working set (`Guide`, about 52 bytes per pixel),
/// kept from one frame to the next of the same size.
///
/// Both passes run a vector of pixels at a time (`taps`: sixteen in AVX-512 registers or
/// eight in AVX2 registers where the CPU has them, else eight in plain arrays): the
/// horizontal pass row by row, each row's guide and demodulated values written into padded
/// planes and filtered while they are in cache; the vertical pass in bands of [`BAND`] rows
/// and strips of [`STRIP`] columns, so the 2r + 1 rows a strip reads stay in the L2 cache.
/// The output equals the scalar filter's within float rounding (the exponential is
/// `slc_bounds::lanes::exp`, within 2 ulp of `expf`; every other operation is the same, in
/// the same order).
#[derive(Debug, Default)]
pub struct CrossBilateral {
    guide: Guide,
}

/// Image rows per task of the vertical pass.
pub const BAND: usize = 32;
/// Columns per strip of the vertical pass (a multiple of the widest vectors, sixteen).
pub const STRIP: usize = 256;
const _: () = assert!(STRIP.is_multiple_of(guide::VECTOR));

impl CrossBilateral {
    /// [`cross_bilateral`] of `image`, reusing the working set of the last call.
    pub fn filter(
        &mut self,
        image: &Image,
        gbuffer: &GBuffer,
        params: BilateralParams,
    ) -> Result<Image, SizeMismatch> {
        self.filter_in(Width::Avx512, image, gbuffer, params)
    }

    /// [`Self::filter`] in lanes no wider than `widest` (the same bits in every width).
    fn filter_in(
        &mut self,
        widest: Width,
        image: &Image,
        gbuffer: &GBuffer,
        params: BilateralParams,
    ) -> Result<Image, SizeMismatch> {
        let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
        if (image.width, image.height) != (gbuffer.width, gbuffer.height)
            || image.pixels.len() != w * h
            || gbuffer.samples.len() != w * h
        {
            return Err(SizeMismatch {
                image_width: image.width,
                image_height: image.height,
                width: gbuffer.width,
                height: gbuffer.height,
            });
        }
        let r = params.radius as usize;
        let inv_2ss = 1.0 / (2.0 * params.sigma_spatial * params.sigma_spatial);
        let kernel = Kernel {
            spatial: (-(r as i64)..=r as i64)
                .map(|d| (-((d * d) as f32) * inv_2ss).exp())
                .collect(),
            inv_2sd: 1.0 / (2.0 * params.sigma_depth * params.sigma_depth),
            normal_squarings: params.normal_squarings,
        };
        let lanes = Lanes::at_most(widest);
        self.guide.fit(w, h, r);
        fill_rows(&mut self.guide, image, gbuffer, |guide, row| {
            lanes::horizontal(lanes, guide, &kernel, row)
        });
        // Pixels without a surface keep their value; the vertical pass writes the others.
        let mut out = Vec::new();
        image.pixels.par_iter().copied().collect_into_vec(&mut out);
        let guide = &self.guide;
        out.par_chunks_mut(BAND * w.max(1))
            .enumerate()
            .for_each(|(b, band)| lanes::vertical(lanes, guide, &kernel, b * BAND, band));
        Ok(Image {
            width: image.width,
            height: image.height,
            pixels: out,
        })
    }
}

#[cfg(test)]
mod tests;
