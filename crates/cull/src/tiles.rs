//! Screen tiles in interleaved subregion images (paper sections 5 and 6, Fig. 8).
//!
//! With K x K interleaving, pixel (x, y) belongs to subregion (x mod K, y mod K) and sits at
//! (x div K, y div K) of that subregion's image. Tiles are [`TILE_SIZE`]² pixels of a
//! subregion image, so a tile covers screen pixels with stride K and spans up to 16K x 16K
//! screen pixels; it is culled against its subregion's VPLs only. K = 1 gives ordinary tiles.
use crate::partition::check;
use slc_core::{CullError, Interleaving, TILE_SIZE};

/// One tile: `count` pixels of subregion `(sx, sy)`'s image starting at `first` (in
/// subregion coordinates).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    sub: [u32; 2],
    first: [u32; 2],
    count: [u32; 2],
}

/// Every tile of a `width` x `height` image with interleaving factor `k`, subregion by
/// subregion (row-major in the K x K grid), row-major within each subregion. Subregions of an
/// image smaller than K, or not a multiple of it, are smaller or empty.
pub(crate) fn tiles(width: u32, height: u32, k: u32) -> Vec<Tile> {
    let mut out = Vec::new();
    for sy in 0..k.min(height) {
        for sx in 0..k.min(width) {
            let size = subregion_size(width, height, k, [sx, sy]);
            for ty in 0..size[1].div_ceil(TILE_SIZE) {
                for tx in 0..size[0].div_ceil(TILE_SIZE) {
                    let first = [tx * TILE_SIZE, ty * TILE_SIZE];
                    out.push(Tile {
                        sub: [sx, sy],
                        first,
                        count: [
                            TILE_SIZE.min(size[0] - first[0]),
                            TILE_SIZE.min(size[1] - first[1]),
                        ],
                    });
                }
            }
        }
    }
    out
}

/// The size of subregion `sub`'s image ([`Interleaving::subregion_size`]).
#[inline]
fn subregion_size(width: u32, height: u32, k: u32, sub: [u32; 2]) -> [u32; 2] {
    Interleaving { k, seed: 0 }.subregion_size(width, height, sub)
}

impl Tile {
    /// The tile's subregion, row-major in the K x K grid (as `Interleaving::pixel_subregion`).
    #[inline]
    pub(crate) fn subregion(&self, k: u32) -> u32 {
        self.sub[1] * k + self.sub[0]
    }

    /// The screen pixels `[x0, x1) x [y0, y1)` bounding the tile's pixels' footprints.
    pub(crate) fn screen_rect(&self, k: u32) -> [u32; 4] {
        let [x0, y0] = self.screen(k, 0, 0);
        let [x1, y1] = self.screen(k, self.count[0] - 1, self.count[1] - 1);
        [x0, y0, x1 + 1, y1 + 1]
    }

    /// The number of pixels of the tile.
    #[inline]
    pub fn pixel_count(&self) -> usize {
        (self.count[0] * self.count[1]) as usize
    }

    /// The number of pixels in a row of the tile.
    #[inline]
    pub(crate) fn columns(&self) -> u32 {
        self.count[0]
    }

    /// The tile's screen pixels (x, y), row by row.
    pub fn pixels(&self, k: u32) -> impl Iterator<Item = [u32; 2]> + '_ {
        (0..self.count[1]).flat_map(move |b| (0..self.count[0]).map(move |a| self.screen(k, a, b)))
    }

    /// The tile's pixels as (slot, screen pixel), the slot numbering [`Self::pixels`]' order,
    /// taken in Z order (the Morton order of the pixel's place in the tile): in a full tile
    /// every 2^(2j) consecutive pixels form a 2^j x 2^j block and every 8 a 4 x 2 block, so
    /// any part of the tile taken in this order stays compact.
    pub fn pixels_z_order(&self, k: u32) -> impl Iterator<Item = (usize, [u32; 2])> + '_ {
        Z_ORDER.iter().filter_map(move |&[a, b]| {
            let (a, b) = (u32::from(a), u32::from(b));
            (a < self.count[0] && b < self.count[1])
                .then(|| ((b * self.count[0] + a) as usize, self.screen(k, a, b)))
        })
    }

    /// The screen pixel (x, y) of the tile's pixel number `slot` (in the order of
    /// [`Self::pixels`]).
    #[inline]
    pub(crate) fn pixel(&self, k: u32, slot: usize) -> [u32; 2] {
        let slot = slot as u32;
        self.screen(k, slot % self.count[0], slot / self.count[0])
    }

    /// Screen coordinates of the tile's pixel (a, b).
    #[inline]
    fn screen(&self, k: u32, a: u32, b: u32) -> [u32; 2] {
        [
            self.sub[0] + k * (self.first[0] + a),
            self.sub[1] + k * (self.first[1] + b),
        ]
    }
}

