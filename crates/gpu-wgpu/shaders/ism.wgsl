// Imperfect shadow maps (Ritschel et al. 2008), as VSGL section 5 uses them for V(x_p, mu_v)
// of eq. (3): one full-sphere octahedral distance map about each VSGL's mu_v, filled by
// projecting every caster point (sampled uniformly by area over the scene, src/ism_pass.rs)
// into every map with atomicMin on the distance's f32 bits (non-negative floats order as
// their u32 bits; empty texels hold +inf). Each point is a disc (position, normal, radius
// from its share of the scene's area): it writes its own distance to its own texel, and to
// each texel within its angular radius (at most max_splat texels away, clamped at the map's
// border, not wrapped across the octahedral seams) the distance along the texel's centre
// direction to the disc, where that ray hits it, so that surfaces close without a hole fill.
// Each map draws its own run of points_per_map casters (a random subset: the casters are
// independent samples); holes are filled afterwards by ism_fill.wgsl.
// ism_map.wgsl comes first. Linear workgroup index wid.y * num_workgroups.x + wid.x.

struct Caster {
    // xyz position, w the disc radius.
    position_radius: vec4<f32>,
    // xyz unit normal.
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> ism: IsmParams;
@group(0) @binding(1) var<storage, read_write> depth: array<atomic<u32>>;
@group(0) @binding(2) var<storage, read> casters: array<Caster>;
@group(0) @binding(3) var<storage, read> centres: array<vec4<f32>>;


const WORKGROUP: u32 = 64u;
// The bits of +inf: an empty texel.
const EMPTY: u32 = 0x7f800000u;

// Every texel of every map to +inf.
@compute @workgroup_size(64)
fn clear(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if i < ism.map_count * ism.resolution * ism.resolution {
        atomicStore(&depth[i], EMPTY);
    }
}

// Where map `map`'s run of casters starts: a hash of its index (pcg), uniform over the casters.
fn map_offset(map: u32) -> u32 {
    var h = map * 747796405u + 2891336453u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    h = (h >> 22u) ^ h;
    return h % ism.point_count;
}

// One invocation per (map, point of its run): item = map * points_per_map + j.
@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let item = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if item >= ism.points_per_map * ism.map_count {
        return;
    }
    let map = item / ism.points_per_map;
    let j = item % ism.points_per_map;
    let c = casters[(map_offset(map) + j) % ism.point_count];
    let d = c.position_radius.xyz - centres[map].xyz;
    let r = c.position_radius.w;
    let dist = length(d);
    if !(dist > 0.0) {
        return;
    }
    let res = ism.resolution;
    let base = map * res * res;
    let own = oct_texel(d / dist, res);
    atomicMin(&depth[base + own.y * res + own.x], bitcast<u32>(dist));
    // The disc's angular radius in texels; texels along the map's diagonals are up to
    // sqrt(2) narrower than texel_angle.
    let angle = asin(min(r / dist, 1.0));
    let k = i32(min(u32(ceil(1.4142135 * angle / ism.texel_angle)), ism.max_splat));
    let n = c.normal.xyz;
    let plane = dot(d, n);
    for (var dy = -k; dy <= k; dy++) {
        let y = i32(own.y) + dy;
        if y < 0 || y >= i32(res) {
            continue;
        }
        for (var dx = -k; dx <= k; dx++) {
            let x = i32(own.x) + dx;
            if x < 0 || x >= i32(res) || (dx == 0 && dy == 0) {
                continue;
            }
            let dir = oct_decode((vec2<f32>(f32(x), f32(y)) + vec2<f32>(0.5)) / f32(res));
            let denom = dot(dir, n);
            if abs(denom) < 1e-6 {
                continue;
            }
            let t = plane / denom;
            let off = dir * t - d;
            if t > 0.0 && dot(off, off) <= r * r {
                atomicMin(&depth[base + u32(y) * res + u32(x)], bitcast<u32>(t));
            }
        }
    }
}
