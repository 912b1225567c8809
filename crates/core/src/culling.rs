//! The interface between culling strategies and shading: what a culler gets, and the light
//! lists it returns.
use crate::camera::Camera;
use crate::framebuffer::GBuffer;
use crate::rng::{hash4, stream};
use crate::strategy::Strategy;
use crate::vpl::Vpl;
use std::borrow::Cow;

/// Pixels per tile side in tiled and clustered culling (paper section 5, 7).
pub const TILE_SIZE: u32 = 16;

/// Interleaved sampling (paper section 6, Fig. 8): the screen is split into K x K subregions
/// (pixel (x, y) belongs to subregion (x mod K, y mod K)), and each VPL to one subregion chosen
/// uniformly at random from its id. A pixel sums only its subregion's VPLs, times K², which
/// keeps the estimate unbiased: each VPL is in the pixel's subregion with probability 1/K².
/// K = 1 turns interleaving off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Interleaving {
    pub k: u32,
    pub seed: u32,
}

impl Interleaving {
    pub fn subregions(&self) -> u32 {
        self.k * self.k
    }

    /// The subregion of pixel (x, y), row-major in the K x K grid.
    #[inline]
    pub fn pixel_subregion(&self, x: u32, y: u32) -> u32 {
        (y % self.k) * self.k + x % self.k
    }

    /// The subregion a VPL belongs to, from its stable id ([`crate::Subregions::of_vpl`]
    /// gives the same without a division).
    #[inline]
    pub fn vpl_subregion(&self, vpl_id: u32) -> u32 {
        if self.k == 1 {
            0
        } else {
            hash4(self.seed, vpl_id, stream::INTERLEAVE, 0) % self.subregions()
        }
    }

    /// The size of subregion `(sx, sy)`'s image for a `width` x `height` screen: the pixels
    /// sx, sx + K, ... below the width by sy, sy + K, ... below the height (0 past the edge).
    #[inline]
    pub fn subregion_size(&self, width: u32, height: u32, [sx, sy]: [u32; 2]) -> [u32; 2] {
        let side = |s: u32, n: u32| n.saturating_sub(s).div_ceil(self.k);
        [side(sx, width), side(sy, height)]
    }

    /// The factor every contribution is multiplied by: K².
    pub fn scale(&self) -> f32 {
        self.subregions() as f32
    }
}

/// Everything a culler may look at. All strategies of a comparison get the same input.
#[derive(Clone, Copy, Debug)]
pub struct CullInput<'a> {
    pub gbuffer: &'a GBuffer,
    pub camera: &'a Camera,
    pub vpls: &'a [Vpl],
    /// δ of eq. (2), the same for every VPL.
    pub delta: f32,
    pub interleaving: Interleaving,
}

/// Light lists in compressed rows: list `i` holds `indices[offsets[i]..offsets[i + 1]]`
/// (indices into `CullInput::vpls`), and pixel `p` shades with list `pixel_list[p]`
/// (`NO_LIST` for pixels that see nothing). A tile with two depth clusters has two lists; a
/// pixel picks the one of its depth.
///
/// A strategy may give a pixel a second list, `shared_list[p]`, that many pixels share
/// (`binned`: the VPLs of large range that may reach the pixel's 4×4 cell). Then every list is strictly
/// ascending ([`Self::check`]), and the pixel is shaded with the union of its two lists in
/// ascending order, each VPL once ([`Self::for_pixel`]). `shared_list` is empty where the
/// strategy gives each pixel one list.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightLists {
    pub offsets: Vec<u32>,
    pub indices: Vec<u32>,
    pub pixel_list: Vec<u32>,
    pub shared_list: Vec<u32>,
}

/// `pixel_list` value of a pixel without a list.
pub const NO_LIST: u32 = u32::MAX;

