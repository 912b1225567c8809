// The RSM resolve of one face, the GPU twin of crates/cpu-ref/src/rsm.rs trace_rsm with
// TexelSample::Centre: texel (i, j) sends its ray through its centre,
// x = (-1 + (i + 1/2) 2/n) e, y = (1 - (j + 1/2) 2/n) e on the face plane (a pinhole from the
// light, or parallel rays from the orthographic plane), and the triangle the visibility pass
// rasterized there is intersected with that ray (scene.wgsl surface). The texel's flux is the
// intensity (times the spot falloff of the ray's direction) times the texel's solid angle
// (pinhole), or the directional light's irradiance times the texel's area (orthographic,
// passed in precomputed). A texel holds a photon where the flux is positive and the ray hits
// the front of a surface. Whatever the ray hits first, front or back, is also written to the
// shadow map (the RSM depth kept for direct light, direct.wgsl). scene_types.wgsl and
// scene.wgsl are prepended; structs mirror src/raster_types.rs.

struct RsmParams {
    // light position or orthographic origin (xyz), face extent e (w)
    origin: vec4<f32>,
    // axes (xyz); forward.w = texel size 2 / n
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    // intensity (pinhole) or per-texel flux (orthographic)
    light: vec4<f32>,
    // spot axis (xyz), cos outer (w)
    spot: vec4<f32>,
    // kind, n, first texel of the face, unused
    info: vec4<u32>,
    // max(cos inner - cos outer, 1e-3) (x)
    falloff: vec4<f32>,
}

struct ShadowTexel {
    position: vec4<f32>,
    normal: vec4<f32>,
}

@group(0) @binding(5) var<uniform> params: RsmParams;
@group(0) @binding(6) var ids: texture_2d<u32>;
@group(0) @binding(7) var<storage, read_write> texels_out: array<RsmTexel>;
@group(0) @binding(8) var<storage, read_write> shadow: array<ShadowTexel>;

const RSM_SPOT: u32 = 1u;
const RSM_DIRECTIONAL: u32 = 2u;

// dw / dA on the face plane at unit distance: (1 + x^2 + y^2)^(-3/2).
fn solid_angle_density(x: f32, y: f32) -> f32 {
    let r2 = 1.0 + x * x + y * y;
    return 1.0 / (r2 * sqrt(r2));
}

// The solid angle of the texel square centred at (x, y) with side h on the plane at unit
// distance, by 3 x 3 Gauss-Legendre quadrature of the density. rsm.rs evaluates the closed
// form F(x1,y1) - F(x0,y1) - F(x1,y0) + F(x0,y0), F = atan2(xy, sqrt(x^2 + y^2 + 1)), in f64;
// in f32 its four O(1) terms would cancel to a few digits for small texels, while the
// quadrature of the smooth density is exact to ~h^6 relative (below f32 rounding for any
// n >= 4 on a cube face).
fn texel_solid_angle(x: f32, y: f32, h: f32) -> f32 {
    let node = 0.5 * h * 0.7745966692414834;
    let offsets = array<f32, 3>(-node, 0.0, node);
    let weights = array<f32, 3>(5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0);
    var sum = 0.0;
    for (var a = 0; a < 3; a++) {
        for (var b = 0; b < 3; b++) {
            sum += weights[a] * weights[b] * solid_angle_density(x + offsets[a], y + offsets[b]);
        }
    }
    return sum * h * h;
}

// Light::spot_falloff: clamp((cos - cos_outer) / max(cos_inner - cos_outer, 1e-3), 0, 1)^2.
fn spot_falloff(cos_axis: f32) -> f32 {
    let t = clamp((cos_axis - params.spot.w) / params.falloff.x, 0.0, 1.0);
    return t * t;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let n = params.info.y;
    if gid.x >= n || gid.y >= n {
        return;
    }
    let texel = params.info.z + gid.y * n + gid.x;
    let e = params.origin.w;
    let ts = params.forward.w;
    let x = (-1.0 + (f32(gid.x) + 0.5) * ts) * e;
    let y = (1.0 - (f32(gid.y) + 0.5) * ts) * e;
    var origin = params.origin.xyz;
    var dir = params.forward.xyz;
    var flux = params.light.xyz;
    if params.info.x == RSM_DIRECTIONAL {
        origin = origin + x * params.right.xyz + y * params.up.xyz;
    } else {
        dir = normalize(params.forward.xyz + x * params.right.xyz + y * params.up.xyz);
        var intensity = params.light.xyz;
        if params.info.x == RSM_SPOT {
            intensity = intensity * spot_falloff(dot(dir, params.spot.xyz));
        }
        flux = intensity * texel_solid_angle(x, y, ts * e);
    }
    var out = RsmTexel(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0),
                       vec4<f32>(0.0), vec4<f32>(0.0), vec4<u32>(0u), vec4<f32>(0.0),
                       vec4<f32>(0.0));
    var occluder = ShadowTexel(vec4<f32>(0.0), vec4<f32>(0.0));
    let id = textureLoad(ids, vec2<i32>(gid.xy), 0).x;
    if id != 0u {
        let s = surface(id - 1u, origin, dir);
        if s.hit {
            occluder = ShadowTexel(vec4<f32>(s.position, 1.0), vec4<f32>(s.geometric_normal, 0.0));
            if s.front && max(flux.x, max(flux.y, flux.z)) > 0.0 {
                out = RsmTexel(
                    vec4<f32>(s.position, 1.0),
                    vec4<f32>(s.shading_normal, s.brdf.alpha),
                    vec4<f32>(-dir, s.brdf.eta),
                    vec4<f32>(flux, 0.0),
                    vec4<f32>(s.brdf.kd, 0.0),
                    vec4<f32>(s.brdf.f0, 0.0),
                    vec4<u32>(s.brdf.fresnel_kind, 0u, 0u, 0u),
                    vec4<f32>(s.geometric_normal, select(0.0, 1.0, s.normal_mapped)),
                    vec4<f32>(s.brdf.tangent, s.brdf.alpha_t),
                );
            }
        }
    }
    texels_out[texel] = out;
    shadow[texel] = occluder;
}