/// The places (a, b) in a full tile in Z order: entry m is the pixel whose Morton code is m
/// (a from its even bits, b from its odd bits).
const Z_ORDER: [[u8; 2]; (TILE_SIZE * TILE_SIZE) as usize] = {
    let mut order = [[0u8; 2]; (TILE_SIZE * TILE_SIZE) as usize];
    let mut m = 0;
    while m < order.len() {
        order[m] = [even_bits(m as u32) as u8, even_bits(m as u32 >> 1) as u8];
        m += 1;
    }
    order
};

/// The even bits of `m` (bits 0, 2, 4, ...) packed: a Morton code's first coordinate.
const fn even_bits(m: u32) -> u32 {
    let mut x = m & 0x5555_5555;
    x = (x | x >> 1) & 0x3333_3333;
    x = (x | x >> 2) & 0x0f0f_0f0f;
    x = (x | x >> 4) & 0x00ff_00ff;
    (x | x >> 8) & 0x0000_ffff
}

/// The tiles of an image grouped in **bands** for shading: band (sy, ty) holds every tile of
/// the row of subregions sy whose pixels lie in tile row ty of its subregion, i.e. in the
/// image rows sy + K·(16·ty + j), j < 16, and no other tile writes those rows. Bands therefore
/// own disjoint rows of an image and can be shaded in parallel, each writing its pixels in
/// place (no image in tile order to put back in row order). Within a band the tiles are in
/// **place order**: the K tiles at one place (sx = 0..K) follow each other, so tiles that read
/// the same G-buffer cache lines (screen pixels x and x + 1 lie in subregions sx and sx + 1)
/// run while those lines are cached.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TileOrder {
    tiles: Vec<Tile>,
    k: u32,
    width: u32,
    height: u32,
}

impl TileOrder {
    /// The tiles of a `width` x `height` image with interleaving factor `k`; errors when K is
    /// not in 1..=1024 or the image has 2³² pixels or more (pixel indices are u32).
    pub fn new(width: u32, height: u32, k: u32) -> Result<Self, CullError> {
        check(Interleaving { k, seed: 0 }, 0)?;
        if u32::try_from(u64::from(width) * u64::from(height)).is_err() {
            return Err(CullError::Input(format!(
                "a {width}x{height} image has more pixels than 32-bit indices address"
            )));
        }
        Ok(Self {
            tiles: tiles(width, height, k),
            k,
            width,
            height,
        })
    }

    /// The bands of `image` (row-major, `per_pixel` entries per pixel), row of subregions by
    /// row of subregions, each band's tiles in place order with the image rows they write.
    /// Errors when `image` does not hold `per_pixel` entries per pixel.
    pub fn bands<'a, T>(
        &self,
        image: &'a mut [T],
        per_pixel: usize,
    ) -> Result<Vec<Band<'_, 'a, T>>, CullError> {
        let (w, h, k) = (self.width, self.height, self.k);
        let row_len = (w as usize).checked_mul(per_pixel);
        if row_len.and_then(|r| r.checked_mul(h as usize)) != Some(image.len()) {
            return Err(CullError::Input(format!(
                "{} entries for a {w}x{h} image of {per_pixel} per pixel",
                image.len()
            )));
        }
        if w == 0 || h == 0 {
            return Ok(Vec::new());
        }
        // Band (sy, ty) is number first_band[sy] + ty.
        let mut first_band = vec![0usize; k.min(h) as usize + 1];
        for sy in 0..k.min(h) {
            let rows = subregion_size(w, h, k, [0, sy])[1];
            first_band[sy as usize + 1] =
                first_band[sy as usize] + rows.div_ceil(TILE_SIZE) as usize;
        }
        let band_of = |sy: u32, b: u32| first_band[sy as usize] + (b / TILE_SIZE) as usize;
        let mut bands: Vec<Band<T>> = (0..k.min(h))
            .flat_map(|sy| {
                (first_band[sy as usize]..first_band[sy as usize + 1]).map(move |b| (sy, b))
            })
            .map(|(sy, b)| Band {
                tiles: Vec::new(),
                rows: BandRows {
                    rows: Vec::new(),
                    place: [sy, (b - first_band[sy as usize]) as u32 * TILE_SIZE],
                    k,
                    per_pixel,
                },
            })
            .collect();
        for tile in &self.tiles {
            bands[band_of(tile.sub[1], tile.first[1])].tiles.push(tile);
        }
        for band in &mut bands {
            band.tiles.sort_by_key(|t| (t.first[0], t.sub[0]));
        }
        // With nothing per pixel there is nothing to write and no row to hand out.
        if let Some(row_len) = row_len.filter(|&r| r > 0) {
            for (y, row) in (0..h).zip(image.chunks_mut(row_len)) {
                bands[band_of(y % k, y / k)].rows.rows.push(row);
            }
        }
        Ok(bands)
    }
}

