// Surface points of the uploaded scene, the WGSL twin of what crates/cpu-ref/src/tracer.rs
// (Tracer::surface) records at a ray hit: the hit point on a given triangle, its oriented
// geometric and shading normals and the material's BRDF there (crates/core/src/material.rs
// brdf_at with the bilinear, wrapping texture lookup of crates/core/src/texture.rs).
// The triangle comes from the visibility pass (the rasterizer decides what is nearest); the
// point is where the pixel's or texel's own ray meets that triangle's plane.
// scene_types.wgsl is prepended.

@group(0) @binding(0) var<storage, read> vertices: array<Vertex>;
@group(0) @binding(1) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(2) var<storage, read> materials: array<SceneMaterial>;
@group(0) @binding(3) var<storage, read> textures: array<TextureInfo>;
@group(0) @binding(4) var<storage, read> texels: array<f32>;

// The BRDF of a surface point (slc_bounds::Brdf): fresnel_kind 0 = Schlick with f0, 1 =
// dielectric with eta.
struct SurfaceBrdf {
    kd: vec3<f32>,
    fresnel_kind: u32,
    f0: vec3<f32>,
    eta: f32,
    alpha: f32,
    // An anisotropy's unit tangent and alpha_t (0: isotropic; Brdf::anisotropy).
    tangent: vec3<f32>,
    alpha_t: f32,
}

struct Surface {
    // false where the ray misses the triangle's plane (edge-on) or meets it behind the origin
    hit: bool,
    // whether the ray arrives on the side the oriented geometric normal points to
    front: bool,
    t: f32,
    position: vec3<f32>,
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
    // whether a normal map perturbed the shading normal (SurfaceHit::normal_mapped)
    normal_mapped: bool,
    brdf: SurfaceBrdf,
}

fn finite_f32(x: f32) -> bool {
    return abs(x) <= F32_MAX;
}

fn texel_rgb(info: TextureInfo, x: i32, y: i32) -> vec3<f32> {
    let i = info.offset + 3u * (u32(y) * info.width + u32(x));
    return vec3<f32>(texels[i], texels[i + 1u], texels[i + 2u]);
}

// Wraps an integral float coordinate into [0, size) (texture.rs: rem_euclid on i64; exact for
// coordinates below 2^24 texels).
fn wrap(x: f32, size: u32) -> i32 {
    let s = f32(size);
    let r = i32(x - floor(x / s) * s) % i32(size);
    return select(r, r + i32(size), r < 0);
}

// glam's Vec3::lerp: a (1 - s) + b s.
fn lerp3(a: vec3<f32>, b: vec3<f32>, s: f32) -> vec3<f32> {
    return a * (1.0 - s) + b * s;
}

// Texture::sample: bilinear with repeat wrapping, texel centres at half-integers, (0, 0) the
// top-left; 1 for an empty texture or a non-finite coordinate.
fn texture_sample(id: u32, uv: vec2<f32>) -> vec3<f32> {
    let info = textures[id];
    if info.width == 0u || info.height == 0u || !(finite_f32(uv.x) && finite_f32(uv.y)) {
        return vec3<f32>(1.0);
    }
    let x = uv.x * f32(info.width) - 0.5;
    let y = uv.y * f32(info.height) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let ix0 = wrap(x0, info.width);
    let ix1 = wrap(x0 + 1.0, info.width);
    let iy0 = wrap(y0, info.height);
    let iy1 = wrap(y0 + 1.0, info.height);
    let top = lerp3(texel_rgb(info, ix0, iy0), texel_rgb(info, ix1, iy0), fx);
    let bottom = lerp3(texel_rgb(info, ix0, iy1), texel_rgb(info, ix1, iy1), fx);
    return lerp3(top, bottom, fy);
}

fn lookup(id: u32, has_uv: bool, uv: vec2<f32>) -> vec3<f32> {
    if id == NO_TEXTURE || !has_uv {
        return vec3<f32>(1.0);
    }
    return texture_sample(id, uv);
}

