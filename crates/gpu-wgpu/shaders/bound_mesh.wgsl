// The raster baselines' bounding meshes (src/bound_mesh.rs; the paper's Table 2: splatting
// [DS06], clustered shading by conservative rasterization [OP16]), shared by splat.wgsl and
// cluster_shell.wgsl: a mesh vertex around the unit sphere mapped onto one VPL's bound
// (bounds.wgsl Shape) and projected into one interleaved subregion's viewport. Structs mirror
// GpuBoundShape and GpuRasterParams in src/cull_types.rs.

// The spheroid of eq. (12)-(15) or a sphere in the culling view: centre (xyz) and the
// semi-axis along `axis` (w); the unit axis (xyz) and the other two semi-axes (w); w < 0:
// no shape.
struct Shape {
    center: vec4<f32>,
    axis: vec4<f32>,
}

struct RasterParams {
    // (aspect tan(yfov/2), tan(yfov/2), W, H), as CullParams.image.
    image: vec4<f32>,
    // Viewport cell (u, v) of subregion (i, j) spans screen pixels i + cell (u - shift.x)
    // .. + cell (the same in y): cell = K, shift = 0.5 - sample offset / K for pixels
    // (splatting: the cell centre is the pixel's sample), cell = 16 K, shift 0 for tiles.
    shift: vec2<f32>,
    cell: f32,
    delta: f32,
    width: u32,
    height: u32,
    k: u32,
    // Vertices per mesh draw (3 per triangle; 6 per triangle's cover in cluster_shell.wgsl).
    mesh_vertices: u32,
    // Cells per subregion viewport.
    view_w: u32,
    view_h: u32,
    // Nodes the node buffer holds.
    capacity: u32,
    // K^2 of the interleaved sampling (section 6).
    scale: f32,
    tiles_x: u32,
    tiles_y: u32,
    vpl_count: u32,
    pad: u32,
}

// Mesh vertex m (around the unit sphere) on the shape: c + r m + (r_u - r) (a.m) a, the
// affine map of the unit ball onto the spheroid (a sphere where r_u = r).
fn shape_point(sh: Shape, m: vec3<f32>) -> vec3<f32> {
    let a = sh.axis.xyz;
    return sh.center.xyz + sh.axis.w * m + (sh.center.w - sh.axis.w) * dot(a, m) * a;
}

// The viewport coordinates (in cells) of view-space point p in subregion (i, j), times its
// depth z: (u z, v z, z). Screen pixel X = (x / (z image.x) + 1) W / 2 (view.rs image_rect).
fn viewport_h(p: vec3<f32>, i: u32, j: u32) -> vec3<f32> {
    let z = p.z;
    let xz = (p.x / params.image.x + z) * (0.5 * params.image.z);
    let yz = (p.y / params.image.y + z) * (0.5 * params.image.w);
    return vec3<f32>((xz - f32(i) * z) / params.cell + params.shift.x * z,
                     (yz - f32(j) * z) / params.cell + params.shift.y * z, z);
}

// The clip position of homogeneous viewport coordinates h (y up in clip space, rows down in
// the viewport); z = 0, so the clipper cuts at the eye plane (w = 0) and nowhere in depth.
fn viewport_clip(h: vec3<f32>) -> vec4<f32> {
    return vec4<f32>(2.0 * h.x / f32(params.view_w) - h.z, h.z - 2.0 * h.y / f32(params.view_h),
                     0.0, h.z);
}

// Subregion s as (i, j).
fn subregion_xy(s: u32) -> vec2<u32> {
    return vec2<u32>(s % params.k, s / params.k);
}
