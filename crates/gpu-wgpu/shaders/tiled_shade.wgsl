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
//
// Before it evaluates a VPL, a pixel tests its own point against the VPL's bound (the tile
// tested the bound against the cluster's frustum): a point outside has p <= xi there, its
// contribution is exactly 0 and is skipped, so the sum is the same, bit for bit. Most of a
// tile's listed pairs are such pixels (the bound's tile-sized false positives); their test
// costs about twenty operations where vpl_contribution costs a GGX lobe. The test is
// conservative for f32 rounding: see unit_ball and inside.

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
// Each hit entry's bound as a unit ball (unit_ball): the columns of M, C in their w.
var<workgroup> ball_x: array<vec4<f32>, 256>;
var<workgroup> ball_y: array<vec4<f32>, 256>;
var<workgroup> ball_z: array<vec4<f32>, 256>;
// Its rounding allowances (Ball.slack).
var<workgroup> ball_slack: array<vec2<f32>, 256>;
var<workgroup> tile_mask: u32;
var<workgroup> sub_range: vec2<u32>;

// Relative error allowed for the f32 rounding of the pixel test's operands and operations,
// about 34 ulps: the columns of M and C carry a few roundings each (bounds.wgsl), the view
// point R (x - eye) a few more, and each component of M p - C three fma roundings.
const BALL_ROUNDING: f32 = 4e-6;

// A bound as the unit ball |M p - C| <= 1 of view-space points p (bound.wgsl): an ellipsoid
// as it is stored (M = BS, C = BS c), a sphere of squared radius r2 around c as M = I / r,
// C = c / r. slack: allowances for rounding, x for C and y per unit of the point's size
// (inside). A sphere too small or too large for 1 / r in f32 gets M = 0, C = 0 and an
// allowance no point exceeds: every pixel is then evaluated.
struct Ball {
    m: mat3x3<f32>,
    c: vec3<f32>,
    slack: vec2<f32>,
}

fn l1(v: vec3<f32>) -> f32 {
    return abs(v.x) + abs(v.y) + abs(v.z);
}

fn unit_ball(b: Bound) -> Ball {
    var m = mat3x3<f32>(b.bs[0].xyz, b.bs[1].xyz, b.bs[2].xyz);
    var c = b.center.xyz;
    if b.kind == BOUND_SPHERE {
        let inv_r = 1.0 / sqrt(b.center.w);
        m = mat3x3<f32>(vec3<f32>(inv_r, 0.0, 0.0), vec3<f32>(0.0, inv_r, 0.0),
                        vec3<f32>(0.0, 0.0, inv_r));
        c = b.center.xyz * inv_r;
    }
    let norm = max(l1(m[0]), max(l1(m[1]), l1(m[2])));
    let slack = BALL_ROUNDING * vec2<f32>(l1(c), norm);
    if !(finite3(c) && abs(norm) <= F32_MAX && abs(slack.x) <= F32_MAX
         && abs(slack.y) <= F32_MAX) {
        return Ball(mat3x3<f32>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0)), vec3<f32>(0.0),
                    vec2<f32>(F32_MAX, 0.0));
    }
    return Ball(m, c, slack);
}

// Whether view-space point p (of size: |p|_1 + |x|_1 + |eye|_1 for the world point x it was
// mapped from) may lie in entry e's bound: |M p - C|^2 against (1 + its allowances)^2, and
// always where the square is not finite (an overflow says nothing).
fn inside(e: u32, p: vec3<f32>, size: f32) -> bool {
    let mx = ball_x[e];
    let my = ball_y[e];
    let mz = ball_z[e];
    let q = mx.xyz * p.x + my.xyz * p.y + mz.xyz * p.z - vec3<f32>(mx.w, my.w, mz.w);
    let d2 = dot(q, q);
    let slack = ball_slack[e];
    let t = 1.0 + BALL_ROUNDING + slack.x + slack.y * size;
    return !(d2 > t * t && d2 <= F32_MAX);
}

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
    var r: Receiver;
    // The pixel's point in the culling view and its size (inside).
    var view = vec3<f32>(0.0);
    var size = 0.0;
    if has_pixel {
        let list = pixel_list[pixel];
        let s = samples[pixel];
        if list != NO_LIST && sample_present(s) {
            cluster = list - 2u * t;
            let x = positions[pixel].xyz;
            r = receiver(s, x);
            let rot = mat3x3<f32>(params.rotation[0].xyz, params.rotation[1].xyz,
                                  params.rotation[2].xyz);
            view = rot * (x - params.eye.xyz);
            size = l1(view) + l1(x) + l1(params.eye.xyz);
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
                let b = bounds[i];
                hit = tile_hits(b, f, mask);
                if any(hit != vec2<u32>(0u)) {
                    let ball = unit_ball(b);
                    ball_x[lid] = vec4<f32>(ball.m[0], ball.c.x);
                    ball_y[lid] = vec4<f32>(ball.m[1], ball.c.y);
                    ball_z[lid] = vec4<f32>(ball.m[2], ball.c.z);
                    ball_slack[lid] = ball.slack;
                }
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
                        if inside(e, view, size) {
                            let c = vpl_contribution(r, vpls[batch[e]], shading.delta);
                            if any(c != vec3<f32>(0.0)) {
                                sum += c * shading.scale;
                            }
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
