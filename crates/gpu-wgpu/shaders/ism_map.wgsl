// Imperfect shadow maps (Ritschel et al. 2008; VSGL section 5): the parameters and the
// full-sphere octahedral parameterisation shared by the splatting pass (ism.wgsl) and the
// visibility lookup of vsgl_shade.wgsl. Mirrors src/ism_pass.rs GpuIsmParams.

struct IsmParams {
    // Caster points and maps (one per VSGL, about its mu_v).
    point_count: u32,
    map_count: u32,
    // Texels per side of each square octahedral map.
    resolution: u32,
    // The largest splat, in texels from the point's own texel.
    max_splat: u32,
    // pi / resolution: the angle of one texel along the map's axes.
    texel_angle: f32,
    // The tracer's surface offset (Tracer::epsilon): receivers are lifted by it along their
    // geometric normal and segments shorter than twice it are unoccluded, as on the CPU.
    lift: f32,
    // Depth bias in texel angles times the receiver's distance: constant and times the tangent
    // of the receiver's incidence (slope-scaled).
    bias_constant: f32,
    bias_slope: f32,
    // The points each map draws: a run of the caster array from an offset of its own
    // (map_offset), wrapping; point_count when every map takes every point.
    points_per_map: u32,
    // Pull-push hole filling: an empty texel takes the mean depth of the filled texels of its
    // ancestor 2^l texels wide, the nearest l in 1..=fill_levels where any is filled; 0: off.
    fill_levels: u32,
    pad0: u32,
    pad1: u32,
}

fn oct_sign(v: vec2<f32>) -> vec2<f32> {
    return select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
}

// A unit direction to [0, 1]^2 (octahedral, the lower hemisphere folded to the corners).
fn oct_encode(n: vec3<f32>) -> vec2<f32> {
    var p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if n.z < 0.0 {
        p = (vec2<f32>(1.0) - abs(p.yx)) * oct_sign(p);
    }
    return p * 0.5 + vec2<f32>(0.5);
}

// The unit direction of a point of [0, 1]^2.
fn oct_decode(uv: vec2<f32>) -> vec3<f32> {
    let f = uv * 2.0 - vec2<f32>(1.0);
    var n = vec3<f32>(f.x, f.y, 1.0 - abs(f.x) - abs(f.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    return normalize(n);
}

// The texel of a unit direction.
fn oct_texel(n: vec3<f32>, res: u32) -> vec2<u32> {
    let uv = oct_encode(n) * f32(res);
    return min(vec2<u32>(max(uv, vec2<f32>(0.0))), vec2<u32>(res - 1u));
}
