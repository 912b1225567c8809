//! Decoding of image files (PNG, JPEG) into linear RGB [`Texture`]s, shared by the loaders.
use crate::texture::{srgb_to_linear, Texture};
use glam::Vec3;
use std::io::Cursor;
use std::path::Path;
use std::sync::OnceLock;

/// How the values stored in an image file relate to linear values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Encoding {
    /// sRGB-encoded colour (glTF base colour, OBJ `map_Kd`).
    Srgb,
    /// Values stored linearly (glTF metallic-roughness and normal maps).
    Linear,
    /// The alpha channel (linear; 1 where the image has none), stored in all three channels:
    /// the coverage of a glTF cut-out mask.
    Alpha,
    /// The alpha channel where the image has one, else its first (grey) channel, linear, in
    /// all three channels: the coverage of an OBJ `map_d`.
    Coverage,
}

/// Decodes an encoded image (format guessed from its content) into a texture named `name`:
/// its RGB, or its alpha channel for [`Encoding::Alpha`]; 8- and 16-bit images are supported.
pub(crate) fn decode_texture(
    bytes: &[u8],
    name: &str,
    encoding: Encoding,
) -> Result<Texture, String> {
    let image = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?
        .decode()
        .map_err(|e| e.to_string())?;
    let (width, height) = (image.width(), image.height());
    let channel = match encoding {
        Encoding::Alpha => Some(3),
        Encoding::Coverage => Some(if image.color().has_alpha() { 3 } else { 0 }),
        Encoding::Srgb | Encoding::Linear => None,
    };
    let texels = match channel {
        Some(k) => {
            let lut = linear_lut();
            image
                .into_rgba16()
                .as_raw()
                .chunks_exact(4)
                .map(|c| Vec3::splat(lut[c[k] as usize]))
                .collect()
        }
        None => {
            let lut = match encoding {
                Encoding::Srgb => srgb_lut(),
                _ => linear_lut(),
            };
            image
                .into_rgb16()
                .as_raw()
                .chunks_exact(3)
                .map(|c| Vec3::new(lut[c[0] as usize], lut[c[1] as usize], lut[c[2] as usize]))
                .collect()
        }
    };
    Ok(Texture {
        name: name.to_string(),
        width,
        height,
        texels,
    })
}

/// Reads and decodes an image file; the texture is named by the file's path.
pub(crate) fn read_texture(path: &Path, encoding: Encoding) -> Result<Texture, String> {
    let bytes =
        crate::file_read::read_capped(path).map_err(|e| format!("cannot read file: {e}"))?;
    decode_texture(&bytes, &path.display().to_string(), encoding)
}

/// Linear values of every 16-bit sRGB code (8-bit codes c map to 257 c exactly).
fn srgb_lut() -> &'static [f32] {
    static LUT: OnceLock<Vec<f32>> = OnceLock::new();
    LUT.get_or_init(|| {
        (0..=u16::MAX)
            .map(|c| srgb_to_linear(f32::from(c) / 65535.0))
            .collect()
    })
}

/// Values of every 16-bit linear code.
fn linear_lut() -> &'static [f32] {
    static LUT: OnceLock<Vec<f32>> = OnceLock::new();
    LUT.get_or_init(|| (0..=u16::MAX).map(|c| f32::from(c) / 65535.0).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2x1 PNG: one black and one mid-grey (sRGB 128) pixel.
    fn png_2x1() -> Vec<u8> {
        let img = image::RgbImage::from_raw(2, 1, vec![0, 0, 0, 128, 128, 128]).unwrap();
        let mut bytes = Vec::new();
        img.write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
            .unwrap();
        bytes
    }

    #[test]
    fn srgb_and_linear_decoding() {
        let t = decode_texture(&png_2x1(), "t", Encoding::Srgb).unwrap();
        assert_eq!((t.width, t.height), (2, 1));
        assert_eq!(t.texels[0], Vec3::ZERO);
        assert!((t.texels[1].x - srgb_to_linear(128.0 / 255.0)).abs() < 1e-6);
        let t = decode_texture(&png_2x1(), "t", Encoding::Linear).unwrap();
        assert!((t.texels[1].y - 128.0 / 255.0).abs() < 1e-6);
        // No alpha channel: fully covered.
        let t = decode_texture(&png_2x1(), "t", Encoding::Alpha).unwrap();
        assert_eq!(t.texels, vec![Vec3::ONE; 2]);
    }

    #[test]
    fn alpha_decoding() {
        let img = image::RgbaImage::from_raw(2, 1, vec![9, 9, 9, 0, 9, 9, 9, 128]).unwrap();
        let mut bytes = Vec::new();
        img.write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
            .unwrap();
        // Coverage 0 and 128/255 in every channel.
        let is_zero_and_half = |t: Texture| {
            t.texels[0] == Vec3::ZERO
                && (t.texels[1] - Vec3::splat(128.0 / 255.0))
                    .abs()
                    .max_element()
                    < 1e-6
        };
        for encoding in [Encoding::Alpha, Encoding::Coverage] {
            assert!(is_zero_and_half(
                decode_texture(&bytes, "t", encoding).unwrap()
            ));
        }
        // A grey map_d without alpha: its grey level.
        let grey = decode_texture(&png_2x1(), "t", Encoding::Coverage).unwrap();
        assert!(is_zero_and_half(grey));
    }

    #[test]
    fn garbage_is_an_error() {
        assert!(decode_texture(b"not an image", "t", Encoding::Srgb).is_err());
        assert!(read_texture(Path::new("/nonexistent/t.png"), Encoding::Srgb).is_err());
    }
}
