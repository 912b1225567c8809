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
    pub(crate) fn pixel_count(&self) -> usize {
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

/// The pixels of an image laid out tile by tile: every tile of the culling, in its order
/// (subregion by subregion, row-major within each), each
/// tile's pixels row by row, so a tile's pixels are one contiguous run (the subregion images
/// of section 6 deinterleaved). Shading in this order reads each tile's G-buffer samples with
/// the subregion's stride K and writes one run per tile; [`TileOrder::slot`] maps a screen
/// pixel back to its place in the run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TileOrder {
    tiles: Vec<Tile>,
    /// Where tile t's run starts; the last entry is the pixel count.
    starts: Vec<usize>,
    /// Per subregion (row-major in the K x K grid, clipped to the image): its first tile and
    /// tiles per row.
    first_tile: Vec<u32>,
    tiles_per_row: Vec<u32>,
    k: u32,
    width: u32,
}

impl TileOrder {
    /// The tile order of a `width` x `height` image with interleaving factor `k`; errors when
    /// K is not in 1..=1024 or the image has 2³² pixels or more (pixel indices are u32).
    pub fn new(width: u32, height: u32, k: u32) -> Result<Self, CullError> {
        check(Interleaving { k, seed: 0 }, 0)?;
        if u32::try_from(u64::from(width) * u64::from(height)).is_err() {
            return Err(CullError::Input(format!(
                "a {width}x{height} image has more pixels than 32-bit indices address"
            )));
        }
        let tiles = tiles(width, height, k);
        let mut starts = Vec::with_capacity(tiles.len() + 1);
        starts.push(0);
        let (mut first_tile, mut tiles_per_row) = (Vec::new(), Vec::new());
        for (t, tile) in tiles.iter().enumerate() {
            starts.push(starts[t] + tile.pixel_count());
            if tile.first == [0, 0] {
                first_tile.push(t as u32);
                tiles_per_row
                    .push(subregion_size(width, height, k, tile.sub)[0].div_ceil(TILE_SIZE));
            }
        }
        Ok(Self {
            tiles,
            starts,
            first_tile,
            tiles_per_row,
            k,
            width,
        })
    }

    /// The tiles, in order.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// The length of each tile's run, in order.
    pub fn run_lengths(&self) -> impl Iterator<Item = usize> + '_ {
        self.starts.windows(2).map(|w| w[1] - w[0])
    }

    /// The place of screen pixel (x, y) in the tile-by-tile layout.
    #[inline]
    pub fn slot(&self, x: u32, y: u32) -> usize {
        let k = self.k;
        let sub = (y % k) * k.min(self.width) + x % k;
        let (a, b) = (x / k, y / k);
        let t = self.first_tile[sub as usize]
            + (b / TILE_SIZE) * self.tiles_per_row[sub as usize]
            + a / TILE_SIZE;
        let tile = &self.tiles[t as usize];
        self.starts[t as usize] + ((b % TILE_SIZE) * tile.count[0] + a % TILE_SIZE) as usize
    }

    /// Calls `f(x, slot(x, y))` for every pixel of row `y`, x running over each residue
    /// x mod K in turn: the slots of one residue are consecutive within a tile, so
    /// [`Self::slot`] (four divisions) is formed only at tile edges.
    pub fn for_each_in_row(&self, y: u32, mut f: impl FnMut(u32, usize)) {
        for r in 0..self.k.min(self.width) {
            let mut slot = self.slot(r, y);
            let (mut x, mut column) = (r, 0);
            loop {
                f(x, slot);
                x = match x.checked_add(self.k) {
                    Some(next) if next < self.width => next,
                    _ => break,
                };
                column += 1;
                slot = if column % TILE_SIZE == 0 {
                    self.slot(x, y)
                } else {
                    slot + 1
                };
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
    fn tile_order_slots_are_the_tiles_pixels_in_order() {
        for (w, h) in [
            (0, 0),
            (0, 5),
            (1, 1),
            (5, 3),
            (17, 33),
            (100, 37),
            (130, 260),
        ] {
            for k in [1, 2, 3, 8, 200] {
                let order = TileOrder::new(w, h, k).unwrap();
                let mut next = 0;
                for tile in order.tiles() {
                    for [x, y] in tile.pixels(k) {
                        assert_eq!(order.slot(x, y), next, "{w}x{h} K {k}: ({x}, {y})");
                        next += 1;
                    }
                }
                assert_eq!(next, (w * h) as usize);
                assert_eq!(order.run_lengths().sum::<usize>(), next);
                for y in 0..h {
                    let mut seen = vec![false; w as usize];
                    order.for_each_in_row(y, |x, slot| {
                        assert_eq!(slot, order.slot(x, y), "{w}x{h} K {k}: ({x}, {y})");
                        assert!(!std::mem::replace(&mut seen[x as usize], true));
                    });
                    assert!(seen.iter().all(|&s| s), "{w}x{h} K {k}: row {y}");
                }
            }
        }
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
