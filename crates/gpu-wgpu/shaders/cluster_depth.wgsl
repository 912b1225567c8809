// Depth clusters of exponential slices per tile, the GPU twin of crates/cull/src/tiled.rs
// (cull: the G-buffer's depth range; gather) + depth.rs (DepthSplit::Slices) + frusta.rs
// (set): one 16 x 16 workgroup per tile of an interleaved subregion (tiles.wgsl and
// clusters.wgsl prepended), run twice.
// - params.mode 0 (range): the smallest and largest view depth of all samples, into
//   depth_range as f32 bits (positive floats order like their bits); a sample not in front
//   of the camera is recorded in status[0].
// - params.mode 1 (split): slice s of [near, far] holds the depths near (far / near)^(s/32)
//   .. near (far / near)^((s+1)/32): s = floor((ln z - ln near) 32 / (ln far - ln near)),
//   clamped to 0..31 (depth.rs key; a difference of logarithms, which no ratio can overflow,
//   for the CPU's f64 ln(z / near)). Each occupied slice's range is [min z, max z] of its
//   samples; the rectangle bounds the tile's pixels' footprints and every sample's
//   projection; all grow by the frustum slack. Pixel p of tile t gets list 32 t + s
//   (NO_LIST without a sample).

@group(0) @binding(0) var<uniform> params: CullParams;
// World-space G-buffer positions; w = 0 where the pixel has no sample.
@group(0) @binding(1) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> frusta: array<ClusterFrusta>;
@group(0) @binding(3) var<storage, read_write> pixel_list: array<u32>;
// GpuCullStatus: [0] smallest pixel whose sample is not in front of the camera.
@group(0) @binding(4) var<storage, read_write> status: array<atomic<u32>, 4>;
// [0] bits of the smallest view depth, [1] of the largest.
@group(0) @binding(5) var<storage, read_write> depth_range: array<atomic<u32>, 2>;

const MODE_SPLIT: u32 = 1u;

var<workgroup> lows: array<vec2<f32>, 256>;
var<workgroup> highs: array<vec2<f32>, 256>;
var<workgroup> slice_lo: array<atomic<u32>, 32>;
var<workgroup> slice_hi: array<atomic<u32>, 32>;
var<workgroup> occupied: atomic<u32>;

// Min of `lows` and max of `highs` over the workgroup, into element 0.
fn reduce(lid: u32) {
    for (var stride = 128u; stride > 0u; stride >>= 1u) {
        workgroupBarrier();
        if lid < stride {
            lows[lid] = min(lows[lid], lows[lid + stride]);
            highs[lid] = max(highs[lid], highs[lid + stride]);
        }
    }
    workgroupBarrier();
}

// The image-plane coordinate at unit depth of pixel corner (x, y) (crates/cull/src/view.rs
// image_rect, as tile_depth.wgsl).
fn image_point(x: u32, y: u32) -> vec2<f32> {
    return (2.0 * vec2<f32>(f32(x), f32(y)) / params.image.zw - 1.0) * params.image.xy;
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
    let split = params.mode == MODE_SPLIT;
    if lid < SLICES {
        atomicStore(&slice_lo[lid], 0xffffffffu);
        atomicStore(&slice_hi[lid], 0u);
    }
    if lid == 0u {
        atomicStore(&occupied, 0u);
    }
    workgroupBarrier();
    let tile = tile_of(t, params);
    let a = lid % TILE;
    let b = lid / TILE;
    let has_pixel = a < tile.cx && b < tile.cy;
    let x = tile.sx + params.k * (tile.fx + a);
    let y = tile.sy + params.k * (tile.fy + b);
    let pixel = y * params.width + x;
    var sample = false;
    var z = 0.0;
    var uv = vec2<f32>(0.0);
    if has_pixel {
        let world = positions[pixel];
        if world.w != 0.0 {
            let rot = mat3x3<f32>(params.rotation[0].xyz, params.rotation[1].xyz,
                                  params.rotation[2].xyz);
            let p = rot * (world.xyz - params.eye.xyz);
            if p.z > 0.0 && finite3(p) {
                sample = true;
                z = p.z;
                uv = p.xy / p.z;
            } else if !split {
                atomicMin(&status[0], pixel);
            }
        }
    }
    if !split {
        lows[lid] = vec2<f32>(select(F32_MAX, z, sample), 0.0);
        highs[lid] = vec2<f32>(select(0.0, z, sample), 0.0);
        reduce(lid);
        if lid == 0u && lows[0].x <= highs[0].x {
            atomicMin(&depth_range[0], bitcast<u32>(lows[0].x));
            atomicMax(&depth_range[1], bitcast<u32>(highs[0].x));
        }
        return;
    }
    var slice = 0u;
    if sample {
        let log_near = log(bitcast<f32>(atomicLoad(&depth_range[0])));
        let span = log(bitcast<f32>(atomicLoad(&depth_range[1]))) - log_near;
        let scale = select(0.0, f32(SLICES) / span, span > 0.0);
        let key = floor((log(z) - log_near) * scale);
        slice = u32(clamp(key, 0.0, f32(SLICES - 1u)));
        atomicMin(&slice_lo[slice], bitcast<u32>(z));
        atomicMax(&slice_hi[slice], bitcast<u32>(z));
        atomicOr(&occupied, 1u << slice);
    }
    if has_pixel {
        pixel_list[pixel] = select(NO_LIST, SLICES * t + slice, sample);
    }
    lows[lid] = select(vec2<f32>(F32_MAX), uv, sample);
    highs[lid] = select(vec2<f32>(-F32_MAX), uv, sample);
    reduce(lid);
    let mask = atomicLoad(&occupied);
    if lid < SLICES {
        var range = vec2<f32>(0.0);
        if (mask & (1u << lid)) != 0u {
            range = vec2<f32>(bitcast<f32>(atomicLoad(&slice_lo[lid])) *
                                  (1.0 - params.frustum_slack),
                              bitcast<f32>(atomicLoad(&slice_hi[lid])) *
                                  (1.0 + params.frustum_slack));
        }
        frusta[t].ranges[lid] = range;
    }
    if lid != 0u {
        return;
    }
    if mask == 0u {
        frusta[t].rect = vec4<f32>(0.0);
        frusta[t].info = vec4<u32>(0u);
        return;
    }
    // The rectangle of the pixels' footprints [x0, x1) x [y0, y1), grown to every sample's
    // projection, then by the slack (frusta.rs set).
    let x0 = tile.sx + params.k * tile.fx;
    let y0 = tile.sy + params.k * tile.fy;
    let x1 = tile.sx + params.k * (tile.fx + tile.cx - 1u) + 1u;
    let y1 = tile.sy + params.k * (tile.fy + tile.cy - 1u) + 1u;
    let rect_lo = min(image_point(x0, y0), lows[0]);
    let rect_hi = max(image_point(x1, y1), highs[0]);
    let extent = max(abs(rect_lo), abs(rect_hi));
    let pad = params.frustum_slack * (1.0 + max(extent.x, extent.y));
    frusta[t].rect = vec4<f32>(rect_lo - pad, rect_hi + pad);
    frusta[t].info = vec4<u32>(mask, 0u, 0u, 0u);
}
