// Clustered shading by rasterizing bounding meshes [OP16], the paper's Table 2 baseline: the
// "shell" pass. Each VPL's 20-triangle mesh (bound_mesh.wgsl) is rasterized conservatively
// at tile resolution into its subregion's viewport (one cell per 16 x 16 tile), and each
// fragment marks, for its VPL and tile, the depth slices (clusters.wgsl's 32 exponential
// slices of the G-buffer's depth range) the triangle spans over the tile: the slices a convex
// volume occupies in a tile lie between the ones its front and back surface reach there, and
// cluster_fill.wgsl fills the span.
//
// Conservative rasterization without the adapter feature (lavapipe has none): each triangle
// is drawn as its cover, the rectangle of whole cells around its projection (6 vertices), a
// superset of the cells the hardware's overestimating mode gives. A triangle reaching the eye
// plane covers every cell from depth 0. Each cell is marked with the triangle's vertex depth
// range. ([OP16] keeps only the cells the triangle meets and cuts the range by its plane over
// the tile, which is tighter; not done here.)
// bound_mesh.wgsl is prepended.

@group(0) @binding(0) var<uniform> params: RasterParams;
@group(0) @binding(1) var<storage, read> mesh: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
@group(0) @binding(3) var<storage, read> sub_offsets: array<u32>;
@group(0) @binding(4) var<storage, read> order: array<u32>;
// [0] bits of the G-buffer's smallest view depth, [1] of the largest (cluster_depth.wgsl).
@group(0) @binding(5) var<storage, read> depth_range: array<u32, 2>;
// The slices (bit s) each VPL's mesh reaches in each tile of its subregion, per slot j of
// the partition's order: cells[j tiles_x tiles_y + tile].
@group(0) @binding(6) var<storage, read_write> cells: array<atomic<u32>>;

const SLICES: u32 = 32u;
// Relative growth of depth ranges for f32 rounding.
const SLACK: f32 = 1e-5;
// Viewport coordinates beyond which a triangle covers every cell (its cover's corners would
// lose the cell's scale in f32).
const FAR_CELLS: f32 = 1e6;

struct ShellVertex {
    @builtin(position) position: vec4<f32>,
    // The slot in the partition's order and the subregion.
    @location(0) @interpolate(flat) ids: vec2<u32>,
    // The triangle's depth range (smallest, largest); a negative smallest depth: the
    // triangle reaches the eye plane (every cell, from depth 0).
    @location(1) @interpolate(flat) depth: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32)
    -> ShellVertex {
    let s = vertex / params.mesh_vertices;
    let local = vertex % params.mesh_vertices;
    let j = sub_offsets[s] + instance;
    let sh = shapes[order[j]];
    var out: ShellVertex;
    out.ids = vec2<u32>(j, s);
    out.position = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if sh.center.w < 0.0 {
        return out;
    }
    let t = local / 6u;
    let ij = subregion_xy(s);
    let p0 = shape_point(sh, mesh[3u * t].xyz);
    let p1 = shape_point(sh, mesh[3u * t + 1u].xyz);
    let p2 = shape_point(sh, mesh[3u * t + 2u].xyz);
    let h0 = viewport_h(p0, ij.x, ij.y);
    let h1 = viewport_h(p1, ij.x, ij.y);
    let h2 = viewport_h(p2, ij.x, ij.y);
    let z_max = max(p0.z, max(p1.z, p2.z));
    let view = vec2<f32>(f32(params.view_w), f32(params.view_h));
    var lo = vec2<f32>(0.0);
    var hi = view;
    var z_min = min(p0.z, min(p1.z, p2.z));
    if z_min > 0.0 {
        let a = h0.xy / h0.z;
        let b = h1.xy / h1.z;
        let c = h2.xy / h2.z;
        // Whole cells around the projection, at least one, within the viewport.
        lo = clamp(floor(min(a, min(b, c))), vec2<f32>(0.0), view);
        hi = clamp(floor(max(a, max(b, c))) + 1.0, vec2<f32>(0.0), view);
        out.depth = vec2<f32>(z_min, z_max);
        let far_out = vec2<f32>(FAR_CELLS);
        if !(all(abs(a) < far_out) && all(abs(b) < far_out) && all(abs(c) < far_out)) {
            // Projected too far out for the edge functions (or not at all, NaN): the whole
            // viewport.
            lo = vec2<f32>(0.0);
            hi = view;
            out.depth.x = -1.0;
        }
    } else {
        out.depth = vec2<f32>(-1.0, z_max);
    }
    if z_max <= 0.0 {
        // Wholly behind the eye: nothing in front to bound.
        return out;
    }
    // The cover's two triangles: corners (lo, lo), (hi, lo), (lo, hi), (hi, lo), (hi, hi),
    // (lo, hi) in cells, to clip space (y up).
    let corner = local % 6u;
    let pick = vec2<bool>(corner == 1u || corner == 3u || corner == 4u,
                          corner == 2u || corner == 4u || corner == 5u);
    let uv = select(lo, hi, pick);
    out.position = vec4<f32>(2.0 * uv.x / view.x - 1.0, 1.0 - 2.0 * uv.y / view.y, 0.0, 1.0);
    return out;
}

// Slice of depth z among SLICES exponential slices of [near, far] (cluster_depth.wgsl).
fn slice_of(z: f32, near: f32, far: f32) -> u32 {
    if z <= near || far <= near {
        return 0u;
    }
    let s = floor((log(z) - log(near)) * f32(SLICES) / (log(far) - log(near)));
    return u32(clamp(s, 0.0, f32(SLICES - 1u)));
}

@fragment
fn fs_main(in: ShellVertex) -> @location(0) vec4<f32> {
    let ij = subregion_xy(in.ids.y);
    let cell = vec2<u32>(in.position.xy) - ij * vec2<u32>(params.view_w, params.view_h);
    let z_lo = max(in.depth.x * (1.0 - SLACK), 0.0);
    let z_hi = in.depth.y * (1.0 + SLACK);
    let near = bitcast<f32>(depth_range[0]);
    let far = bitcast<f32>(depth_range[1]);
    if z_hi < near || z_lo > far {
        discard;
    }
    let s_lo = slice_of(z_lo, near, far);
    let s_hi = slice_of(z_hi, near, far);
    let span = ((0xffffffffu >> (SLICES - 1u - s_hi)) >> s_lo) << s_lo;
    let per_sub = params.tiles_x * params.tiles_y;
    atomicOr(&cells[in.ids.x * per_sub + cell.y * params.tiles_x + cell.x], span);
    return vec4<f32>(0.0);
}
