//! Heat maps in the spirit of the paper's Fig. 9 and 10: brightness is the number of VPLs a
//! pixel is shaded with (full brightness at `max_lights`), colour is the pixel's false
//! discovery rate on a spectrum from blue (0: every listed VPL contributes) to red (1: none does).
use image::{Rgb, RgbImage};

/// An HSV colour with full saturation to RGB in [0, 1]; `hue` in degrees.
fn hue_to_rgb(hue: f32, value: f32) -> [f32; 3] {
    let h = (hue.rem_euclid(360.0)) / 60.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    [r * value, g * value, b * value]
}

/// The heat-map colour of a pixel with `lights` listed VPLs and false discovery rate `fdr`.
pub fn heat_colour(lights: u32, fdr: f32, max_lights: u32) -> Rgb<u8> {
    let value = (lights as f32 / max_lights.max(1) as f32).clamp(0.0, 1.0);
    let hue = 240.0
        * (1.0
            - if fdr.is_finite() {
                fdr.clamp(0.0, 1.0)
            } else {
                0.0
            });
    let c = hue_to_rgb(hue, value);
    Rgb(c.map(|v| (v * 255.0 + 0.5) as u8))
}

/// A heat map image from per-pixel light counts and false discovery rates (row-major).
pub fn heat_map(width: u32, height: u32, lights: &[u32], fdr: &[f32], max_lights: u32) -> RgbImage {
    RgbImage::from_fn(width, height, |x, y| {
        let i = (y * width + x) as usize;
        heat_colour(lights[i], fdr[i], max_lights)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_follow_the_legend() {
        assert_eq!(heat_colour(0, 0.5, 256), Rgb([0, 0, 0]));
        assert_eq!(heat_colour(256, 0.0, 256), Rgb([0, 0, 255]));
        assert_eq!(heat_colour(512, 1.0, 256), Rgb([255, 0, 0]));
        let mid = heat_colour(128, 0.5, 256);
        assert!(mid.0[1] > 100 && mid.0[0] < 10 && mid.0[2] < 10, "{mid:?}");
        assert_eq!(heat_colour(10, f32::NAN, 10), Rgb([0, 0, 255]));
    }
}
