// The G-buffer resolve, the GPU twin of crates/cpu-ref/src/gbuffer.rs trace_gbuffer: for
// each pixel whose rasterized triangle id (visibility.wgsl) is set, the pixel's own ray of
// Camera::ray_direction (crates/core/src/camera.rs) meets that triangle's plane (scene.wgsl
// surface); a hit on the back of a one-sided surface, like a miss, leaves the pixel empty.
// Writes the GpuSample layout the tile depth, tiled culling and shading passes read
// (src/gpu_types.rs, `Sample` of shade.wgsl), the oriented geometric normal, and the
// position with w = 1 (0: empty) for the tile depth pass. scene_types.wgsl and scene.wgsl
// are prepended; structs mirror src/raster_types.rs and src/gpu_types.rs.

struct GbufferParams {
    position: vec4<f32>,
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    // (W / H, tan(yfov / 2), s, t)
    frame: vec4<f32>,
    width: u32,
    height: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(5) var<uniform> params: GbufferParams;
@group(0) @binding(6) var ids: texture_2d<u32>;
@group(0) @binding(7) var<storage, read_write> samples: array<Sample>;
@group(0) @binding(8) var<storage, read_write> geometric_normals: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> positions: array<vec4<f32>>;

// Camera::ray_direction for pixel (i, j) at the frame's sub-pixel offset, same operation order.
fn ray_direction(i: u32, j: u32) -> vec3<f32> {
    let aspect = params.frame.x;
    let tan_half = params.frame.y;
    let x = (2.0 * (f32(i) + params.frame.z) / f32(params.width) - 1.0) * aspect * tan_half;
    let y = (1.0 - 2.0 * (f32(j) + params.frame.w) / f32(params.height)) * tan_half;
    return normalize(params.forward.xyz + x * params.right.xyz + y * params.up.xyz);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.width || gid.y >= params.height {
        return;
    }
    let pixel = gid.y * params.width + gid.x;
    let id = textureLoad(ids, vec2<i32>(gid.xy), 0).x;
    var out = Sample(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec3<f32>(0.0), 0u);
    var normal = vec4<f32>(0.0);
    var position = vec4<f32>(0.0);
    if id != 0u {
        let dir = ray_direction(gid.x, gid.y);
        let s = surface(id - 1u, params.position.xyz, dir);
        if s.hit && s.front {
            // GpuSample::new: the tangent as its angle (Anisotropy::angle), a dielectric's eta
            // in f0_eta.x.
            let n = s.shading_normal;
            let t = s.brdf.tangent;
            let phi = select(0.0, atan2(dot(frame_y(n), t), dot(frame_x(n), t)), s.brdf.alpha_t > 0.0);
            let dielectric = s.brdf.fresnel_kind != 0u;
            out = Sample(
                vec4<f32>(n, s.brdf.alpha),
                vec4<f32>(-dir, phi),
                vec4<f32>(s.brdf.kd, s.brdf.alpha_t),
                select(s.brdf.f0, vec3<f32>(s.brdf.eta, 0.0, 0.0), dielectric),
                SAMPLE_PRESENT | select(0u, SAMPLE_DIELECTRIC, dielectric),
            );
            normal = vec4<f32>(s.geometric_normal, 0.0);
            position = vec4<f32>(s.position, 1.0);
        }
    }
    samples[pixel] = out;
    geometric_normals[pixel] = normal;
    positions[pixel] = position;
}
