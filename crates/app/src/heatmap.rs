//! Heat maps in the spirit of the paper's Fig. 9 and 10: brightness is the number of VPLs a
//! pixel is shaded with (full brightness at `max_lights`), colour is the pixel's false
//! discovery rate on a spectrum from blue (0: every listed VPL contributes) to red (1: none does).
use image::{Rgb, RgbImage};

/// Where a heat map is at full brightness.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeatScale {
    /// At this many lights per pixel in every heat map (`--heat-max`), so they compare.
    Fixed(u32),
    /// At each heat map's own largest count (the default): the range its frame spans, so a
    /// frame of 4 to 34 lights per pixel is not black.
    PerFrame,
}

impl HeatScale {
    /// `--heat-max` if given, else each frame's own range.
    pub fn of(heat_max: Option<u32>) -> Self {
        heat_max.map_or(Self::PerFrame, Self::Fixed)
    }

    /// The count at full brightness for a frame with `lights` per pixel (at least 1).
    pub fn full_at(self, lights: &[u32]) -> u32 {
        match self {
            Self::Fixed(max) => max.max(1),
            Self::PerFrame => lights.iter().copied().max().unwrap_or(0).max(1),
        }
    }

    /// How a caption says it.
    pub fn describe(self) -> String {
        match self {
            Self::Fixed(max) => format!("full at {max} VPLs per pixel (--heat-max)"),
            Self::PerFrame => {
                "full at each frame's own maximum, given with it (--heat-max sets one for all)"
                    .into()
            }
        }
    }
}

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

    #[test]
    fn the_scale_is_the_frames_range_unless_fixed() {
        assert_eq!(HeatScale::of(None).full_at(&[4, 34, 12]), 34);
        assert_eq!(HeatScale::of(None).full_at(&[0, 0]), 1);
        assert_eq!(HeatScale::of(Some(256)).full_at(&[4, 34, 12]), 256);
        assert!(HeatScale::PerFrame.describe().contains("own maximum"));
    }
}
