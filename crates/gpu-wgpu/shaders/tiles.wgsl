// Interleaved-subregion tiles shared by tile_depth.wgsl and tiled_cull.wgsl (prepended to
// both). Structs mirror src/gpu_types.rs (GpuCullParams, GpuTileFrusta).

struct CullParams {
    rotation: array<vec4<f32>, 3>,
    eye: vec4<f32>,
    // (aspect tan(yfov/2), tan(yfov/2), W, H)
    image: vec4<f32>,
    width: u32,
    height: u32,
    k: u32,
    tiles_x: u32,
    tiles_y: u32,
    tile_count: u32,
    vpl_count: u32,
    frustum_slack: f32,
    mode: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

struct TileFrusta {
    // (u0, v0, u1, v1) at unit depth.
    rect: vec4<f32>,
    // near [z0, z1], far [z0, z1].
    ranges: vec4<f32>,
    // x: cluster mask (bit 0 near, bit 1 far); yz: the range of the tile's subregion's VPLs
    // in the partition's order.
    info: vec4<u32>,
}

const TILE: u32 = 16u;
const NO_LIST: u32 = 0xffffffffu;
const F32_MAX: f32 = 3.40282347e38;

// Tile t of the uniform per-subregion grid (paper supplemental Listing 2): its subregion
// (sx, sy), its first pixel (fx, fy) in the subregion image and its pixel counts (cx, cy),
// 0 past the subregion image's edge. Pixel (a, b) of the tile is screen pixel
// (sx + K (fx + a), sy + K (fy + b)).
struct Tile {
    subregion: u32,
    sx: u32,
    sy: u32,
    fx: u32,
    fy: u32,
    cx: u32,
    cy: u32,
}

fn subregion_extent(s: u32, size: u32, k: u32) -> u32 {
    if s >= size {
        return 0u;
    }
    return (size - s + k - 1u) / k;
}

fn tile_of(t: u32, p: CullParams) -> Tile {
    let per_sub = p.tiles_x * p.tiles_y;
    let s = t / per_sub;
    let local = t % per_sub;
    let sx = s % p.k;
    let sy = s / p.k;
    let fx = (local % p.tiles_x) * TILE;
    let fy = (local / p.tiles_x) * TILE;
    let w = subregion_extent(sx, p.width, p.k);
    let h = subregion_extent(sy, p.height, p.k);
    var cx = 0u;
    var cy = 0u;
    if fx < w && fy < h {
        cx = min(TILE, w - fx);
        cy = min(TILE, h - fy);
    }
    return Tile(s, sx, sy, fx, fy, cx, cy);
}

fn finite3(v: vec3<f32>) -> bool {
    return all(abs(v) <= vec3<f32>(F32_MAX));
}
