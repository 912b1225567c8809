//! Frame buffers: linear RGB images and the G-buffer.
use crate::frame::RenderError;
use glam::Vec3;
use slc_bounds::Brdf;

/// A linear-RGB float image, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Vec3>,
}

impl Image {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![Vec3::ZERO; width as usize * height as usize],
        }
    }

    #[inline]
    pub fn get(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// Mean over all pixels, per channel (accumulated in f64).
    pub fn mean(&self) -> Vec3 {
        let mut s = [0.0f64; 3];
        for p in &self.pixels {
            for c in 0..3 {
                s[c] += p[c] as f64;
            }
        }
        let n = self.pixels.len().max(1) as f64;
        Vec3::new((s[0] / n) as f32, (s[1] / n) as f32, (s[2] / n) as f32)
    }

    /// Pixel-wise sum of two images of the same size.
    pub fn add(&self, other: &Image) -> Image {
        assert_eq!((self.width, self.height), (other.width, other.height));
        let pixels = self
            .pixels
            .iter()
            .zip(&other.pixels)
            .map(|(a, b)| *a + *b)
            .collect();
        Image {
            width: self.width,
            height: self.height,
            pixels,
        }
    }

    /// Adds `other` (of the same size) pixel by pixel in place: the pixels [`Self::add`]
    /// gives, without a new image.
    pub fn add_assign(&mut self, other: &Image) {
        assert_eq!((self.width, self.height), (other.width, other.height));
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            *a += *b;
        }
    }

    /// Root-mean-square error against another image of the same size, over all pixels and channels.
    pub fn rmse(&self, other: &Image) -> f32 {
        assert_eq!((self.width, self.height), (other.width, other.height));
        // In f64: the squares of f32 differences above 1.8e19 overflow f32 (a 1e20 W/sr light
        // gave an infinite RMSE).
        let mut s = 0.0f64;
        for (a, b) in self.pixels.iter().zip(&other.pixels) {
            s += (a.as_dvec3() - b.as_dvec3()).length_squared();
        }
        (s / (3.0 * self.pixels.len().max(1) as f64)).sqrt() as f32
    }

    /// Pixels with a NaN or infinite channel.
    pub fn non_finite_pixels(&self) -> usize {
        self.pixels.iter().filter(|p| !p.is_finite()).count()
    }

    /// `Ok` when every pixel is finite, else [`RenderError::NonFinite`] naming `pass`.
    pub fn check_finite(&self, pass: &'static str) -> Result<(), RenderError> {
        match self.non_finite_pixels() {
            0 => Ok(()),
            count => Err(RenderError::NonFinite {
                pass,
                count,
                pixels: self.pixels.len(),
            }),
        }
    }

    /// Whether every value is finite and non-negative.
    pub fn is_finite_non_negative(&self) -> bool {
        self.pixels
            .iter()
            .all(|p| p.is_finite() && p.min_element() >= 0.0)
    }
}

/// What the camera sees at one pixel: the surface point and its BRDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GSample {
    pub position: Vec3,
    /// Unit shading normal, on the side facing the camera.
    pub normal: Vec3,
    /// Unit geometric normal, on the side facing the camera (lifts shadow-ray origins).
    pub geometric_normal: Vec3,
    /// Unit direction from the surface towards the camera.
    pub omega_o: Vec3,
    /// Linear view depth (distance along the camera's forward axis).
    pub depth: f32,
    pub brdf: Brdf,
}

/// A G-buffer: per pixel, the visible surface, or `None` where the camera sees nothing or the
/// back of a one-sided surface (both black).
#[derive(Clone, Debug, PartialEq)]
pub struct GBuffer {
    pub width: u32,
    pub height: u32,
    pub samples: Vec<Option<GSample>>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_pixels_are_an_error_naming_the_pass_and_count() {
        let mut img = Image::new(4, 2);
        img.check_finite("indirect").unwrap();
        img.pixels[1].x = f32::NAN;
        img.pixels[5].z = f32::INFINITY;
        img.pixels[6] = Vec3::splat(f32::NEG_INFINITY);
        assert_eq!(img.non_finite_pixels(), 3);
        let e = img.check_finite("indirect").unwrap_err().to_string();
        assert!(
            e.contains("indirect pass produced 3 non-finite pixel(s) of 8"),
            "{e}"
        );
    }

    #[test]
    fn add_assign_gives_the_pixels_of_add() {
        let mut a = Image::new(3, 1);
        let mut b = Image::new(3, 1);
        a.pixels = vec![
            Vec3::new(1.0, -0.0, 3e38),
            Vec3::splat(0.1),
            Vec3::splat(-0.0),
        ];
        b.pixels = vec![
            Vec3::new(0.2, -0.0, 3e38),
            Vec3::splat(0.2),
            Vec3::splat(0.0),
        ];
        let sum = a.add(&b);
        a.add_assign(&b);
        let bits = |i: &Image| -> Vec<[u32; 3]> {
            i.pixels
                .iter()
                .map(|p| p.to_array().map(f32::to_bits))
                .collect()
        };
        assert_eq!(bits(&a), bits(&sum));
    }

    #[test]
    fn rmse_of_images_lit_by_the_largest_accepted_light_is_finite() {
        // Radiance of 1e20 W/sr lights: the f32 square of a difference overflows.
        let mut a = Image::new(2, 1);
        let b = Image::new(2, 1);
        a.pixels[0] = Vec3::new(3e20, 0.0, 0.0);
        let e = a.rmse(&b);
        // sqrt((3e20)² / 6)
        assert!((e / (3e20 / 6f32.sqrt()) - 1.0).abs() < 1e-6, "{e}");
        a.pixels[1] = Vec3::splat(f32::MAX);
        assert!(a.rmse(&b).is_finite());
    }
}
