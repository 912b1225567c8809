// Clustered shading by rasterizing bounding meshes [OP16], the paper's Table 2 baseline: the
// "shell" pass. Each VPL's 20-triangle mesh (bound_mesh.wgsl) is rasterized conservatively
// at tile resolution into its subregion's viewport (one cell per 16 x 16 tile), and each
// fragment marks, for its VPL and tile, the depth slices (clusters.wgsl's 32 exponential
// slices of the G-buffer's depth range) the triangle spans over the tile: the slices a convex
// volume occupies in a tile lie between the ones its front and back surface reach there, and
// cluster_fill.wgsl fills the span.
//
// Conservative rasterization in hardware where the adapter has it (vs_conservative, with
// Features::CONSERVATIVE_RASTERIZATION), else in software (vs_main; lavapipe has no such
// feature): each triangle is drawn as its cover, the rectangle of whole cells around its
// projection (6 vertices). Either way the fragment keeps a cell only where the triangle meets
// it (edge functions with a margin): every cell the triangle touches. Each kept cell is
// marked with the triangle's depth range over it (its vertices' range cut by its plane at the
// cell's corners, as [OP16]); a triangle reaching the eye plane marks every cell from depth 0.
// Marks before the nearest sample or past the farthest go to the first or last slice: the
// fill spans from the nearest mark to the farthest, so neither end may be dropped.
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
// The plane cut of cell_depths: the smallest sine between a corner's ray and the triangle's
// plane, and the relative growth of the cut for its rounding.
const MIN_SIN: f32 = 1e-2;
const CORNER_SLACK: f32 = 1e-3;
// Relative growth of depth ranges for f32 rounding.
const SLACK: f32 = 1e-5;
// Viewport coordinates beyond which a triangle covers every cell (its cover's corners would
// lose the cell's scale in f32).
const FAR_CELLS: f32 = 1e6;

struct ShellVertex {
    @builtin(position) position: vec4<f32>,
    // The slot in the partition's order, the subregion and the mesh triangle.
    @location(0) @interpolate(flat) ids: vec3<u32>,
}

// One mesh triangle in the culling view and in the subregion's viewport: its vertices' view
// positions, their viewport positions (cells) and whether those are usable (every vertex in
// front of the eye and within FAR_CELLS).
struct Triangle {
    p: array<vec3<f32>, 3>,
    uv: array<vec2<f32>, 3>,
    projected: bool,
}

fn triangle(j: u32, s: u32, t: u32) -> Triangle {
    let sh = shapes[order[j]];
    let ij = subregion_xy(s);
    var tri: Triangle;
    tri.projected = true;
    for (var k = 0u; k < 3u; k++) {
        let p = shape_point(sh, mesh[3u * t + k].xyz);
        let h = viewport_h(p, ij.x, ij.y);
        tri.p[k] = p;
        tri.uv[k] = h.xy / h.z;
        if !(p.z > 0.0 && all(abs(tri.uv[k]) < vec2<f32>(FAR_CELLS))) {
            tri.projected = false;
        }
    }
    return tri;
}

// Clip-space position of a vertex that draws nothing: outside the clip volume, so that no
// rasterizer, also one that rasterizes degenerate triangles conservatively, makes a fragment.
const NOWHERE: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

// Clip-space position (y up) of viewport position uv, in cells.
fn clip_of(uv: vec2<f32>, view: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(2.0 * uv.x / view.x - 1.0, 1.0 - 2.0 * uv.y / view.y, 0.0, 1.0);
}

// Vertex `corner` (0..6) of the rectangle [lo, hi] as two triangles: (lo, lo), (hi, lo),
// (lo, hi), (hi, lo), (hi, hi), (lo, hi) in cells.
fn rectangle_corner(corner: u32, lo: vec2<f32>, hi: vec2<f32>) -> vec2<f32> {
    let pick = vec2<bool>(corner == 1u || corner == 3u || corner == 4u,
                          corner == 2u || corner == 4u || corner == 5u);
    return select(lo, hi, pick);
}

// The cover of a triangle in a viewport of `view` cells, (lo, hi): the whole cells around its
// projection (at least one, within the viewport), or the whole viewport where it is not
// projected.
fn cover(tri: Triangle, view: vec2<f32>) -> vec4<f32> {
    if !tri.projected {
        return vec4<f32>(vec2<f32>(0.0), view);
    }
    let lo = clamp(floor(min(tri.uv[0], min(tri.uv[1], tri.uv[2]))), vec2<f32>(0.0), view);
    let hi = clamp(floor(max(tri.uv[0], max(tri.uv[1], tri.uv[2]))) + 1.0, vec2<f32>(0.0), view);
    return vec4<f32>(lo, hi);
}