// Material::brdf_at.
fn material_brdf(m: SceneMaterial, has_uv: bool, uv: vec2<f32>) -> SurfaceBrdf {
    var kd: vec3<f32>;
    var f0: vec3<f32>;
    var alpha: f32;
    if m.info.x == MATERIAL_DIRECT {
        kd = m.color.xyz * lookup(m.info.y, has_uv, uv);
        f0 = m.f0_alpha.xyz;
        alpha = m.f0_alpha.w;
    } else {
        let base = m.color.xyz * lookup(m.info.y, has_uv, uv);
        let mr = lookup(m.info.z, has_uv, uv);
        let metal = clamp(m.params.x * mr.z, 0.0, 1.0);
        let rough = clamp(m.params.y * mr.y, 0.0, 1.0);
        kd = base * (1.0 - metal);
        f0 = vec3<f32>(0.04 * (1.0 - metal)) + base * metal;
        alpha = rough * rough;
    }
    var b: SurfaceBrdf;
    b.kd = clamp(kd, vec3<f32>(0.0), vec3<f32>(1.0));
    b.alpha = clamp(alpha, ALPHA_MIN, 1.0);
    if (m.info.w & MATERIAL_DIELECTRIC) != 0u {
        b.fresnel_kind = 1u;
        b.f0 = vec3<f32>(0.0);
        b.eta = m.params.z;
    } else {
        b.fresnel_kind = 0u;
        b.f0 = clamp(f0, vec3<f32>(0.0), vec3<f32>(1.0));
        b.eta = 0.0;
    }
    return b;
}

// glam's try_normalize: None (here: `fallback`) for a zero or non-finite length.
fn normalize_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let rcp = 1.0 / sqrt(dot(v, v));
    if finite_f32(rcp) && rcp > 0.0 {
        return v * rcp;
    }
    return fallback;
}

// AlphaMask::cuts (Material::cuts): whether material m's mask cuts the surface away at uv
// (coverage 1 without a texture or texture coordinates).
fn cut_away(m: SceneMaterial, has_uv: bool, uv: vec2<f32>) -> bool {
    if (m.info.w & MATERIAL_ALPHA_MASK) == 0u {
        return false;
    }
    return m.map_params.z * lookup(m.maps.y, has_uv, uv).x < m.map_params.y;
}

// Material::mapped_normal with NormalMap::perturb: the unit normal n perturbed by material
// m's normal map in the frame of `tangent` (xyz, handedness w), kept only on n's side and on
// n's side of the triangle's plane (face normal g); the zero vector where it is not kept.
fn mapped_normal(m: SceneMaterial, n: vec3<f32>, g: vec3<f32>, tangent: vec4<f32>,
                 uv: vec2<f32>) -> vec3<f32> {
    let t = normalize_or(tangent.xyz - n * dot(n, tangent.xyz), vec3<f32>(0.0));
    if all(t == vec3<f32>(0.0)) {
        return vec3<f32>(0.0);
    }
    let b = cross(n, t) * select(1.0, -1.0, tangent.w < 0.0);
    let c = (texture_sample(m.maps.x, uv) * 2.0 - vec3<f32>(1.0))
        * vec3<f32>(m.map_params.x, m.map_params.x, 1.0);
    let p = normalize_or(t * c.x + b * c.y + n * c.z, vec3<f32>(0.0));
    if dot(p, n) > 0.0 && dot(p, g) * dot(n, g) > 0.0 {
        return p;
    }
    return vec3<f32>(0.0);
}

