// Visibility by rasterization: every scene triangle drawn from a camera, an RSM cube face or
// spot face (pinhole) or a directional light (orthographic), both faces (one-sided surfaces
// seen from behind still occlude; the resolve passes decide what they reflect), with a
// depth test; each pixel keeps its nearest triangle's index + 1 (0: nothing).
// Pinhole depth is reversed with an infinite far plane (depth = near / z, test "greater"),
// orthographic depth is 1 - z / range. A sub-pixel offset (s, t) moves the geometry 0.5 - s
// pixels right and 0.5 - t pixels down, so that the rasterizer's pixel centre sees what the
// ray through (i + s, j + t) sees (Camera::ray_direction). scene_types.wgsl is prepended; the struct
// mirrors src/raster_types.rs GpuRasterView.

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

@group(0) @binding(0) var<storage, read> vertices: array<Vertex>;
@group(0) @binding(1) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(2) var<uniform> view: RasterView;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) id: u32,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> Varyings {
    let tri = vi / 3u;
    let corner = vi % 3u;
    let p = vertices[triangles[tri].vertices[corner]].position_u.xyz - view.origin.xyz;
    let x = dot(p, view.right.xyz) * view.right.w;
    let y = dot(p, view.up.xyz) * view.up.w;
    let z = dot(p, view.forward.xyz);
    var clip: vec4<f32>;
    if view.shift.z != 0.0 {
        clip = vec4<f32>(x + view.shift.x, y + view.shift.y, 1.0 - z * view.forward.w, 1.0);
    } else {
        clip = vec4<f32>(x + view.shift.x * z, y + view.shift.y * z, view.forward.w, z);
    }
    return Varyings(clip, tri + 1u);
}

@fragment
fn fs_main(v: Varyings) -> @location(0) u32 {
    return v.id;
}
