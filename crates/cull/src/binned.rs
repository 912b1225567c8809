//! The `binned` strategy (docs/many-vpls.md): scatter instead of gather. Each VPL's bound is
//! mapped once to the rectangle of its subregion image's pixels it may cover
//! ([`crate::scatter`]), and each pixel of that rectangle tests its own G-buffer point x
//! against the bound and the sign of ωo·n at the VPL ([`PixelTest`]). A pixel's list is
//! every VPL that passes there, ascending (for the VPLs of large rectangles, below, its
//! cell's list stands in). The cost is the VPLs plus the pixels their rectangles cover, not
//! VPLs × tiles, and no pixel's own list holds a pair outside its VPL's bound.
//!
//! The guarantee is the tiled strategies': a pair with p > ξ lies inside its VPL's bound
//! (grown by `BOUND_SLACK`) and not behind the VPL, so its pixel lies in the VPL's rectangle
//! (computed in f64 and grown) and passes the test, and its cell passes the cell's.
//!
//! The VPLs whose rectangles cover more than a tile's worth of pixels ([`LARGE_PIXELS`])
//! are not tested pixel by pixel: each is tested once per 4 x 4 cell of its rectangle
//! against the box of the cell's samples (`cells::CellTest`) and listed in the cell's list,
//! which the cell's pixels share ([`LightLists::shared_list`]). Per pixel they
//! made most of the tests and the pairs; the shading decides them eight receivers at a time.
//!
//! The VPLs are read once, in their order, a piece at a time (the VPLs, 100+ bytes each,
//! are streamed through the scatter); each piece's scattered bounds then test the pixels of
//! their rectangles subregion by subregion, so one subregion image's positions stay in
//! cache while they are read. The pairs that pass, each pixel's in VPL order, are then
//! sorted by pixel ([`crate::pair_lists`]). A GPU twin gets the lists of
//! [`crate::BinnedCuller::per_pixel`] (every VPL tested per pixel) by binning each rectangle
//! into the tiles it overlaps, then testing each tile's pixels against its bin
//! (docs/many-vpls.md).
use crate::cells::CellBoxes;
use crate::lists::pixel_count;
use crate::pair_lists::{self, Bands};
use crate::partition::check;
use crate::pixel_rows::{Layout, PixelRows};
use crate::prefetch::prefetch;
use crate::scatter::Screen;
use crate::scatter_lanes::scatter;
use crate::view::CullView;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use slc_bounds::StochasticParams;
use slc_core::{CullError, CullInput, GBuffer, LightLists, NO_LIST, TILE_SIZE};

/// VPLs scattered per piece of parallel work.
const VPLS_PER_PIECE: usize = 4096;

/// How far ahead in its row [`Receivers::new`] asks for a G-buffer sample (4, 8 and 16
/// measured alike).
const SAMPLES_AHEAD: usize = 8;

/// The lists of `input` by binning (see the module), VPLs whose rectangles cover more than
/// `shared_above` pixels culled per cell ([`LARGE_PIXELS`] by default).
pub(crate) fn cull(input: &CullInput, shared_above: u64) -> Result<LightLists, CullError> {
    let pixels = pixel_count(input.gbuffer)?;
    let il = input.interleaving;
    check(il, input.vpls.len())?;
    let (width, height) = (input.gbuffer.width, input.gbuffer.height);
    if pixels == 0 {
        return Ok(LightLists::default());
    }
    let view = CullView::new(input.camera, width, height)?;
    let receivers = Receivers::new(input.gbuffer, &view, il.k)?;
    let screen = Screen::new(&view, width, height, il, receivers.stray, receivers.near)?;
    if !input.vpls.is_empty() {
        // δ is checked once here for the lanes, which take it as valid.
        StochasticParams::new(input.delta, 0.5)?;
    }
    // The cells' boxes only where a rectangle can be large (not at K = 1024, where there
    // would be K² cells of a pixel or two each).
    let largest = il.subregion_size(width, height, [0, 0]);
    let cells = (u64::from(largest[0]) * u64::from(largest[1]) > shared_above)
        .then(|| receivers.rows.cell_boxes());
    // Per piece of VPLs (in order), the (pixel, VPL) pairs that pass and the (cell, VPL)
    // pairs of the large rectangles, each pixel's or cell's in VPL order, by band.
    let pieces = input
        .vpls
        .par_chunks(VPLS_PER_PIECE)
        .enumerate()
        .map_init(
            || Vec::with_capacity(VPLS_PER_PIECE),
            |scattered, (piece, vpls)| {
                let first = (piece * VPLS_PER_PIECE) as u32;
                scatter(&screen, vpls, first, input.delta, scattered)?;
                let mut shared = Bands::new(cells.as_ref().map_or(0, CellBoxes::len));
                if let Some(cells) = &cells {
                    cells.take_large(scattered, shared_above, &mut shared);
                }
                let mut pairs = Bands::new(pixels);
                receivers.rows.test(scattered, &mut pairs);
                Ok((pairs, shared))
            },
        )
        .collect::<Result<Vec<(Bands, Bands)>, CullError>>()?;
    let (bands, shared): (Vec<Bands>, Vec<Bands>) = pieces.into_iter().unzip();
    let mut lists = pair_lists::lists(&bands, pixels)?;
    if let Some(cells) = &cells {
        let of_cells = pair_lists::lists(&shared, cells.len())?;
        share(&mut lists, of_cells, cells, &receivers.sampled, width)?;
    }
    Ok(lists)
}