impl LightLists {
    /// The VPL indices pixel `p` is shaded with, in the order it sums them: its list as it
    /// is, or with a second list the union of both, ascending, each VPL once. The lists must
    /// be well formed ([`Self::check`]); a list id past the offsets panics.
    pub fn for_pixel(&self, p: usize) -> Cow<'_, [u32]> {
        match self.lists_of(p) {
            [own, []] => Cow::Borrowed(own),
            [[], shared] => Cow::Borrowed(shared),
            [own, shared] => Cow::Owned(union(own, shared)),
        }
    }

    /// Pixel `p`'s own list and its second, shared list (empty where it has none).
    #[inline]
    pub fn lists_of(&self, p: usize) -> [&[u32]; 2] {
        let shared = self.shared_list.get(p).copied().unwrap_or(NO_LIST);
        [self.list(self.pixel_list[p]), self.list(shared)]
    }

    /// The entries of list `l`, none for `NO_LIST`.
    #[inline]
    pub fn list(&self, l: u32) -> &[u32] {
        match l {
            NO_LIST => &[],
            l => {
                &self.indices
                    [self.offsets[l as usize] as usize..self.offsets[l as usize + 1] as usize]
            }
        }
    }

    /// Pixel-VPL pairs the lists hold: the sum over pixels of the VPLs each is shaded with
    /// (what shading evaluates, before its early exits).
    pub fn listed_pairs(&self) -> u64 {
        (0..self.pixel_list.len())
            .map(|p| self.for_pixel(p).len() as u64)
            .sum()
    }

    /// The same lists with one list per pixel: where a pixel has a second list, its own
    /// becomes the union ([`Self::for_pixel`]), for a reader of single lists (the GPU's
    /// shading of uploaded lists). Errors when the unions hold more entries than 32-bit
    /// offsets address. The lists must be well formed ([`Self::check`]).
    pub fn flattened(&self) -> Result<LightLists, CullError> {
        if self.shared_list.is_empty() {
            return Ok(self.clone());
        }
        let mut flat = LightLists {
            offsets: vec![0],
            ..LightLists::default()
        };
        for p in 0..self.pixel_list.len() {
            let list = self.for_pixel(p);
            if list.is_empty() {
                flat.pixel_list.push(NO_LIST);
                continue;
            }
            flat.pixel_list.push((flat.offsets.len() - 1) as u32);
            flat.indices.extend_from_slice(&list);
            let end = u32::try_from(flat.indices.len()).map_err(|_| {
                CullError::Input(format!(
                    "more than {} light-list entries once each pixel's lists are one",
                    u32::MAX
                ))
            })?;
            flat.offsets.push(end);
        }
        Ok(flat)
    }

    /// Number of lists.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Errors unless these are lists for `pixels` pixels and `vpls` VPLs: one entry per
    /// pixel, each a list or `NO_LIST`; offsets starting at 0, never decreasing and ending
    /// at the number of indices; every index below `vpls`; and where there are second lists,
    /// one entry per pixel in `shared_list` too, each a list or `NO_LIST`, and every list
    /// strictly ascending.
    pub fn check(&self, pixels: usize, vpls: usize) -> Result<(), CullError> {
        let bad = |what: String| Err(CullError::Input(format!("malformed light lists: {what}")));
        if self.pixel_list.len() != pixels {
            return bad(format!(
                "{} list entries for {pixels} pixels",
                self.pixel_list.len()
            ));
        }
        if self.offsets.first().is_some_and(|&o| o != 0)
            || self.offsets.windows(2).any(|w| w[0] > w[1])
            || self.offsets.last().map_or(0, |&o| o as usize) != self.indices.len()
        {
            return bad(format!(
                "{} offsets do not cut {} indices into lists",
                self.offsets.len(),
                self.indices.len()
            ));
        }
        // The largest entries first, in reductions without an early exit (they vectorize; a
        // search for the first bad entry does not), the offender looked up only if one is bad.
        if self
            .indices
            .iter()
            .max()
            .is_some_and(|&i| i as usize >= vpls)
        {
            let i = self.indices.iter().find(|&&i| i as usize >= vpls);
            return bad(format!(
                "VPL index {} of {vpls} VPLs",
                i.expect("the largest")
            ));
        }
        let lists = self.len();
        // l + 1, NO_LIST (u32::MAX) as 0: at most `lists` for a pixel without or with a list.
        let named = |l: u32| l.wrapping_add(1);
        for (map, which) in [(&self.pixel_list, ""), (&self.shared_list, "shared ")] {
            if map
                .iter()
                .map(|&l| named(l))
                .max()
                .is_some_and(|l| l as usize > lists)
            {
                let l = map.iter().find(|&&l| named(l) as usize > lists);
                return bad(format!(
                    "{which}list {} of {lists} lists",
                    l.expect("the largest")
                ));
            }
        }
        if self.shared_list.is_empty() {
            return Ok(());
        }
        if self.shared_list.len() != pixels {
            return bad(format!(
                "{} shared list entries for {pixels} pixels",
                self.shared_list.len()
            ));
        }
        // Unions are merged: with second lists, every list is strictly ascending.
        if let Some(l) = (0..lists).find(|&l| self.list(l as u32).windows(2).any(|w| w[0] >= w[1]))
        {
            return bad(format!(
                "list {l} is not strictly ascending beside shared lists"
            ));
        }
        Ok(())
    }
}