// MaterialAnisotropy::at: material m's anisotropy at a point with unit shading normal n and
// interpolated tangent (xyz, handedness w), as (direction, alpha_t) for roughness alpha; zero
// where the material is isotropic or the frame degenerates.
fn material_anisotropy(m: SceneMaterial, n: vec3<f32>, tangent: vec4<f32>, alpha: f32) -> vec4<f32> {
    let s = m.anisotropy.x;
    if s == 0.0 {
        return vec4<f32>(0.0);
    }
    let t = normalize_or(tangent.xyz - n * dot(n, tangent.xyz), vec3<f32>(0.0));
    if all(t == vec3<f32>(0.0)) {
        return vec4<f32>(0.0);
    }
    let b = cross(n, t) * select(1.0, -1.0, tangent.w < 0.0);
    let d = normalize_or(t * m.anisotropy.y + b * m.anisotropy.z, vec3<f32>(0.0));
    let direction = normalize_or(d - n * dot(n, d), vec3<f32>(0.0));
    if all(direction == vec3<f32>(0.0)) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(direction, clamp(alpha + (1.0 - alpha) * s * s, alpha, 1.0));
}

// The hit of the ray origin + t dir (t > 0) with triangle `tri`, oriented and shaded as
// Tracer::surface: barycentrics as watertight.rs barycentric (here in f32), the shading
// normal interpolated, perturbed by the normal map and flipped to the geometric normal's
// side, two-sided materials facing the ray.
fn surface(tri: u32, origin: vec3<f32>, dir: vec3<f32>) -> Surface {
    var s: Surface;
    let tr = triangles[tri];
    let va = vertices[tr.vertices.x];
    let vb = vertices[tr.vertices.y];
    let vc = vertices[tr.vertices.z];
    let a = va.position_u.xyz;
    let e1 = vb.position_u.xyz - a;
    let e2 = vc.position_u.xyz - a;
    let n = cross(e1, e2);
    let t = dot(a - origin, n) / dot(dir, n);
    s.hit = t > 0.0 && finite_f32(t);
    if !s.hit {
        return s;
    }
    s.t = t;
    s.position = origin + dir * t;
    let area2 = dot(n, n);
    let ap = s.position - a;
    let w1 = dot(cross(ap, e2), n) / area2;
    let w2 = dot(cross(e1, ap), n) / area2;
    let w0 = 1.0 - w1 - w2;
    var ng = normalize(n);
    var ns = ng;
    if (tr.info.x & TRIANGLE_NORMALS) != 0u {
        ns = normalize_or(va.normal_v.xyz * w0 + vb.normal_v.xyz * w1 + vc.normal_v.xyz * w2, ng);
    }
    let m = materials[tr.vertices.w];
    let has_uv = (tr.info.x & TRIANGLE_UVS) != 0u;
    let uv = vec2<f32>(va.position_u.w, va.normal_v.w) * w0
        + vec2<f32>(vb.position_u.w, vb.normal_v.w) * w1
        + vec2<f32>(vc.position_u.w, vc.normal_v.w) * w2;
    let has_tangents = (tr.info.x & TRIANGLE_TANGENTS) != 0u;
    var tangent = vec4<f32>(va.tangent.xyz * w0 + vb.tangent.xyz * w1 + vc.tangent.xyz * w2,
                            va.tangent.w);
    if m.maps.x != NO_TEXTURE && has_uv && has_tangents {
        let mapped = mapped_normal(m, ns, ng, tangent, uv);
        s.normal_mapped = any(mapped != vec3<f32>(0.0));
        if s.normal_mapped {
            ns = mapped;
        }
    }
    s.front = dot(dir, ng) < 0.0;
    if (m.info.w & MATERIAL_DOUBLE_SIDED) != 0u && !s.front {
        ng = -ng;
        s.front = true;
    }
    // A flipped shading normal keeps the tangent frame's bitangent (Tracer::surface).
    if dot(ns, ng) < 0.0 {
        ns = -ns;
        tangent.w = -tangent.w;
    }
    s.geometric_normal = ng;
    s.shading_normal = ns;
    s.brdf = material_brdf(m, has_uv, uv);
    if has_tangents {
        let a = material_anisotropy(m, ns, tangent, s.brdf.alpha);
        s.brdf.tangent = a.xyz;
        s.brdf.alpha_t = a.w;
    }
    return s;
}