// Vertex `vertex` of the subregion draw's instance `instance`: its ids, and the triangle it
// belongs to in the culling view and the viewport. Six vertices per mesh triangle.
struct ShellInput {
    ids: vec3<u32>,
    tri: Triangle,
    corner: u32,
    // False for a VPL without a bound and a triangle wholly behind the eye: nothing to draw.
    drawn: bool,
}

fn shell_input(vertex: u32, instance: u32) -> ShellInput {
    let s = vertex / params.mesh_vertices;
    let local = vertex % params.mesh_vertices;
    let j = sub_offsets[s] + instance;
    var input: ShellInput;
    input.ids = vec3<u32>(j, s, local / 6u);
    input.corner = local % 6u;
    if shapes[order[j]].center.w < 0.0 {
        return input;
    }
    input.tri = triangle(j, s, input.ids.z);
    let p = input.tri.p;
    // Wholly behind the eye: nothing in front to bound.
    input.drawn = max(p[0].z, max(p[1].z, p[2].z)) > 0.0;
    return input;
}

// The software form: each triangle drawn as its cover; fs_main keeps the cells the triangle
// meets.
@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32)
    -> ShellVertex {
    let input = shell_input(vertex, instance);
    var out: ShellVertex;
    out.ids = input.ids;
    out.position = NOWHERE;
    if !input.drawn {
        return out;
    }
    let view = vec2<f32>(f32(params.view_w), f32(params.view_h));
    let c = cover(input.tri, view);
    out.position = clip_of(rectangle_corner(input.corner, c.xy, c.zw), view);
    return out;
}

// The hardware form (a pipeline with conservative rasterization): a projected triangle
// drawn as itself in its first three vertices, the other three drawing nothing; the
// rasterizer's overestimating mode makes a fragment in every cell the triangle touches and
// in cells just beyond (its dilation), and fs_main keeps the cells of its cover that it meets:
// the cells of the software form. A triangle that is not projected (reaching the eye plane or
// beyond FAR_CELLS, which clipping would cut short) is drawn as its cover, the whole
// viewport, as in the software form.
@vertex
fn vs_conservative(@builtin(vertex_index) vertex: u32,
                   @builtin(instance_index) instance: u32) -> ShellVertex {
    let input = shell_input(vertex, instance);
    var out: ShellVertex;
    out.ids = input.ids;
    out.position = NOWHERE;
    if !input.drawn {
        return out;
    }
    let tri = input.tri;
    let view = vec2<f32>(f32(params.view_w), f32(params.view_h));
    if !tri.projected {
        let c = cover(tri, view);
        out.position = clip_of(rectangle_corner(input.corner, c.xy, c.zw), view);
    } else if input.corner < 3u {
        out.position = clip_of(tri.uv[input.corner], view);
    }
    return out;
}

// Slice of depth z among SLICES exponential slices of [near, far], as cluster_depth.wgsl
// computes it for the samples (the same f32 operations); depths at or below near: slice 0.
fn slice_of(z: f32, near: f32, far: f32) -> u32 {
    if z <= near {
        return 0u;
    }
    let log_near = log(near);
    let span = log(far) - log_near;
    let scale = select(0.0, f32(SLICES) / span, span > 0.0);
    let key = floor((log(z) - log_near) * scale);
    return u32(clamp(key, 0.0, f32(SLICES - 1u)));
}

// 2D cross product of (b - a) and (p - a).
fn edge(a: vec2<f32>, b: vec2<f32>, p: vec2<f32>) -> f32 {
    let e = b - a;
    let d = p - a;
    return e.x * d.y - e.y * d.x;
}

// Whether the cell [lo, lo + 1]^2 lies strictly beyond the edge p -> q of a triangle wound
// as `orient`: all four corners outside, by more than a margin for f32 rounding.
fn beyond_edge(p: vec2<f32>, q: vec2<f32>, orient: f32, lo: vec2<f32>) -> bool {
    let margin = SLACK * length(q - p) * (length(lo - p) + 2.0) + 1e-6;
    let limit = -margin;
    return orient * edge(p, q, lo) < limit && orient * edge(p, q, lo + vec2<f32>(1.0, 0.0)) < limit
        && orient * edge(p, q, lo + vec2<f32>(0.0, 1.0)) < limit
        && orient * edge(p, q, lo + vec2<f32>(1.0, 1.0)) < limit;
}

