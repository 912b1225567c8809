// The bound-versus-frustum tests of Modified HalfZ (paper section 5.2, supplemental Listing 2),
// the GPU twin of crates/cull/src/frusta.rs, shared by tiled_cull.wgsl and
// clustered_cull.wgsl (bound.wgsl prepended). A cluster frustum is {z (u, v, 1) : (u, v) in
// the tile's rectangle at unit depth, z in a depth range}.

// What a bound is tested as: the ball |p - center|^2 <= r2 against boxes swept from the
// rectangle [lo, hi] (at unit depth, in the bound's test space) over a depth range.
struct BoundBox {
    lo: vec3<f32>,
    hi: vec3<f32>,
    center: vec3<f32>,
    r2: f32,
}

// The box {z w : w in [lo, hi], z in [z0, z1]} against the ball |p - c|^2 <= r2
// (frusta.rs Box3::swept + meets_ball; Listing 2's CalculateFrustumAABB and
// ComputeSquaredDistanceToBox).
fn meets(lo: vec3<f32>, hi: vec3<f32>, range: vec2<f32>, c: vec3<f32>, r2: f32) -> bool {
    let box_min = min(lo * range.x, lo * range.y);
    let box_max = max(hi * range.x, hi * range.y);
    let gap = max(max(box_min - c, c - box_max), vec3<f32>(0.0));
    return dot(gap, gap) <= r2;
}

fn box_meets(b: BoundBox, range: vec2<f32>) -> bool {
    return meets(b.lo, b.hi, range, b.center, b.r2);
}

// The test of bound `b` against frusta of the rectangle `rect` (u0, v0, u1, v1): spheres
// against the view-space rectangle, ellipsoids as the unit ball at BS c against the
// rectangle's corners mapped by BS, bounded (frusta.rs sphere_hits, ellipsoid_hits). False
// for bounds that are never listed.
fn bound_box(b: Bound, rect: vec4<f32>, out: ptr<function, BoundBox>) -> bool {
    if b.kind == BOUND_SPHERE {
        *out = BoundBox(vec3<f32>(rect.xy, 1.0), vec3<f32>(rect.zw, 1.0), b.center.xyz,
                        b.center.w);
        return true;
    }
    if b.kind == BOUND_ELLIPSOID {
        let u0 = b.bs[0].xyz * rect.x;
        let u1 = b.bs[0].xyz * rect.z;
        let v0 = b.bs[1].xyz * rect.y;
        let v1 = b.bs[1].xyz * rect.w;
        *out = BoundBox(b.bs[2].xyz + min(u0, u1) + min(v0, v1),
                        b.bs[2].xyz + max(u0, u1) + max(v0, v1), b.center.xyz, 1.0);
        return true;
    }
    return false;
}

// Which of a Modified HalfZ tile's clusters (x near, y far; TileFrusta of tiles.wgsl) the
// bound may touch: the whole tile first, then each cluster.
fn tile_hits(b: Bound, f: TileFrusta, mask: u32) -> vec2<u32> {
    var test: BoundBox;
    if !bound_box(b, f.rect, &test) {
        return vec2<u32>(0u);
    }
    let has_near = (mask & 1u) != 0u;
    let has_far = (mask & 2u) != 0u;
    let whole = vec2<f32>(select(f.ranges.z, f.ranges.x, has_near),
                          select(f.ranges.y, f.ranges.w, has_far));
    if !box_meets(test, whole) {
        return vec2<u32>(0u);
    }
    if mask != 3u {
        return vec2<u32>(mask & 1u, mask >> 1u);
    }
    return vec2<u32>(select(0u, 1u, box_meets(test, f.ranges.xy)),
                     select(0u, 1u, box_meets(test, f.ranges.zw)));
}
