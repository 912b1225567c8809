// Tiled culling and shading in one pass (the paper's Fig. 2; sections 5-6): one 256-thread
// workgroup per 16 x 16 tile of an interleaved subregion image, one thread per pixel, after
// the bounds, partition and tile-depth passes. The tile's subregion's VPLs are taken 256 at
// a time (in the partition's order, ascending in the VPL index): each thread tests one
// against the tile's Modified HalfZ frusta (frustum_tests.wgsl tile_hits, as tiled_cull.wgsl) and
// sets its bit in the near and far masks in workgroup memory (mark_hits: hits_subgroup.wgsl
// with subgroup operations, hits_atomic.wgsl without, appended); then each pixel shades the
// VPLs of its cluster's mask in order (vpl_eval.wgsl). The light lists live only in those
// masks, so nothing is counted, scanned or stored, and each pixel sums the same VPLs in the
// same order as shade.wgsl over tiled_cull.wgsl's lists. tiles.wgsl, bound.wgsl,
// frustum_tests.wgsl, brdf.wgsl, gsample.wgsl, gvpl.wgsl and vpl_eval.wgsl are prepended.

@group(0) @binding(0) var<uniform> params: CullParams;
@group(0) @binding(1) var<uniform> shading: ShadeParams;
@group(0) @binding(2) var<storage, read> frusta: array<TileFrusta>;
@group(0) @binding(3) var<storage, read> bounds: array<Bound>;
// The subregions' VPLs (partition.wgsl): the tile's are order[info.y .. info.z].
@group(0) @binding(4) var<storage, read> order: array<u32>;
@group(0) @binding(5) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(6) var<storage, read> samples: array<Sample>;
// The G-buffer positions [x, y, z, 1] (gsample.wgsl).
@group(0) @binding(7) var<storage, read> positions: array<vec4<f32>>;
// Each pixel's cluster list, 2 t + 0 near or 2 t + 1 far (tile_depth.wgsl); NO_LIST: none.
@group(0) @binding(8) var<storage, read> pixel_list: array<u32>;
// RGB per pixel, every pixel written.
@group(0) @binding(9) var<storage, read_write> image: array<f32>;

const GROUP: u32 = 256u;
const WORDS: u32 = 8u;

// The batch's VPLs that may touch the near and far cluster (bit e of word e / 32).
var<workgroup> near_bits: array<atomic<u32>, 8>;
var<workgroup> far_bits: array<atomic<u32>, 8>;
// The VPL index of each entry of the batch.
var<workgroup> batch: array<u32, 256>;
var<workgroup> tile_mask: u32;
var<workgroup> sub_range: vec2<u32>;

@compute @workgroup_size(256)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let t = wid.y * groups.x + wid.x;
    if t >= params.tile_count {
        return;
    }
    if lid == 0u {
        tile_mask = frusta[t].info.x;
        sub_range = frusta[t].info.yz;
    }
    let mask = workgroupUniformLoad(&tile_mask);
    let range = workgroupUniformLoad(&sub_range);
    let tile = tile_of(t, params);
    let a = lid % TILE;
    let b = lid / TILE;
    let has_pixel = a < tile.cx && b < tile.cy;
    let pixel = (tile.sy + params.k * (tile.fy + b)) * params.width
        + tile.sx + params.k * (tile.fx + a);
    // 0 near, 1 far, 2 nothing to shade.
    var cluster = 2u;
    var s: Sample;
    var x = vec3<f32>(0.0);
    if has_pixel {
        let list = pixel_list[pixel];
        s = samples[pixel];
        if list != NO_LIST && sample_present(s) {
            cluster = list - 2u * t;
            x = positions[pixel].xyz;
        }
    }
    var sum = vec3<f32>(0.0);
    if mask != 0u {
        let f = frusta[t];
        for (var base = range.x; base < range.y; base += GROUP) {
            if lid < WORDS {
                atomicStore(&near_bits[lid], 0u);
                atomicStore(&far_bits[lid], 0u);
            }
            workgroupBarrier();
            let j = base + lid;
            var hit = vec2<u32>(0u);
            if j < range.y {
                let i = order[j];
                batch[lid] = i;
                hit = tile_hits(bounds[i], f, mask);
            }
            mark_hits(lid, hit);
            workgroupBarrier();
            if cluster < 2u {
                for (var w = 0u; w < WORDS; w++) {
                    var bits = select(atomicLoad(&far_bits[w]), atomicLoad(&near_bits[w]),
                                      cluster == 0u);
                    while bits != 0u {
                        let e = 32u * w + firstTrailingBit(bits);
                        bits &= bits - 1u;
                        let c = vpl_contribution(s, x, vpls[batch[e]], shading.delta);
                        if any(c != vec3<f32>(0.0)) {
                            sum += c * shading.scale;
                        }
                    }
                }
            }
            workgroupBarrier();
        }
    }
    if has_pixel {
        image[3u * pixel] = sum.x;
        image[3u * pixel + 1u] = sum.y;
        image[3u * pixel + 2u] = sum.z;
    }
}
