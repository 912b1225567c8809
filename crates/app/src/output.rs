//! Writing images: linear float EXR and sRGB PNG.
use crate::out_dir::OutDir;
use slc_core::Image;
use std::path::Path;

/// Writes a linear-RGB float EXR (no exposure, no tone map).
pub fn write_exr(path: &Path, image: &Image) -> Result<(), String> {
    let w = image.width as usize;
    exr::prelude::write_rgb_file(path, w, image.height as usize, |x, y| {
        let p = image.pixels[y * w + x];
        (p.x, p.y, p.z)
    })
    .map_err(|e| format!("EXR: {e}"))
}

/// The sRGB opto-electronic transfer function of a linear value clamped to [0, 1].
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = if c.is_finite() {
        c.clamp(0.0, 1.0)
    } else {
        0.0
    };
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// An 8-bit sRGB image of a linear image scaled by 2^`exposure`, values clamped to [0, 1]
/// (like the reference previews at exposure 0).
pub fn to_srgb8(image: &Image, exposure: f32) -> image::RgbImage {
    let scale = exposure.exp2();
    let to8 = |c: f32| (linear_to_srgb(c * scale) * 255.0 + 0.5) as u8;
    let mut out = image::RgbImage::new(image.width, image.height);
    for (o, p) in out.pixels_mut().zip(&image.pixels) {
        *o = image::Rgb([to8(p.x), to8(p.y), to8(p.z)]);
    }
    out
}

/// Writes an 8-bit sRGB PNG of a linear image (see [`to_srgb8`]).
pub fn write_png(path: &Path, image: &Image, exposure: f32) -> Result<(), String> {
    to_srgb8(image, exposure)
        .save(path)
        .map_err(|e| format!("PNG: {e}"))
}

/// The files of a frame in the folder `dir` (empty: the top): [`write_frame`]'s, its
/// `layers.exr` and its `report.json`.
pub fn frame_files(dir: &str) -> Vec<std::path::PathBuf> {
    ["direct", "indirect", "total"]
        .iter()
        .flat_map(|n| [format!("{n}.exr"), format!("{n}.png")])
        .chain(["layers.exr".into(), "report.json".into()])
        .map(|f| Path::new(dir).join(f))
        .collect()
}

/// Stages a frame's files in `out` under the relative folder `dir` (empty: the top):
/// `direct`, `indirect` and `total`, each as EXR and PNG (at `exposure`, in stops), after
/// checking that every pixel is finite; returns the images by name (total included) for the
/// report.
pub fn write_frame<'a>(
    out: &mut OutDir,
    dir: &str,
    exposure: f32,
    direct: &'a Image,
    indirect: &'a Image,
    total: &'a Image,
) -> Result<[(&'static str, &'a Image); 3], String> {
    let images = [("direct", direct), ("indirect", indirect), ("total", total)];
    for (name, img) in images {
        img.check_finite(name).map_err(|e| e.to_string())?;
    }
    for (name, img) in images {
        let at = |ext: &str| Path::new(dir).join(format!("{name}.{ext}"));
        out.write_with(at("exr"), |path| write_exr(path, img))?;
        out.write_with(at("png"), |path| write_png(path, img, exposure))?;
    }
    Ok(images)
}

/// Stages an 8-bit picture (heat map, strip) as a PNG.
pub fn write_rgb8(
    out: &mut OutDir,
    relative: &str,
    picture: &image::RgbImage,
) -> Result<(), String> {
    out.write_with(relative, |path| picture.save(path))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Reads a linear-RGB EXR (the first RGB layer) into an image.
    fn read_exr(path: &Path) -> Result<Image, String> {
        use exr::prelude::*;
        use glam::Vec3;
        let img = read_first_rgba_layer_from_file(
            path,
            |res, _| (res.width(), vec![Vec3::ZERO; res.width() * res.height()]),
            |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b)
            },
        )
        .map_err(|e| format!("{}: cannot read EXR: {e}", path.display()))?;
        let size = img.layer_data.size;
        let (_, pixels) = img.layer_data.channel_data.pixels;
        Ok(slc_core::Image {
            width: size.width() as u32,
            height: size.height() as u32,
            pixels,
        })
    }

    #[test]
    fn exr_round_trip_is_exact() {
        let mut img = Image::new(3, 2);
        img.pixels[4] = Vec3::new(0.25, 4.5, 1e-7);
        let path = std::env::temp_dir().join(format!("slc-exr-{}.exr", std::process::id()));
        write_exr(&path, &img).unwrap();
        let back = read_exr(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!(back, img);
    }

    #[test]
    fn srgb_curve() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((linear_to_srgb(0.214) - 0.5).abs() < 2e-3);
        assert_eq!(linear_to_srgb(f32::NAN), 0.0);
    }
}