/// One band of [`TileOrder::bands`]: its tiles in place order and the image rows they write.
pub struct Band<'o, 'a, T> {
    pub tiles: Vec<&'o Tile>,
    pub rows: BandRows<'a, T>,
}

/// The image rows of a band: sy + K·(16·ty + j) for j = 0, 1, ...
pub struct BandRows<'a, T> {
    rows: Vec<&'a mut [T]>,
    /// The band's row of subregions sy and first row 16·ty of the subregion image: every
    /// tile of the band has `sub[1]` and `first[1]` equal to these.
    place: [u32; 2],
    k: u32,
    per_pixel: usize,
}

impl<T: Copy> BandRows<'_, T> {
    /// Writes `values` (`per_pixel` entries per pixel of `tile`, in the order of
    /// [`Tile::pixels`]) to the tile's pixels. `tile` must be one of the band's tiles.
    ///
    /// # Panics
    /// If `values` is not `per_pixel` entries per pixel of `tile`, or `tile` is not one of
    /// the band's.
    pub fn put(&mut self, tile: &Tile, values: &[T]) {
        let n = self.per_pixel;
        assert_eq!(values.len(), tile.pixel_count() * n, "values of one tile");
        assert_eq!(
            [tile.sub[1], tile.first[1]],
            self.place,
            "a tile of the band"
        );
        if n == 0 {
            return;
        }
        let x = |a: usize| (tile.sub[0] + self.k * (tile.first[0] + a as u32)) as usize;
        let rows = self
            .rows
            .iter_mut()
            .zip(values.chunks_exact(tile.count[0] as usize * n));
        if n == 1 {
            // One value per pixel (the shading's): assigned, not copied as a slice of runtime
            // length (a call to memcpy per pixel).
            for (row, values) in rows {
                for (a, &value) in values.iter().enumerate() {
                    row[x(a)] = value;
                }
            }
            return;
        }
        for (row, values) in rows {
            for (a, value) in values.chunks_exact(n).enumerate() {
                row[x(a) * n..(x(a) + 1) * n].copy_from_slice(value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_core::Interleaving;

    #[test]
    fn tiles_cover_every_pixel_once_in_its_subregion() {
        for (w, h) in [(1, 1), (5, 3), (16, 16), (17, 33), (100, 37), (64, 64)] {
            for k in [1, 2, 3, 4, 8] {
                let il = Interleaving { k, seed: 0 };
                let mut seen = vec![0u32; (w * h) as usize];
                for tile in tiles(w, h, k) {
                    let [x0, y0, x1, y1] = tile.screen_rect(k);
                    assert!(x1 - x0 <= TILE_SIZE * k && y1 - y0 <= TILE_SIZE * k);
                    let mut n = 0;
                    for [x, y] in tile.pixels(k) {
                        assert!(x < w && y < h, "{w}x{h} K {k}: ({x}, {y})");
                        assert!((x0..x1).contains(&x) && (y0..y1).contains(&y));
                        assert_eq!(il.pixel_subregion(x, y), tile.subregion(k));
                        seen[(y * w + x) as usize] += 1;
                        n += 1;
                    }
                    assert!(n > 0 && n <= TILE_SIZE * TILE_SIZE);
                }
                assert!(seen.iter().all(|&c| c == 1), "{w}x{h} K {k}");
            }
        }
    }

    #[test]
    fn z_order_takes_every_pixel_once_in_compact_blocks() {
        for (w, h) in [(16, 16), (17, 33), (100, 37), (5, 3)] {
            for k in [1, 3] {
                for tile in tiles(w, h, k) {
                    let rows: Vec<[u32; 2]> = tile.pixels(k).collect();
                    let z: Vec<(usize, [u32; 2])> = tile.pixels_z_order(k).collect();
                    assert_eq!(z.len(), rows.len());
                    let mut seen = vec![false; rows.len()];
                    for &(slot, pixel) in &z {
                        assert_eq!(rows[slot], pixel);
                        assert_eq!(tile.pixel(k, slot), pixel);
                        assert!(!std::mem::replace(&mut seen[slot], true));
                    }
                    if tile.pixel_count() == (TILE_SIZE * TILE_SIZE) as usize {
                        // Every eight consecutive pixels form a 4 x 2 block.
                        for eight in z.chunks(8) {
                            let (xs, ys) =
                                (eight.iter().map(|p| p.1[0]), eight.iter().map(|p| p.1[1]));
                            let span =
                                |v: Vec<u32>| v.iter().max().unwrap() - v.iter().min().unwrap();
                            assert_eq!(span(xs.collect()), 3 * k);
                            assert_eq!(span(ys.collect()), k);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn bands_write_every_pixel_of_their_tiles_in_place_order() {
        for (w, h) in [
            (0, 0),
            (0, 5),
            (5, 0),
            (1, 1),
            (5, 3),
            (17, 33),
            (100, 37),
            (130, 260),
        ] {
            for k in [1, 2, 3, 8, 200] {
                for n in [0, 1, 2] {
                    let order = TileOrder::new(w, h, k).unwrap();
                    let mut image = vec![usize::MAX; (w * h) as usize * n];
                    let mut tiles = 0;
                    for band in order.bands(&mut image, n).unwrap() {
                        let Band {
                            tiles: band_tiles,
                            mut rows,
                        } = band;
                        for pair in band_tiles.windows(2) {
                            let (a, b) = (pair[0], pair[1]);
                            assert_eq!((a.sub[1], a.first[1]), (b.sub[1], b.first[1]));
                            // The K tiles at one place follow each other.
                            if a.first == b.first {
                                assert_eq!(b.sub[0], a.sub[0] + 1, "{w}x{h} K {k}");
                            } else {
                                assert_eq!(b.sub[0], 0, "{w}x{h} K {k}: {b:?} after {a:?}");
                            }
                        }
                        for tile in band_tiles {
                            let values: Vec<usize> = tile
                                .pixels(k)
                                .flat_map(|[x, y]| {
                                    (0..n).map(move |c| (y * w + x) as usize * n + c)
                                })
                                .collect();
                            rows.put(tile, &values);
                            tiles += 1;
                        }
                    }
                    assert_eq!(tiles, super::tiles(w, h, k).len(), "{w}x{h} K {k}");
                    let wrong = image.iter().enumerate().position(|(i, &v)| v != i);
                    assert_eq!(wrong, None, "{w}x{h} K {k}, {n} per pixel");
                }
            }
        }
        let order = TileOrder::new(5, 3, 2).unwrap();
        assert!(order.bands(&mut [0u8; 29], 2).is_err());
        assert!(order.bands(&mut [0u8; 30], 2).is_ok());
        // A band refuses another band's tile, even one with as many rows and pixels.
        let order = TileOrder::new(4, 4, 2).unwrap();
        let mut image = [0u8; 16];
        let mut bands = order.bands(&mut image, 1).unwrap();
        let (ours, other) = (*bands[0].tiles[0], *bands[1].tiles[0]);
        assert_eq!((ours.count, ours.sub[0]), (other.count, other.sub[0]));
        let values = vec![1; other.pixel_count()];
        let put = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            bands[0].rows.put(&other, &values)
        }));
        assert!(put.is_err());
        bands[0].rows.put(&ours, &values);
    }

    #[test]
    fn tile_order_refuses_what_it_cannot_address() {
        assert!(TileOrder::new(4, 4, 0).is_err());
        assert!(TileOrder::new(4, 4, 1025).is_err());
        assert!(TileOrder::new(65536, 65536, 8).is_err());
    }

    #[test]
    fn full_hd_with_k_8_has_the_papers_tile_count() {
        // 1920x1080 with 8x8 subregions of 240x135 pixels: 15 x 9 tiles each, 8,640 tiles
        // (the last row of each subregion's tiles is 7 pixels high).
        let t = tiles(1920, 1080, 8);
        assert_eq!(t.len(), 64 * 15 * 9);
        assert_eq!(t.iter().filter(|t| t.count == [16, 7]).count(), 64 * 15);
    }
}