/// The union of two strictly ascending lists, ascending, each VPL once.
fn union(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let (x, y) = (a[i], b[j]);
        out.push(x.min(y));
        i += usize::from(x <= y);
        j += usize::from(y <= x);
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// Why culling failed.
#[derive(Debug, thiserror::Error)]
pub enum CullError {
    #[error("invalid culling input: {0}")]
    Input(String),
    #[error(transparent)]
    Bounds(#[from] slc_bounds::BoundsError),
}

/// A culling strategy as a backend runs it: reads `Input` (a G-buffer, camera and VPLs where
/// the backend keeps them) and builds, for every pixel, the list of VPLs that may contribute
/// there. A culler must never leave out a VPL whose probability p(ωo, l) of eq. (2) at a
/// pixel exceeds its ξ (that would bias the estimate); listing extra VPLs only costs time.
///
/// The CPU cullers (`slc_cull::culler`) read a [`CullInput`] and return [`LightLists`]
/// ([`CpuCuller`]); the GPU's (`slc_gpu_wgpu::cull`) read a frame on the device and leave
/// their lists there.
pub trait Culler<Input: ?Sized> {
    /// The lists, where this backend keeps them.
    type Lists;
    type Error;
    /// The strategy this culler implements.
    fn strategy(&self) -> Strategy;
    fn cull(&self, input: &Input) -> Result<Self::Lists, Self::Error>;
}

/// A culler on the CPU: [`CullInput`] in, [`LightLists`] out.
pub trait CpuCuller:
    for<'a> Culler<CullInput<'a>, Lists = LightLists, Error = CullError> + Sync
{
}

impl<T> CpuCuller for T where
    T: for<'a> Culler<CullInput<'a>, Lists = LightLists, Error = CullError> + Sync
{
}

/// True and false positives and misses of light lists against the brute-force truth
/// (`slc_cull::metrics`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CullMetrics {
    /// Listed pairs that contribute.
    pub true_positive_pairs: u64,
    /// Listed pairs that do not contribute (including VPLs of another subregion and repeated
    /// entries).
    pub false_positive_pairs: u64,
    /// Contributing pairs that are not listed: culling errors that bias the estimate; must be 0.
    pub missed_pairs: u64,
    /// Mean list length over all pixels (pixels without a G-buffer sample count as 0).
    pub lights_per_pixel_mean: f64,
    /// FP / (TP + FP) over all pairs; 0 when nothing is listed.
    pub false_discovery_rate: f64,
    /// List length of every pixel (row-major), for heat maps.
    pub lights_per_pixel: Vec<u32>,
    /// FP / (TP + FP) of every pixel (row-major), 0 where nothing is listed.
    pub fdr_per_pixel: Vec<f32>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn malformed_lists_are_errors() {
        let good = LightLists {
            offsets: vec![0, 2],
            indices: vec![0, 1],
            pixel_list: vec![0, NO_LIST],
            shared_list: Vec::new(),
        };
        assert!(good.check(2, 2).is_ok());
        assert!(good.check(3, 2).is_err());
        assert!(good.check(2, 1).is_err());
        let dangling = LightLists {
            pixel_list: vec![1, 0],
            ..good.clone()
        };
        assert!(dangling.check(2, 2).is_err());
        let short = LightLists {
            offsets: vec![0, 3],
            ..good
        };
        assert!(short.check(2, 2).is_err());
        // No lists at all: every pixel without one is fine, a pixel naming list 0 is not.
        let none = LightLists {
            offsets: vec![0],
            indices: vec![],
            pixel_list: vec![NO_LIST; 3],
            shared_list: Vec::new(),
        };
        assert!(none.check(3, 0).is_ok());
        let named = LightLists {
            pixel_list: vec![NO_LIST, 0, NO_LIST],
            ..none
        };
        let message = named.check(3, 0).unwrap_err().to_string();
        assert!(message.contains("list 0 of 0 lists"), "{message}");
        assert!(LightLists::default().check(0, 0).is_ok());
    }

    /// Second lists: a pixel is shaded with the union of its two lists, ascending, each VPL
    /// once; the pairs and the flattened lists count and hold exactly that; lists beside
    /// shared ones must be strictly ascending, and a shared list must exist.
    #[test]
    fn a_pixel_with_a_shared_list_is_shaded_with_the_union() {
        // Lists 0 and 1 are pixels' own, list 2 is shared by pixels 0, 1 and 3.
        let lists = LightLists {
            offsets: vec![0, 3, 4, 7],
            indices: vec![1, 5, 9, 2, 0, 5, 6],
            pixel_list: vec![0, NO_LIST, 1, NO_LIST, 1],
            shared_list: vec![2, 2, NO_LIST, 2, NO_LIST],
        };
        assert!(lists.check(5, 10).is_ok());
        assert_eq!(*lists.for_pixel(0), [0, 1, 5, 6, 9], "VPL 5 once");
        assert_eq!(*lists.for_pixel(1), [0, 5, 6]);
        assert_eq!(*lists.for_pixel(2), [2]);
        assert_eq!(*lists.for_pixel(3), [0, 5, 6]);
        assert_eq!(lists.lists_of(0), [&[1, 5, 9][..], &[0, 5, 6][..]]);
        assert_eq!(lists.listed_pairs(), 5 + 3 + 1 + 3 + 1);
        let flat = lists.flattened().unwrap();
        assert!(flat.shared_list.is_empty());
        assert!(flat.check(5, 10).is_ok());
        for p in 0..5 {
            assert_eq!(flat.for_pixel(p), lists.for_pixel(p), "pixel {p}");
        }
        assert_eq!(flat.listed_pairs(), lists.listed_pairs());
        let unsorted = LightLists {
            indices: vec![1, 5, 9, 2, 0, 6, 5],
            ..lists.clone()
        };
        let message = unsorted.check(5, 10).unwrap_err().to_string();
        assert!(
            message.contains("list 2 is not strictly ascending"),
            "{message}"
        );
        let short = LightLists {
            shared_list: vec![2, 2],
            ..lists.clone()
        };
        assert!(short.check(5, 10).is_err());
        let dangling = LightLists {
            shared_list: vec![3, 2, NO_LIST, 2, NO_LIST],
            ..lists
        };
        let message = dangling.check(5, 10).unwrap_err().to_string();
        assert!(message.contains("shared list 3 of 3 lists"), "{message}");
    }

    #[test]
    fn listed_pairs_count_each_pixel_with_its_list() {
        // Two lists (3 and 1 VPLs); pixels 0 and 2 share list 0, pixel 1 has none.
        let lists = LightLists {
            offsets: vec![0, 3, 4],
            indices: vec![5, 6, 7, 1],
            pixel_list: vec![0, NO_LIST, 0, 1],
            shared_list: Vec::new(),
        };
        // Pixels 0 and 2: three pairs each; pixel 1: none; pixel 3: one.
        assert_eq!(lists.listed_pairs(), 7);
        assert_eq!(LightLists::default().listed_pairs(), 0);
    }
}
