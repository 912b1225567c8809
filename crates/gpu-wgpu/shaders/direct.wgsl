// Direct light with shadow maps, the GPU twin of crates/cpu-ref/src/direct.rs shade_direct
// with the shadow ray replaced by a shadow-map lookup: per G-buffer pixel and light,
// sum += f(wl, wo) E cos(theta_l) V, with E = I / d^2 (times the spot falloff) or the
// directional irradiance (Light::incident), the full BRDF of brdf.wgsl, and zero unless
// both the shading and the geometric normal face the light. One dispatch per light adds
// to the image, lights in scene order as on the CPU.
//
// Visibility V: the pixel's point x is projected into the light's map (the cube face of
// the largest component of the direction from the light, the spot face, or the
// orthographic map), nearest texel, no filtering. The texel stores the first surface its
// centre ray met (position and geometric normal, rsm.wgsl). The occluder's depth along the
// ray towards x is taken from that surface's plane (the texel's tangent plane: exact for
// planar occluders, so flat receivers do not shadow themselves however grazing the light),
// or from the texel centre's depth where the plane is within 1e-2 of parallel to the ray
// or meets it behind the light. x is lit when its distance is at most that depth plus
// bias = shadow.x (absolute, from the scene extent) + shadow.y (relative) x distance.
// Points outside a single-face map are lit (the spot falloff is zero there).
// fresnel_ggx.wgsl and brdf.wgsl are prepended; structs mirror src/raster_types.rs and
// src/gpu_types.rs.

struct DirectParams {
    light: vec4<f32>,
    // spot axis (xyz), SpotCone::h_outer (w)
    spot: vec4<f32>,
    // intensity or irradiance (rgb), SpotCone::h_width (w)
    radiometry: vec4<f32>,
    // shadow-map origin (xyz), face extent (w)
    origin: vec4<f32>,
    // forward, right, up of each face
    axes: array<vec4<f32>, 18>,
    // kind, faces, resolution, pixel count
    info: vec4<u32>,
    // absolute bias, relative bias, orthographic flag
    shadow: vec4<f32>,
}

struct ShadowTexel {
    position: vec4<f32>,
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: DirectParams;
@group(0) @binding(1) var<storage, read> samples: array<Sample>;
@group(0) @binding(2) var<storage, read> geometric_normals: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> shadow: array<ShadowTexel>;
// RGB per pixel, accumulated over the lights.
@group(0) @binding(4) var<storage, read_write> image: array<f32>;
// The G-buffer positions [x, y, z, 1] (gsample.wgsl).
@group(0) @binding(5) var<storage, read> positions: array<vec4<f32>>;

const LIGHT_SPOT: u32 = 1u;
const LIGHT_DIRECTIONAL: u32 = 2u;
const WORKGROUP: u32 = 64u;

struct Incident {
    valid: bool,
    omega_i: vec3<f32>,
    irradiance: vec3<f32>,
}

// Light::incident (crates/core/src/light.rs).
fn incident(x: vec3<f32>) -> Incident {
    var inc: Incident;
    if params.info.x == LIGHT_DIRECTIONAL {
        inc.valid = true;
        inc.omega_i = -params.light.xyz;
        inc.irradiance = params.radiometry.xyz;
        return inc;
    }
    let to_light = params.light.xyz - x;
    let d2 = dot(to_light, to_light);
    inc.valid = d2 > 0.0;
    if !inc.valid {
        return inc;
    }
    inc.omega_i = to_light / sqrt(d2);
    inc.irradiance = params.radiometry.xyz / d2;
    if params.info.x == LIGHT_SPOT {
        let falloff = spot_falloff(-inc.omega_i, params.spot.xyz, params.spot.w,
                                   params.radiometry.w);
        inc.valid = falloff > 0.0;
        inc.irradiance = inc.irradiance * falloff;
    }
    return inc;
}

// Whether x is lit according to the shadow map (see the header).
fn visible(x: vec3<f32>) -> bool {
    let ortho = params.shadow.z != 0.0;
    let rel = x - params.origin.xyz;
    var dir: vec3<f32>;
    var distance: f32;
    var face = 0u;
    if ortho {
        dir = params.axes[0].xyz;
        distance = dot(rel, dir);
    } else {
        distance = length(rel);
        if !(distance > 0.0) {
            return true;
        }
        dir = rel / distance;
        var best = dot(dir, params.axes[0].xyz);
        for (var f = 1u; f < params.info.y; f++) {
            let c = dot(dir, params.axes[3u * f].xyz);
            if c > best {
                best = c;
                face = f;
            }
        }
    }
    let forward = params.axes[3u * face].xyz;
    let right = params.axes[3u * face + 1u].xyz;
    let up = params.axes[3u * face + 2u].xyz;
    var u: f32;
    var v: f32;
    if ortho {
        u = dot(rel, right) / params.origin.w;
        v = dot(rel, up) / params.origin.w;
    } else {
        let z = dot(dir, forward);
        if !(z > 0.0) {
            return true;
        }
        u = dot(dir, right) / (z * params.origin.w);
        v = dot(dir, up) / (z * params.origin.w);
    }
    if !(abs(u) <= 1.0 && abs(v) <= 1.0) {
        return true;
    }
    let n = params.info.z;
    let i = min(u32(max((u + 1.0) * 0.5 * f32(n), 0.0)), n - 1u);
    let j = min(u32(max((1.0 - v) * 0.5 * f32(n), 0.0)), n - 1u);
    let texel = shadow[face * n * n + j * n + i];
    if texel.position.w == 0.0 {
        return true;
    }
    // The ray towards x: from the light, or from x's foot on the orthographic plane.
    var ray_origin = params.origin.xyz;
    if ortho {
        ray_origin = x - distance * dir;
    }
    let p = texel.position.xyz;
    var depth = length(p - ray_origin);
    if ortho {
        depth = dot(p - ray_origin, dir);
    }
    let ng = texel.normal.xyz;
    let denom = dot(dir, ng);
    if abs(denom) > 1e-2 {
        let t = dot(p - ray_origin, ng) / denom;
        if t > 0.0 {
            depth = t;
        }
    }
    return distance <= depth + params.shadow.x + params.shadow.y * distance;
}

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if pixel >= params.info.w {
        return;
    }
    let s = samples[pixel];
    if !sample_present(s) {
        return;
    }
    let x = positions[pixel].xyz;
    let n = s.normal_alpha.xyz;
    let inc = incident(x);
    if !inc.valid {
        return;
    }
    let cos_l = dot(n, inc.omega_i);
    if cos_l <= 0.0 || dot(geometric_normals[pixel].xyz, inc.omega_i) <= 0.0 {
        return;
    }
    if !visible(x) {
        return;
    }
    let c = brdf_eval(sample_material(s), n, inc.omega_i, s.omega_o_phi.xyz) * inc.irradiance
        * cos_l;
    image[3u * pixel] += c.x;
    image[3u * pixel + 1u] += c.y;
    image[3u * pixel + 2u] += c.z;
}