/// A VPL whose rectangle covers more pixels than this (a tile's worth of its subregion
/// image) is not tested pixel by pixel: it joins the shared list of every cell of its
/// subregion image (4 x 4 pixels) that its rectangle overlaps and its bound may reach
/// (`CellBoxes::take_large`). Such VPLs are a minority (at 960x540 with RSM 256, 9,348 of
/// 51,468; at RSM 1024, 11,024 of 823,592) but made most of the pixel tests and the pairs
/// (docs/many-vpls.md); the shading tests them against its receivers eight at a time at a
/// fraction of that cost. Of the settings measured (8 x 8 cells above one, two or four
/// tiles, 4 x 4 cells above one or two), 4 x 4 cells above one tile were the fastest whose
/// lists keep within 20 false positives per true positive at RSM 1024 (13 at 960x540; 8 x 8
/// cells above one tile gave 23).
pub(crate) const LARGE_PIXELS: u64 = (TILE_SIZE as u64) * (TILE_SIZE as u64);

/// Appends the cells' lists `of_cells` (one "pixel" per cell, each list ascending) to
/// `lists`, and names each as the shared list of its cell's pixels with a sample (`sampled`:
/// per pixel of the `width`-pixel screen rows, row by row). Nothing changes without entries.
fn share(
    lists: &mut LightLists,
    of_cells: LightLists,
    cells: &CellBoxes,
    sampled: &[bool],
    width: u32,
) -> Result<(), CullError> {
    if of_cells.indices.is_empty() {
        return Ok(());
    }
    let total = lists.indices.len() + of_cells.indices.len();
    if u32::try_from(total).is_err() {
        return Err(CullError::Input(format!(
            "{total} light-list entries exceed 32-bit offsets"
        )));
    }
    let (first_list, first_entry) = (lists.len() as u32, lists.indices.len() as u32);
    lists.indices.extend_from_slice(&of_cells.indices);
    let offsets = &of_cells.offsets[1..];
    lists
        .offsets
        .extend(offsets.iter().map(|o| o + first_entry));
    let of_cell: Vec<u32> = (of_cells.pixel_list.iter())
        .map(|&l| {
            if l == NO_LIST {
                NO_LIST
            } else {
                first_list + l
            }
        })
        .collect();
    let mut shared_list = vec![NO_LIST; sampled.len()];
    shared_list
        .par_chunks_mut(width as usize)
        .zip(sampled.par_chunks(width as usize))
        .enumerate()
        .for_each(|(y, (row, sampled))| {
            for ((list, &sampled), cell) in row.iter_mut().zip(sampled).zip(cells.of_row(y as u32))
            {
                if sampled {
                    *list = of_cell[cell];
                }
            }
        });
    lists.shared_list = shared_list;
    Ok(())
}

