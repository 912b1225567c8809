// Splatting [DS06], the paper's Table 2 baseline: each VPL's bounding mesh (80 triangles
// around its spheroid or sphere, bound_mesh.wgsl) drawn into its interleaved subregion's
// viewport of a deinterleaved atlas. Back faces only (the front ones are culled) and no depth
// test, so each pixel whose sample ray meets the mesh is shaded exactly once per VPL, the
// camera inside the mesh included; the blend adds the contributions (vpl_eval.wgsl) in f32.
// fs_list instead appends each covered pixel's VPL to a per-pixel linked list (the metrics).
// bound_mesh.wgsl, brdf.wgsl, gsample.wgsl, gvpl.wgsl and vpl_eval.wgsl are prepended.

@group(0) @binding(0) var<uniform> params: RasterParams;
// Mesh vertices [x, y, z, 0], 3 per triangle.
@group(0) @binding(1) var<storage, read> mesh: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
@group(0) @binding(3) var<storage, read> sub_offsets: array<u32>;
@group(0) @binding(4) var<storage, read> order: array<u32>;
@group(0) @binding(5) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(6) var<storage, read> samples: array<Sample>;
// The G-buffer positions [x, y, z, 1] (gsample.wgsl).
@group(0) @binding(7) var<storage, read> positions: array<vec4<f32>>;
// fs_list: each pixel's first node (END: none), the nodes (VPL, next) and their count.
@group(0) @binding(8) var<storage, read_write> heads: array<atomic<u32>>;
@group(0) @binding(9) var<storage, read_write> nodes: array<vec2<u32>>;
@group(0) @binding(10) var<storage, read_write> node_count: array<atomic<u32>, 4>;

const END: u32 = 0xffffffffu;

// Subregion pixels the mesh's silhouette lies beyond the bound's: the rasterizer snaps
// vertices to its sub-pixel grid (at coarsest 1/16 of a pixel in Vulkan, so by at most
// 1/32), which a growth relative to the bound does not cover when the bound is a few pixels
// wide.
const SNAP_PIXELS: f32 = 0.0625;

// The shape grown so that its mesh covers every pixel whose ray passes within SNAP_PIXELS of
// the bound: eps = SNAP_PIXELS subregion pixels at the bound's farthest depth, and the shape
// scaled about its centre by 1 + eps/r (r the smaller semi-axis), which holds every point
// within eps of it (a ball of radius eps is inside eps/r times the shape, and for a convex
// shape S, S + (eps/r) S = (1 + eps/r) S).
fn snap_grown(sh: Shape) -> Shape {
    let far = max(sh.center.z + sh.center.w, 0.0);
    let eps = SNAP_PIXELS * params.cell * 2.0 * params.image.y / params.image.w * far;
    var grown = sh;
    grown.axis.w = sh.axis.w + eps;
    grown.center.w = sh.center.w + eps * (sh.center.w / sh.axis.w);
    return grown;
}

struct SplatVertex {
    @builtin(position) position: vec4<f32>,
    // The VPL and its subregion.
    @location(0) @interpolate(flat) ids: vec2<u32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32)
    -> SplatVertex {
    let s = vertex / params.mesh_vertices;
    let i = order[sub_offsets[s] + instance];
    let sh = shapes[i];
    var out: SplatVertex;
    out.ids = vec2<u32>(i, s);
    if sh.center.w < 0.0 {
        // No shape: every vertex at one point, nothing drawn.
        out.position = vec4<f32>(0.0, 0.0, 0.0, 1.0);
        return out;
    }
    let m = mesh[vertex % params.mesh_vertices].xyz;
    let ij = subregion_xy(s);
    out.position = viewport_clip(viewport_h(shape_point(snap_grown(sh), m), ij.x, ij.y));
    return out;
}

// The screen pixel of a fragment of subregion s's viewport (END past the image's edge).
fn splat_pixel(in: SplatVertex) -> u32 {
    let ij = subregion_xy(in.ids.y);
    let cell = vec2<u32>(in.position.xy) - ij * vec2<u32>(params.view_w, params.view_h);
    let x = ij.x + params.k * cell.x;
    let y = ij.y + params.k * cell.y;
    if x >= params.width || y >= params.height {
        return END;
    }
    return y * params.width + x;
}

@fragment
fn fs_shade(in: SplatVertex) -> @location(0) vec4<f32> {
    let pixel = splat_pixel(in);
    if pixel == END {
        discard;
    }
    let s = samples[pixel];
    if !sample_present(s) {
        discard;
    }
    let c = vpl_contribution(receiver(s, positions[pixel].xyz), vpls[in.ids.x], params.delta);
    return vec4<f32>(c * params.scale, 0.0);
}

@fragment
fn fs_list(in: SplatVertex) -> @location(0) vec4<f32> {
    let pixel = splat_pixel(in);
    if pixel == END {
        discard;
    }
    // positions' w: 1 where the pixel has a sample.
    if positions[pixel].w == 0.0 {
        discard;
    }
    let n = atomicAdd(&node_count[2], 1u);
    if n == END {
        // The count wraps: GpuCullStatus.total_overflow.
        atomicStore(&node_count[3], 1u);
    }
    if n < params.capacity {
        nodes[n] = vec2<u32>(in.ids.x, atomicExchange(&heads[pixel], n));
    }
    return vec4<f32>(0.0);
}
