// Modified HalfZ depth bounds per tile (Stewart, GPU Pro 6; paper section 5.1), the GPU twin
// of crates/cull/src/tiled.rs (gather) + depth.rs (DepthSplit::HalfZ) + frusta.rs (set):
// one 16 x 16 workgroup per tile of an interleaved subregion (tiles.wgsl, prepended). Each
// sample is mapped to the culling view, R (p - eye); the tile's depth range [z_min, z_max]
// is split at half_z = (z_min + z_max) / 2 into a near cluster [z_min, max z < half_z] and a
// far cluster [min z >= half_z, z_max]. The tile rectangle at unit depth bounds its pixels'
// footprints and every sample's projection; rectangle and ranges grow by the frustum slack.
// Each pixel gets the list of its cluster (2 t + 0 near, 2 t + 1 far; NO_LIST if no sample).

@group(0) @binding(0) var<uniform> params: CullParams;
// World-space G-buffer positions; w = 0 where the pixel has no sample.
@group(0) @binding(1) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> frusta: array<TileFrusta>;
@group(0) @binding(3) var<storage, read_write> pixel_list: array<u32>;
// GpuCullStatus: [0] smallest pixel whose sample is not in front of the camera.
@group(0) @binding(4) var<storage, read_write> status: array<atomic<u32>, 4>;
// The subregions' VPLs (partition.wgsl): subregion s holds order[sub_offsets[s] ..
// sub_offsets[s + 1]]; each tile's range goes to its frusta (info.yz).
@group(0) @binding(5) var<storage, read> sub_offsets: array<u32>;

var<workgroup> lows: array<vec4<f32>, 256>;
var<workgroup> highs: array<vec4<f32>, 256>;

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
// image_rect): (2 x / W - 1) aspect tan(yfov/2), (2 y / H - 1) tan(yfov/2).
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
            } else {
                atomicMin(&status[0], pixel);
            }
        }
    }
    lows[lid] = select(vec4<f32>(F32_MAX), vec4<f32>(uv, z, 0.0), sample);
    highs[lid] = select(vec4<f32>(-F32_MAX), vec4<f32>(uv, z, 0.0), sample);
    reduce(lid);
    let lo = lows[0];
    let hi = highs[0];
    let half_z = 0.5 * (lo.z + hi.z);
    let near = sample && z < half_z;
    workgroupBarrier();
    // Second reduction: the far cluster's smallest depth, the near cluster's largest.
    lows[lid] = vec4<f32>(select(F32_MAX, z, sample && !near), 0.0, 0.0, 0.0);
    highs[lid] = vec4<f32>(select(-F32_MAX, z, near), 0.0, 0.0, 0.0);
    reduce(lid);
    if has_pixel {
        pixel_list[pixel] = select(NO_LIST, 2u * t + select(1u, 0u, near), sample);
    }
    if lid != 0u {
        return;
    }
    let range = vec2<u32>(sub_offsets[tile.subregion], sub_offsets[tile.subregion + 1u]);
    if !(lo.z <= hi.z) {
        frusta[t] = TileFrusta(vec4<f32>(0.0), vec4<f32>(0.0), vec4<u32>(0u, range, 0u));
        return;
    }
    let near_hi = highs[0].x;
    let far_lo = lows[0].x;
    var mask = 0u;
    if near_hi > -F32_MAX {
        mask |= 1u;
    }
    if far_lo < F32_MAX {
        mask |= 2u;
    }
    // The rectangle of the pixels' footprints [x0, x1) x [y0, y1), grown to every sample's
    // projection, then by the slack (frusta.rs set).
    let x0 = tile.sx + params.k * tile.fx;
    let y0 = tile.sy + params.k * tile.fy;
    let x1 = tile.sx + params.k * (tile.fx + tile.cx - 1u) + 1u;
    let y1 = tile.sy + params.k * (tile.fy + tile.cy - 1u) + 1u;
    let rect_lo = min(image_point(x0, y0), lo.xy);
    let rect_hi = max(image_point(x1, y1), hi.xy);
    let extent = max(abs(rect_lo), abs(rect_hi));
    let pad = params.frustum_slack * (1.0 + max(extent.x, extent.y));
    let shrink = 1.0 - params.frustum_slack;
    let grow = 1.0 + params.frustum_slack;
    frusta[t] = TileFrusta(
        vec4<f32>(rect_lo - pad, rect_hi + pad),
        vec4<f32>(
            select(vec2<f32>(0.0), vec2<f32>(lo.z * shrink, near_hi * grow), (mask & 1u) != 0u),
            select(vec2<f32>(0.0), vec2<f32>(far_lo * shrink, hi.z * grow), (mask & 2u) != 0u),
        ),
        vec4<u32>(mask, range, 0u),
    );
}
