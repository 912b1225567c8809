// Visibility by rasterization: every scene triangle drawn from a camera, an RSM cube face or
// spot face (pinhole) or a directional light (orthographic), both faces (one-sided surfaces
// seen from behind still occlude; the resolve passes decide what they reflect), with a
// depth test; each pixel keeps its nearest triangle's index + 1 (0: nothing).
// Pinhole depth is reversed with an infinite far plane (depth = near / z, test "greater"),
// orthographic depth is 1 - z / range. A sub-pixel offset (s, t) moves the geometry 0.5 - s
// pixels right and 0.5 - t pixels down, so that the rasterizer's pixel centre sees what the
// ray through (i + s, j + t) sees (Camera::ray_direction). Fragments where an alpha mask
// cuts the surface away are discarded (the CPU tracer's any-hit test), so cut-outs neither
// hide nor shadow. scene_types.wgsl and scene.wgsl (the scene at bindings 0-4) are
// prepended; the struct mirrors src/raster_types.rs GpuRasterView.

struct RasterView {
    origin: vec4<f32>,
    // axis (xyz), 1 / extent (w)
    right: vec4<f32>,
    up: vec4<f32>,
    // axis (xyz), near plane (pinhole) or 1 / depth range (orthographic)
    forward: vec4<f32>,
    // NDC shift (xy), 1 for orthographic (z)
    shift: vec4<f32>,
}

@group(0) @binding(5) var<uniform> view: RasterView;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) id: u32,
    @location(1) uv: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> Varyings {
    let tri = vi / 3u;
    let corner = vi % 3u;
    let vertex = vertices[triangles[tri].vertices[corner]];
    let p = vertex.position_u.xyz - view.origin.xyz;
    let x = dot(p, view.right.xyz) * view.right.w;
    let y = dot(p, view.up.xyz) * view.up.w;
    let z = dot(p, view.forward.xyz);
    var clip: vec4<f32>;
    if view.shift.z != 0.0 {
        clip = vec4<f32>(x + view.shift.x, y + view.shift.y, 1.0 - z * view.forward.w, 1.0);
    } else {
        clip = vec4<f32>(x + view.shift.x * z, y + view.shift.y * z, view.forward.w, z);
    }
    return Varyings(clip, tri + 1u, vec2<f32>(vertex.position_u.w, vertex.normal_v.w));
}

@fragment
fn fs_main(v: Varyings) -> @location(0) u32 {
    let tr = triangles[v.id - 1u];
    if cut_away(materials[tr.vertices.w], (tr.info.x & TRIANGLE_UVS) != 0u, v.uv) {
        discard;
    }
    return v.id;
}