/// The G-buffer as the scatter reads it: per pixel its sample's world position, in rows of
/// each subregion image ([`PixelRows`]; NaN where it has no sample, which fails every test),
/// with how far any sample's projection strays outside its own pixel (signed: below 0 where
/// every sample lies inside its pixel, [`CENTRED`] where each is at its centre) and the
/// smallest view depth.
struct Receivers {
    rows: PixelRows,
    /// Per pixel, row by row, whether it has a sample (so the cells' lists are handed out
    /// without reading the G-buffer's samples again).
    sampled: Vec<bool>,
    stray: f64,
    near: f64,
}

/// The stray of a sample at its pixel's centre, the least: 0.5 pixels inside the pixel's
/// edges. With samples at the centres (one per pixel, `slc`'s default), a VPL's rectangle
/// of pixels is the pixels whose centre its footprint covers, where with samples anywhere in
/// their pixel (a stray of 0) it takes every pixel the footprint touches: a pixel more per
/// axis, which at a million VPLs placed 10% more VPLs and made 9% more pixel tests
/// (docs/many-vpls.md, "Rectangles of the pixels' centres").
const CENTRED: f64 = -0.5;

/// Whether a view-space point's projection ([`CullView::to_screen`] of v.xy / v.z) surely
/// lies within a screen rectangle, without a division: with v.z > 0, X = (v.x / v.z) scale +
/// offset lies in [lo, hi] where v.x scale + offset v.z lies in [lo v.z, hi v.z] (per axis).
/// Both forms round by a few ulps of the image's size and of the rectangle's corners (where
/// the test passes, X is near them); the rectangle is shrunk by a margin some 10⁶ times
/// that, so where the test passes, `to_screen`'s own X lies in [lo, hi] too, and so do the
/// differences [`Receivers::new`] forms from it.
struct Projection {
    scale: DVec2,
    offset: DVec2,
    /// The image's width plus height plus 2: the scale of the rounding.
    size: f64,
}

impl Projection {
    fn new(view: &CullView, width: u32, height: u32) -> Self {
        let (scale, offset) = view.screen_map();
        Self {
            scale: DVec2::from(scale),
            offset: DVec2::from(offset),
            size: f64::from(width) + f64::from(height) + 2.0,
        }
    }

    #[inline]
    fn surely_within(&self, v: DVec3, lo: DVec2, hi: DVec2) -> bool {
        let margin = 1e-9 * (self.size + lo.abs().max_element() + hi.abs().max_element());
        let h = DVec2::new(v.x, v.y) * self.scale + self.offset * v.z;
        h.cmpge((lo + margin) * v.z).all() && h.cmple((hi - margin) * v.z).all()
    }
}

