// The RSM resolve of one face, the GPU twin of crates/cpu-ref/src/rsm.rs trace_rsm with
// TexelSample::Centre: texel (i, j) sends its ray through its centre,
// x = (-1 + (i + 1/2) 2/n) e, y = (1 - (j + 1/2) 2/n) e on the face plane (a pinhole from the
// light, or parallel rays from the orthographic plane), and the triangle the visibility pass
// rasterized there is intersected with that ray (scene.wgsl surface). The texel's flux is the
// intensity (times the spot falloff of the ray's direction) times the texel's solid angle
// (pinhole), or the directional light's irradiance times the texel's area (orthographic,
// passed in precomputed). A texel holds a photon where the flux is positive and the ray hits
// the front of a surface. Whatever the ray hits first, front or back, is also written to the
// shadow map (the RSM depth kept for direct light, direct.wgsl). scene_types.wgsl,
// scene.wgsl, rsm_texel.wgsl and solid_angle.wgsl are prepended; structs mirror src/raster_types.rs.

struct RsmParams {
    // light position or orthographic origin (xyz), face extent e (w)
    origin: vec4<f32>,
    // axes (xyz); forward.w = texel size 2 / n
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    // intensity (pinhole) or per-texel flux (orthographic)
    light: vec4<f32>,
    // spot axis (xyz), SpotCone::h_outer (w)
    spot: vec4<f32>,
    // kind, n, first texel of the face, unused
    info: vec4<u32>,
    // SpotCone::h_width (x)
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
            intensity = intensity * spot_falloff(dir, params.spot.xyz, params.spot.w,
                                                 params.falloff.x);
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
