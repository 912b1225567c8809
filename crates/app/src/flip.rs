//! Perceptual error: ꟻLIP (Andersson et al. 2020, NVIDIA's `nv-flip`) between two images as
//! a viewer sees them, i.e. the sRGB previews at the chosen exposure (LDR-ꟻLIP), at the
//! library's default 67 pixels per degree (a 0.7 m view of a 24" 4K monitor).
use crate::output::to_srgb8;
use image::RgbImage;
use slc_core::Image;

/// The mean ꟻLIP error of `test` against `reference` (0 = identical, 1 = most different)
/// and the error map in the magma colour map.
pub fn flip(reference: &Image, test: &Image, exposure: f32) -> (f32, RgbImage) {
    let as_flip = |i: &Image| {
        nv_flip::FlipImageRgb8::with_data(i.width, i.height, to_srgb8(i, exposure).as_raw())
    };
    let error = nv_flip::flip(
        as_flip(reference),
        as_flip(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mean = nv_flip::FlipPool::from_image(&error).mean();
    let map = error.apply_color_lut(&nv_flip::magma_lut());
    let picture = RgbImage::from_raw(reference.width, reference.height, map.to_vec())
        .expect("the map has the image's size");
    (mean, picture)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn identical_images_have_no_error_and_a_difference_has_some() {
        let mut a = Image::new(32, 24);
        a.pixels
            .iter_mut()
            .enumerate()
            .for_each(|(i, p)| *p = Vec3::splat((i % 7) as f32 / 7.0));
        let (same, map) = flip(&a, &a, 0.0);
        assert_eq!(same, 0.0);
        assert_eq!((map.width(), map.height()), (32, 24));
        let mut b = a.clone();
        b.pixels[100] = Vec3::new(1.0, 0.0, 0.0);
        let (one, _) = flip(&a, &b, 0.0);
        let mut c = a.clone();
        c.pixels
            .iter_mut()
            .for_each(|p| *p = Vec3::new(1.0, 0.0, 0.0));
        let (all, _) = flip(&a, &c, 0.0);
        assert!(0.0 < one && one < all && all <= 1.0, "{one} {all}");
    }
}
