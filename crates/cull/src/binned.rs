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
//! The VPLs are read once, in their order, and each tests the pixels of its rectangle where
//! it is (the samples' positions, a few MB, stay in cache; the VPLs, 100+ bytes each, are
//! streamed): the pairs that pass, in VPL order, are then sorted by pixel. A GPU twin gets
//! the same lists by binning each rectangle into the tiles it overlaps, then testing each
//! tile's pixels against its bin (docs/many-vpls.md).
use crate::lists::pixel_count;
use crate::partition::check;
use crate::scatter::{Scattered, Screen};
use crate::scatter_lanes::{plain, scatter_plain};
use crate::view::CullView;
use glam::{DVec2, Vec3};
use rayon::prelude::*;
use slc_bounds::StochasticParams;
use slc_core::{CullError, CullInput, GBuffer, LightLists, Vpl, NO_LIST};

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
    let receivers = Receivers::new(input.gbuffer, &view)?;
    let screen = Screen::new(&view, width, height, il, receivers.stray, receivers.near);
    if !input.vpls.is_empty() {
        // δ is checked once here for the lanes, which take it as valid.
        StochasticParams::new(input.delta, 0.5)?;
    }
    // Per piece of VPLs (in order), the (pixel, VPL) pairs that pass, in VPL order.
    let pieces = input
        .vpls
        .par_chunks(VPLS_PER_PIECE)
        .enumerate()
        .map_init(Vec::new, |scattered, (piece, vpls)| {
            let first = (piece * VPLS_PER_PIECE) as u32;
            scatter(&screen, vpls, first, input.delta, scattered)?;
            let mut pairs = Vec::new();
            for s in scattered.iter().flatten() {
                receivers.test(s, width, il.k, &mut pairs);
            }
            Ok(pairs)
        })
        .collect::<Result<Vec<Vec<(u32, u32)>>, CullError>>()?;
    lists(&pieces, pixels)
}

/// Each of `vpls` (numbered from `first`) scattered into `out`, in their order: the plain
/// ones eight at a time in lanes, the others (and the lanes' extremes) one at a time.
fn scatter(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut Vec<Option<Scattered>>,
) -> Result<(), CullError> {
    out.clear();
    out.resize(vpls.len(), None);
    // Up to eight plain VPLs and their numbers.
    let mut group: Vec<&Vpl> = Vec::with_capacity(8);
    let mut indices: Vec<u32> = Vec::with_capacity(8);
    let flush = |group: &mut Vec<&Vpl>, indices: &mut Vec<u32>, out: &mut [Option<Scattered>]| {
        let mut results = [None; 8];
        let left = match group.is_empty() {
            true => 0,
            false => scatter_plain(screen, group, indices, delta, &mut results),
        };
        for (k, (&vpl, &index)) in group.iter().zip(indices.iter()).enumerate() {
            out[(index - first) as usize] = match left >> k & 1 {
                1 => screen.scatter(vpl, index, delta)?,
                _ => results[k],
            };
        }
        group.clear();
        indices.clear();
        Ok::<(), CullError>(())
    };
    for (i, vpl) in vpls.iter().enumerate() {
        let index = first + i as u32;
        if plain(vpl) {
            group.push(vpl);
            indices.push(index);
            if group.len() == 8 {
                flush(&mut group, &mut indices, out)?;
            }
        } else {
            out[i] = screen.scatter(vpl, index, delta)?;
        }
    }
    flush(&mut group, &mut indices, out)
}

/// One list per pixel with pairs (a counting sort of the pairs by pixel, keeping their VPL
/// order), numbered in pixel order.
fn lists(pieces: &[Vec<(u32, u32)>], pixels: usize) -> Result<LightLists, CullError> {
    let total: usize = pieces.iter().map(Vec::len).sum();
    if u32::try_from(total).is_err() {
        return Err(CullError::Input(format!(
            "{total} light-list entries exceed 32-bit offsets"
        )));
    }
    let mut counts = vec![0u32; pixels];
    for &(p, _) in pieces.iter().flatten() {
        counts[p as usize] += 1;
    }
    let mut offsets = vec![0u32];
    let mut pixel_list = vec![NO_LIST; pixels];
    let mut next = vec![0u32; pixels];
    for (p, &count) in counts.iter().enumerate() {
        if count > 0 {
            pixel_list[p] = (offsets.len() - 1) as u32;
            next[p] = offsets[offsets.len() - 1];
            offsets.push(next[p] + count);
        }
    }
    let mut indices = vec![0u32; total];
    for &(p, vpl) in pieces.iter().flatten() {
        indices[next[p as usize] as usize] = vpl;
        next[p as usize] += 1;
    }
    Ok(LightLists {
        offsets,
        indices,
        pixel_list,
    })
}

/// The G-buffer as the scatter reads it: per pixel its sample's world position (NaN where it
/// has no sample, which fails every test), with how far any sample's projection strays
/// outside its own pixel and the smallest view depth.
struct Receivers {
    positions: Vec<Vec3>,
    stray: f64,
    near: f64,
}

impl Receivers {
    /// Errors on a sample not in front of the camera (as the other strategies do).
    fn new(gbuffer: &GBuffer, view: &CullView) -> Result<Self, CullError> {
        let width = gbuffer.width;
        let per_pixel = gbuffer
            .samples
            .par_iter()
            .enumerate()
            .map(|(p, g)| {
                let Some(g) = g else {
                    return Ok((f64::INFINITY, 0.0));
                };
                let v = view.to_view(g.position);
                let (x, y) = (p as u32 % width, p as u32 / width);
                if !(v.z > 0.0 && v.is_finite()) {
                    return Err(CullError::Input(format!(
                        "G-buffer sample of pixel ({x}, {y}) is not in front of the camera \
                         (view depth {})",
                        v.z
                    )));
                }
                let at = view.to_screen(DVec2::new(v.x, v.y) / v.z);
                let corner = DVec2::new(f64::from(x), f64::from(y));
                let outside = (corner - at).max(at - corner - 1.0).max_element().max(0.0);
                Ok((v.z, outside))
            })
            .collect::<Result<Vec<_>, CullError>>()?;
        Ok(Self {
            positions: gbuffer
                .samples
                .par_iter()
                .map(|g| g.as_ref().map_or(Vec3::NAN, |g| g.position))
                .collect(),
            stray: per_pixel.iter().map(|s| s.1).fold(0.0, f64::max),
            near: per_pixel.iter().map(|s| s.0).fold(f64::INFINITY, f64::min),
        })
    }

    /// Appends (pixel, VPL) for every pixel of `s`'s rectangle whose sample passes its test.
    #[inline]
    fn test(&self, s: &Scattered, width: u32, k: u32, pairs: &mut Vec<(u32, u32)>) {
        let [i0, j0, i1, j1] = s.pixels;
        let [sx, sy] = s.subregion;
        for j in j0..=j1 {
            let row = (sy + k * j) * width + sx;
            for i in i0..=i1 {
                let p = row + k * i;
                if s.test.contains(self.positions[p as usize]) {
                    pairs.push((p, s.index));
                }
            }
        }
    }
}