impl Receivers {
    /// Errors on a sample not in front of the camera (as the other strategies do). The
    /// samples are read once, in order, a screen row per piece of work.
    fn new(gbuffer: &GBuffer, view: &CullView, k: u32) -> Result<Self, CullError> {
        let width = gbuffer.width as usize;
        let mut rows = PixelRows::empty(gbuffer.width, gbuffer.height, k);
        let mut sampled = vec![false; gbuffer.samples.len()];
        let (layout, screen_rows) = rows.screen_rows_mut();
        let projection = Projection::new(view, gbuffer.width, gbuffer.height);
        let (near, stray) = screen_rows
            .zip(gbuffer.samples.par_chunks(width))
            .zip(sampled.par_chunks_mut(width))
            .enumerate()
            .map(|(y, ((row, samples), sampled))| {
                let (mut near, mut stray) = (f64::INFINITY, CENTRED);
                let slots = layout.slots();
                for (x, ((g, sampled), slot)) in samples.iter().zip(sampled).zip(slots).enumerate()
                {
                    // A hint only, as in the scatter: without it the loop waits on each
                    // sample's first read (docs/many-vpls.md, "The G-buffer read ahead").
                    if let Some(ahead) = samples.get(x + SAMPLES_AHEAD) {
                        prefetch(ahead);
                    }
                    let Some(g) = g else {
                        continue;
                    };
                    *sampled = true;
                    let (x, y) = (x as u32, y as f64);
                    let v = view.to_view(g.position);
                    if !(v.z > 0.0 && v.is_finite()) {
                        return Err(CullError::Input(format!(
                            "G-buffer sample of pixel ({x}, {y}) is not in front of the camera \
                             (view depth {})",
                            v.z
                        )));
                    }
                    let corner = DVec2::new(f64::from(x), y);
                    // Only a projection that may stray further than those before it can
                    // raise the maximum: most lie well inside their pixel.
                    if !projection.surely_within(v, corner - stray, corner + 1.0 + stray) {
                        let at = view.to_screen(DVec2::new(v.x, v.y) / v.z);
                        let outside = (corner - at).max(at - corner - 1.0).max_element();
                        stray = stray.max(outside);
                    }
                    Layout::set(row, slot, g.position);
                    near = near.min(v.z);
                }
                Ok((near, stray))
            })
            .try_reduce(
                || (f64::INFINITY, CENTRED),
                |a, b| Ok((a.0.min(b.0), a.1.max(b.1))),
            )?;
        Ok(Self {
            rows,
            sampled,
            stray,
            near,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use slc_bounds::{Brdf, Fresnel};
    use slc_core::{Camera, GSample, Interleaving};

    /// A sample at `position` facing up.
    fn sample(position: Vec3) -> Option<GSample> {
        Some(GSample {
            position,
            normal: Vec3::Y,
            geometric_normal: Vec3::Y,
            omega_o: Vec3::Y,
            depth: 1.0,
            brdf: Brdf {
                kd: Vec3::splat(0.5),
                fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
                alpha: 0.3,
                anisotropy: None,
            },
        })
    }

    /// The receivers' stray (skipping the projections that surely lie within the stray so
    /// far) is the maximum of every sample's own: samples at their pixels' centres, jittered
    /// within them or on their edges, up to two pixels outside (images from 37 to 1e3 pixels
    /// wide), and one sample 1e5 pixels off.
    #[test]
    fn the_stray_is_every_samples_largest() {
        use crate::test_rng::Rng;
        let camera = Camera::look_at(Vec3::new(0.3, 4.0, -6.0), Vec3::ZERO, Vec3::Y, 0.9).unwrap();
        let mut rng = Rng(17);
        for (case, (w, h)) in [(37, 20), (64, 64), (1000, 3)].into_iter().enumerate() {
            for spread in [0.0, 0.5, 2.0, 1e5] {
                let view = CullView::new(&camera, w, h).unwrap();
                let offset = |rng: &mut Rng| match spread {
                    0.0 => 0.5,
                    // On either edge of the pixel or within it.
                    0.5 => [0.0, 1.0, rng.range(0.0, 1.0)][(rng.f32() * 3.0) as usize],
                    _ => rng.range(-2.0, 3.0),
                };
                let mut samples = Vec::new();
                for (y, x) in (0..h).flat_map(|y| (0..w).map(move |x| (y, x))) {
                    let (u, v) = (offset(&mut rng), offset(&mut rng));
                    let far = spread == 1e5 && (x, y) == (w / 2, h / 2);
                    let u = if far { 1e5 } else { u };
                    let d = camera.ray_direction(x, y, u, v, w, h);
                    samples.push(sample(camera.position + d * rng.range(1.0, 9.0)));
                }
                let want = samples.iter().enumerate().fold(CENTRED, |m, (p, g)| {
                    let v = view.to_view(g.as_ref().unwrap().position);
                    let at = view.to_screen(DVec2::new(v.x, v.y) / v.z);
                    let corner = DVec2::new((p as u32 % w).into(), (p as u32 / w).into());
                    m.max((corner - at).max(at - corner - 1.0).max_element())
                });
                let gbuffer = GBuffer {
                    width: w,
                    height: h,
                    samples,
                };
                let got = Receivers::new(&gbuffer, &view, 2).unwrap().stray;
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "case {case}, spread {spread}"
                );
                // Centred samples stay half a pixel inside their pixel's edges, up to their f32
                // rounding; those on an edge stray by that rounding only.
                let expected = match spread {
                    0.0 => -0.5..=-0.45,
                    0.5 => -1e-3..=0.1,
                    2.0 => 0.5..=2.0,
                    _ => 1e4..=1e6,
                };
                assert!(
                    expected.contains(&want),
                    "case {case}, spread {spread}: {want}"
                );
            }
        }
    }

    /// With samples at their pixels' centres (a stray of about −0.5), every pixel of a VPL's
    /// subregion whose sample the VPL's test passes lies in its rectangle: VPLs on and near a
    /// floor's samples, with δ from 1e-9 to 1e3 (ranges from far below a pixel to the whole
    /// image), K = 1, 3 and 8, through the lanes and slc-bounds' path alike. The test of
    /// each VPL is taken from a screen whose stray covers every pixel.
    #[test]
    fn centred_samples_lie_in_their_vpls_rectangles() {
        use crate::test_rng::{random_vpl, Rng};
        use slc_core::Vpl;
        let camera = Camera::look_at(Vec3::new(0.3, 4.0, -6.0), Vec3::ZERO, Vec3::Y, 0.9).unwrap();
        let (w, h) = (96, 64);
        let view = CullView::new(&camera, w, h).unwrap();
        // The floor y = 0, and a wall 12 away where a ray misses it.
        let mut samples = Vec::new();
        for (y, x) in (0..h).flat_map(|y| (0..w).map(move |x| (y, x))) {
            let d = camera.ray_direction(x, y, 0.5, 0.5, w, h);
            let t = if d.y < -0.05 {
                (4.0 / -d.y).min(12.0)
            } else {
                12.0
            };
            samples.push(sample(camera.position + d * t));
        }
        let gbuffer = GBuffer {
            width: w,
            height: h,
            samples,
        };
        let mut rng = Rng(0xCE47);
        let (mut passing, mut on_edge) = (0, 0);
        for k in [1u32, 3, 8] {
            let receivers = Receivers::new(&gbuffer, &view, k).unwrap();
            assert!(receivers.stray < -0.49, "{}", receivers.stray);
            let il = Interleaving { k, seed: 7 };
            let near = receivers.near;
            let narrow = Screen::new(&view, w, h, il, receivers.stray, near).unwrap();
            let wide = Screen::new(&view, w, h, il, 1e4, near).unwrap();
            for case in 0..250u32 {
                let delta = 10f32.powf(rng.range(-9.0, 3.0));
                let vpls: Vec<Vpl> = (0..8)
                    .map(|i| {
                        let mut vpl = random_vpl(&mut rng, case * 8 + i);
                        let at = (rng.f32() * (w * h) as f32) as usize % (w * h) as usize;
                        let offset = Vec3::new(rng.f32(), rng.f32(), rng.f32()) - 0.5;
                        vpl.position = gbuffer.samples[at].unwrap().position + offset * 0.2;
                        vpl
                    })
                    .collect();
                let (mut placed, mut all) = (Vec::new(), Vec::new());
                scatter(&narrow, &vpls, 0, delta, &mut placed).unwrap();
                scatter(&wide, &vpls, 0, delta, &mut all).unwrap();
                for s in &all {
                    let [sx, sy] = s.subregion;
                    let kept = placed.iter().find(|p| p.index == s.index);
                    for y in (sy..h).step_by(k as usize) {
                        for x in (sx..w).step_by(k as usize) {
                            let g = gbuffer.samples[(y * w + x) as usize].unwrap();
                            if !s.test.contains(g.position) {
                                continue;
                            }
                            passing += 1;
                            let kept = kept.unwrap_or_else(|| panic!("K {k}: {s:?} not placed"));
                            assert_eq!(kept.test, s.test);
                            let ([i, j], [i0, j0, i1, j1]) = ([x / k, y / k], kept.pixels);
                            assert!(
                                (i0..=i1).contains(&i) && (j0..=j1).contains(&j),
                                "K {k}: pixel ({x}, {y}) outside {kept:?}"
                            );
                            on_edge += usize::from(i == i0 || i == i1 || j == j0 || j == j1);
                        }
                    }
                }
            }
        }
        assert!(
            passing > 1_000_000 && on_edge > 100_000,
            "{passing} pairs, {on_edge} on an edge"
        );
    }

    /// A sample behind the camera is an error naming its pixel: the first pixel, and one in a
    /// later screen row, another piece of the receivers' work.
    #[test]
    fn a_sample_behind_the_camera_is_an_error_naming_its_pixel() {
        let camera = Camera::look_at(Vec3::new(0.0, 4.0, 0.0), Vec3::ZERO, Vec3::Z, 1.0).unwrap();
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
            let err = cull(&input, LARGE_PIXELS).unwrap_err().to_string();
            assert!(
                err.contains(&format!("pixel ({x}, {y}) is not in front of the camera")),
                "{err}"
            );
        }
    }
}
