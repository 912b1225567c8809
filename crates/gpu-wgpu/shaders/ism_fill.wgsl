// Pull-push hole filling of imperfect shadow maps (Ritschel et al. 2008, section 3.3), after
// the splatting of ism.wgsl: `pull` builds pyramid level pull_level.x, each texel the mean
// depth of its 2x2 children where all but one of them are filled (three of four; at a map's
// odd border, one of two): a gap inside a surface; at a silhouette against empty directions
// fewer are. +inf elsewhere. `fill` gives each
// empty texel of the maps the depth of its nearest filled ancestor, levels 1 to fill_levels.
// ism_map.wgsl comes first. Linear workgroup index wid.y * num_workgroups.x + wid.x.

@group(0) @binding(0) var<uniform> ism: IsmParams;
@group(0) @binding(1) var<storage, read_write> depth: array<atomic<u32>>;
// Levels 1..=fill_levels, level-major, map-major within a level.
@group(0) @binding(2) var<storage, read_write> pyramid: array<f32>;
@group(0) @binding(3) var<uniform> pull_level: vec4<u32>;

const WORKGROUP: u32 = 64u;
// The bits of +inf: an empty texel.
const EMPTY: u32 = 0x7f800000u;
const F32_MAX: f32 = 3.40282347e38;

// Texels per side of pyramid level l (level 0: the map itself).
fn level_size(l: u32) -> u32 {
    return (ism.resolution + (1u << l) - 1u) >> l;
}

// The first float of level l >= 1 in the pyramid.
fn level_start(l: u32) -> u32 {
    var start = 0u;
    for (var i = 1u; i < l; i++) {
        let r = level_size(i);
        start += ism.map_count * r * r;
    }
    return start;
}

// The depth of texel (x, y) of map `map` at level l (+inf: nothing filled there).
fn level_depth(l: u32, map: u32, x: u32, y: u32) -> f32 {
    let r = level_size(l);
    if l == 0u {
        return bitcast<f32>(atomicLoad(&depth[map * r * r + y * r + x]));
    }
    return pyramid[level_start(l) + map * r * r + y * r + x];
}

// Level pull_level.x from the level below: the mean of the filled children.
@compute @workgroup_size(64)
fn pull(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let l = pull_level.x;
    let r = level_size(l);
    let i = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if i >= ism.map_count * r * r {
        return;
    }
    let map = i / (r * r);
    let x = i % r;
    let y = (i / r) % r;
    let below = level_size(l - 1u);
    var sum = 0.0;
    var count = 0.0;
    var children = 0.0;
    for (var dy = 0u; dy < 2u; dy++) {
        for (var dx = 0u; dx < 2u; dx++) {
            let cx = 2u * x + dx;
            let cy = 2u * y + dy;
            if cx < below && cy < below {
                children += 1.0;
                let d = level_depth(l - 1u, map, cx, cy);
                if d <= F32_MAX {
                    sum += d;
                    count += 1.0;
                }
            }
        }
    }
    let enough = count >= max(children - 1.0, 1.0);
    pyramid[level_start(l) + i] = select(bitcast<f32>(EMPTY), sum / count, enough);
}

// Each empty texel of the maps takes its nearest filled ancestor's depth (levels 1 to
// fill_levels).
@compute @workgroup_size(64)
fn fill(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let res = ism.resolution;
    let i = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if i >= ism.map_count * res * res || atomicLoad(&depth[i]) != EMPTY {
        return;
    }
    let map = i / (res * res);
    let x = i % res;
    let y = (i / res) % res;
    for (var l = 1u; l <= ism.fill_levels; l++) {
        let d = level_depth(l, map, x >> l, y >> l);
        if d <= F32_MAX {
            atomicStore(&depth[i], bitcast<u32>(d));
            return;
        }
    }
}