// Whether the projected triangle (a, b, c) meets the cell [lo, lo + 1]^2: no edge has the
// cell strictly beyond it (an edge's separating axis; the cover already keeps to the
// triangle's bounding box).
fn meets_cell(a: vec2<f32>, b: vec2<f32>, c: vec2<f32>, lo: vec2<f32>) -> bool {
    let orient = sign(edge(a, b, c));
    if orient == 0.0 {
        return true;
    }
    return !(beyond_edge(a, b, orient, lo) || beyond_edge(b, c, orient, lo)
             || beyond_edge(c, a, orient, lo));
}

// The image-plane point at unit depth of viewport position uv of subregion (i, j).
fn image_point(uv: vec2<f32>, ij: vec2<u32>) -> vec3<f32> {
    let screen = vec2<f32>(ij) + (uv - params.shift) * params.cell;
    return vec3<f32>((2.0 * screen / params.image.zw - 1.0) * params.image.xy, 1.0);
}

// The triangle's depth range over the cell: its vertices' range, cut by its plane's depths
// d / (n.ray) at the cell's corners (1/z is linear in the image plane, so the corners bound
// it) where every corner's ray meets the plane at more than about 0.6 degrees (the cut is
// skipped for planes seen nearly edge-on, whose d / (n.ray) rounding grows), grown by
// CORNER_SLACK; from 0 where a vertex is not in front of the eye.
fn cell_depths(tri: Triangle, lo: vec2<f32>, ij: vec2<u32>) -> vec2<f32> {
    let z = vec3<f32>(tri.p[0].z, tri.p[1].z, tri.p[2].z);
    let range = vec2<f32>(min(z.x, min(z.y, z.z)), max(z.x, max(z.y, z.z)));
    if !tri.projected {
        return vec2<f32>(0.0, range.y);
    }
    let n = cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
    let d = dot(n, tri.p[0]);
    var corners = vec2<f32>(3.4e38, 0.0);
    for (var m = 0u; m < 4u; m++) {
        let ray = image_point(lo + vec2<f32>(f32(m & 1u), f32(m >> 1u)), ij);
        let den = dot(n, ray);
        if !(abs(den) > MIN_SIN * length(n) * length(ray)) {
            return range;
        }
        let zc = d / den;
        corners = vec2<f32>(min(corners.x, zc), max(corners.y, zc));
    }
    // The corners must see the plane in front (all depths positive) and on one side.
    if !(corners.x > 0.0 && corners.y < 3.4e38) {
        return range;
    }
    return vec2<f32>(max(range.x, corners.x * (1.0 - CORNER_SLACK)),
                     min(range.y, corners.y * (1.0 + CORNER_SLACK)));
}

@fragment
fn fs_main(in: ShellVertex) -> @location(0) vec4<f32> {
    let ij = subregion_xy(in.ids.y);
    let cell = vec2<u32>(in.position.xy) - ij * vec2<u32>(params.view_w, params.view_h);
    let lo = vec2<f32>(cell);
    let tri = triangle(in.ids.x, in.ids.y, in.ids.z);
    // Cells outside the cover come only from the hardware form's dilation (meets_cell tests
    // the triangle's edges, not its bounding box).
    let c = cover(tri, vec2<f32>(f32(params.view_w), f32(params.view_h)));
    if any(lo < c.xy) || any(lo >= c.zw) {
        discard;
    }
    if tri.projected && !meets_cell(tri.uv[0], tri.uv[1], tri.uv[2], lo) {
        discard;
    }
    let depths = cell_depths(tri, lo, ij);
    let z_lo = max(depths.x * (1.0 - SLACK), 0.0);
    let z_hi = depths.y * (1.0 + SLACK);
    if z_lo > z_hi {
        discard;
    }
    // Depths before the nearest sample or past the farthest still mark the first or last
    // slice: the fill spans from the nearest mark to the farthest, so the ends must be there.
    let near = bitcast<f32>(depth_range[0]);
    let far = bitcast<f32>(depth_range[1]);
    let s_lo = slice_of(z_lo, near, far);
    let s_hi = slice_of(z_hi, near, far);
    let span = ((0xffffffffu >> (SLICES - 1u - s_hi)) >> s_lo) << s_lo;
    let per_sub = params.tiles_x * params.tiles_y;
    atomicOr(&cells[in.ids.x * per_sub + cell.y * params.tiles_x + cell.x], span);
    return vec4<f32>(0.0);
}
