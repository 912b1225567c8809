//! The `binned` strategy (docs/many-vpls.md): scatter instead of gather. Each VPL's bound is
//! mapped once to the rectangle of its subregion image's pixels it may cover
//! ([`crate::scatter`]), and each pixel of that rectangle tests its own G-buffer point x
//! against the bound and the sign of ωo·n at the VPL ([`PixelTest`]). A pixel's list is
//! every VPL that passes there, ascending. The cost is the VPLs plus the pixels their
//! rectangles cover, not VPLs × tiles, and no list holds a pair outside its VPL's bound.
//!
//! The guarantee is the tiled strategies': a pair with p > ξ lies inside its VPL's bound
//! (grown by `BOUND_SLACK`) and not behind the VPL, so its pixel lies in the VPL's rectangle
//! (computed in f64 and grown) and passes the test.
//!
//! The VPLs are read once, in their order, a piece at a time (the VPLs, 100+ bytes each,
//! are streamed through the scatter); each piece's scattered bounds then test the pixels of
//! their rectangles subregion by subregion, so one subregion image's positions stay in
//! cache while they are read. The pairs that pass, each pixel's in VPL order, are then
//! sorted by pixel ([`crate::pair_lists`]). A GPU twin gets
//! the same lists by binning each rectangle into the tiles it overlaps, then testing each
//! tile's pixels against its bin (docs/many-vpls.md).
use crate::lists::pixel_count;
use crate::pair_lists::{lists, Bands};
use crate::partition::check;
use crate::pixel_rows::PixelRows;
use crate::scatter::Screen;
use crate::scatter_lanes::scatter;
use crate::view::CullView;
use glam::DVec2;
use rayon::prelude::*;
use slc_bounds::StochasticParams;
use slc_core::{CullError, CullInput, GBuffer, LightLists};

/// VPLs scattered per piece of parallel work.
const VPLS_PER_PIECE: usize = 4096;

/// The lists of `input` by binning (see the module).
pub(crate) fn cull(input: &CullInput) -> Result<LightLists, CullError> {
    let pixels = pixel_count(input.gbuffer)?;
    let il = input.interleaving;
    check(il, input.vpls.len())?;
    let (width, height) = (input.gbuffer.width, input.gbuffer.height);
    if pixels == 0 {
        return Ok(LightLists::default());
    }
    let view = CullView::new(input.camera, width, height)?;
    let receivers = Receivers::new(input.gbuffer, &view, il.k)?;
    let screen = Screen::new(&view, width, height, il, receivers.stray, receivers.near);
    if !input.vpls.is_empty() {
        // δ is checked once here for the lanes, which take it as valid.
        StochasticParams::new(input.delta, 0.5)?;
    }
    // Per piece of VPLs (in order), the (pixel, VPL) pairs that pass, each pixel's in VPL
    // order, by band.
    let pieces = input
        .vpls
        .par_chunks(VPLS_PER_PIECE)
        .enumerate()
        .map_init(
            || Vec::with_capacity(VPLS_PER_PIECE),
            |scattered, (piece, vpls)| {
                let first = (piece * VPLS_PER_PIECE) as u32;
                scatter(&screen, vpls, first, input.delta, scattered)?;
                let mut pairs = Bands::new(pixels);
                receivers.rows.test(scattered, &mut pairs);
                Ok(pairs)
            },
        )
        .collect::<Result<Vec<Bands>, CullError>>()?;
    lists(&pieces, pixels)
}

/// The G-buffer as the scatter reads it: per pixel its sample's world position, in rows of
/// each subregion image ([`PixelRows`]; NaN where it has no sample, which fails every test),
/// with how far any sample's projection strays outside its own pixel and the smallest view
/// depth.
struct Receivers {
    rows: PixelRows,
    stray: f64,
    near: f64,
}

impl Receivers {
    /// Errors on a sample not in front of the camera (as the other strategies do). The
    /// samples are read once, in order, a screen row per piece of work.
    fn new(gbuffer: &GBuffer, view: &CullView, k: u32) -> Result<Self, CullError> {
        let width = gbuffer.width as usize;
        let mut rows = PixelRows::empty(gbuffer.width, gbuffer.height, k);
        let (layout, screen_rows) = rows.screen_rows_mut();
        let (near, stray) = screen_rows
            .zip(gbuffer.samples.par_chunks(width))
            .enumerate()
            .map(|(y, (row, samples))| {
                let (mut near, mut stray) = (f64::INFINITY, 0.0f64);
                for (x, g) in samples.iter().enumerate() {
                    let Some(g) = g else {
                        continue;
                    };
                    let (x, y) = (x as u32, y as f64);
                    let v = view.to_view(g.position);
                    if !(v.z > 0.0 && v.is_finite()) {
                        return Err(CullError::Input(format!(
                            "G-buffer sample of pixel ({x}, {y}) is not in front of the camera \
                             (view depth {})",
                            v.z
                        )));
                    }
                    let at = view.to_screen(DVec2::new(v.x, v.y) / v.z);
                    let corner = DVec2::new(f64::from(x), y);
                    let outside = (corner - at).max(at - corner - 1.0).max_element();
                    layout.set(row, x, g.position);
                    near = near.min(v.z);
                    stray = stray.max(outside);
                }
                Ok((near, stray))
            })
            .try_reduce(
                || (f64::INFINITY, 0.0),
                |a, b| Ok((a.0.min(b.0), a.1.max(b.1))),
            )?;
        Ok(Self { rows, stray, near })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use slc_bounds::{Brdf, Fresnel};
    use slc_core::{Camera, GSample, Interleaving};

    /// A sample behind the camera is an error naming its pixel: the first pixel, and one in a
    /// later screen row, another piece of the receivers' work.
    #[test]
    fn a_sample_behind_the_camera_is_an_error_naming_its_pixel() {
        let camera = Camera::look_at(Vec3::new(0.0, 4.0, 0.0), Vec3::ZERO, Vec3::Z, 1.0).unwrap();
        let brdf = Brdf {
            kd: Vec3::splat(0.5),
            fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
            alpha: 0.3,
            anisotropy: None,
        };
        let sample = |position| {
            Some(GSample {
                position,
                normal: Vec3::Y,
                geometric_normal: Vec3::Y,
                omega_o: Vec3::Y,
                depth: 1.0,
                brdf,
            })
        };
        let (w, h) = (100, 50);
        for (x, y) in [(0, 0), (96, 40)] {
            let mut samples = vec![sample(Vec3::ZERO); (w * h) as usize];
            // Above the camera, which looks down: behind it.
            samples[(y * w + x) as usize] = sample(Vec3::new(0.0, 9.0, 0.0));
            let gbuffer = GBuffer {
                width: w,
                height: h,
                samples,
            };
            let input = CullInput {
                gbuffer: &gbuffer,
                camera: &camera,
                vpls: &[],
                delta: 1e-3,
                interleaving: Interleaving { k: 1, seed: 0 },
            };
            let err = cull(&input).unwrap_err().to_string();
            assert!(
                err.contains(&format!("pixel ({x}, {y}) is not in front of the camera")),
                "{err}"
            );
        }
    }
}
