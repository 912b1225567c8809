// Per-VPL bounds in the culling view (paper sections 5-7), the GPU twin of
// crates/cull/src/vpl_bounds.rs (which builds them with crates/bounds in f64 and stores f32):
// - diffuse VPLs: the sphere of section 6, radius (4/27)^(1/4) R around q + (1/27)^(1/4) R n,
//   R = sqrt(Phi k / (pi delta xi)) (eq. 5; the corrected centre of crates/bounds/src/sphere.rs);
// - glossy VPLs, by View.glossy: the sphere r/alpha around q (section 7), the sphere r_u around
//   the spheroid centre c (section 7), or the spheroid of eq. (12)-(15) as its test space BS,
//   BS c (eq. 16-17, section 5.2).
// Radii and semi-axes grow by View.slack (BOUND_SLACK); each bound records its VPL's
// interleaved subregion (vpl_subregion of rng.wgsl, prepended). Structs mirror
// src/gpu_types.rs; Bound is in bound.wgsl (prepended).

struct View {
    rotation: array<vec4<f32>, 3>,
    eye: vec4<f32>,
    delta: f32,
    glossy: u32,
    count: u32,
    slack: f32,
    k: u32,
    seed: u32,
    // 1: write each VPL's BoxBound too (the tight strategies), 0: not.
    box_bounds: u32,
    // 1: write each VPL's Shape too (the raster baselines), 0: not.
    shapes: u32,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(2) var<storage, read_write> bounds: array<Bound>;
// The tight strategies' bounds of p over boxes (box_bound.wgsl, prepended).
@group(0) @binding(3) var<storage, read_write> box_bounds: array<BoxBound>;
// The raster baselines' spheroids and spheres as shapes (bound_mesh.wgsl Shape, mirrored here
// as two vec4s: centre and its semi-axis along the axis, unit axis and the other semi-axes).
@group(0) @binding(4) var<storage, read_write> shapes: array<array<vec4<f32>, 2>>;

// The shape of the bound being built (no shape: w < 0), set by sphere_bound and glossy_bound.
var<private> shape: array<vec4<f32>, 2>;

const LOBE_DIFFUSE: u32 = 0u;
const GLOSSY_SPHERE: u32 = 0u;
const GLOSSY_ENCLOSING_SPHERE: u32 = 1u;
// (1/27)^(1/4) and (4/27)^(1/4): centre offset and radius of the diffuse sphere (section 6).
const DIFFUSE_OFFSET: f32 = 0.43869133765083086;
const DIFFUSE_RADIUS: f32 = 0.6204032394013997;
// crates/bounds/src/spheroid.rs MIN_CROSS_SQ: below it omega_w of eq. (14) comes from a frame.
const MIN_CROSS_SQ: f32 = 1e-6;
const F32_MAX: f32 = 3.40282347e38;

fn view_rotation() -> mat3x3<f32> {
    return mat3x3<f32>(view.rotation[0].xyz, view.rotation[1].xyz, view.rotation[2].xyz);
}

// cos of the largest angle between omega_i and a half vector (supplemental, after eq. 2).
// The sine is |n x w_i|, not sqrt(1 - cos^2), which loses half the digits near normal
// incidence (fresnel.rs cos_theta_h_max).
fn cos_theta_h_max(cos_i: f32, sin_i: f32) -> f32 {
    let c = clamp(cos_i, 0.0, 1.0);
    return c / sqrt(2.0 * (1.0 + clamp(sin_i, 0.0, 1.0)));
}

// F_max(omega_i): supplemental eq. (2) (Schlick) and eq. (6) (dielectric) at theta_h_max.
fn fresnel_max(vpl: Vpl, n: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    let h_max = cos_theta_h_max(dot(n, wi), length(cross(n, wi)));
    return fresnel_max_from(vpl.info.y, vpl.f0.xyz, vpl.omega_i_eta.w, h_max);
}

fn finite(x: f32) -> bool {
    return abs(x) <= F32_MAX;
}

fn finite3(v: vec3<f32>) -> bool {
    return finite(v.x) && finite(v.y) && finite(v.z);
}

fn empty_bound(index: u32) -> Bound {
    return Bound(array<vec4<f32>, 3>(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0)),
                 vec4<f32>(2.0, 0.0, 0.0, 0.0), BOUND_EMPTY, index, 0u, 0u);
}

fn overflow_bound(index: u32) -> Bound {
    var b = empty_bound(index);
    b.kind = BOUND_OVERFLOW;
    return b;
}

// A sphere built around the origin (centre `center`, radius `radius`), moved to the
// camera-relative VPL position q and rotated into the view: R (q + centre).
fn sphere_bound(q: vec3<f32>, center: vec3<f32>, radius: f32, index: u32) -> Bound {
    if !(radius > 0.0) {
        return empty_bound(index);
    }
    let grown = radius * (1.0 + view.slack);
    let c = view_rotation() * (q + center);
    let r2 = grown * grown;
    if !(finite3(c) && finite(r2)) {
        return overflow_bound(index);
    }
    shape = array<vec4<f32>, 2>(vec4<f32>(c, grown), vec4<f32>(0.0, 0.0, 1.0, grown));
    return Bound(array<vec4<f32>, 3>(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0)),
                 vec4<f32>(c, r2), BOUND_SPHERE, index, 0u, 0u);
}

// R = [omega_u, omega_w x omega_u, omega_w] of eq. (14).
fn spheroid_rotation(omega_u: vec3<f32>, n: vec3<f32>) -> mat3x3<f32> {
    let cr = cross(omega_u, n);
    let len_sq = dot(cr, cr);
    var omega_w: vec3<f32>;
    if len_sq > MIN_CROSS_SQ {
        omega_w = cr / sqrt(len_sq);
    } else {
        omega_w = frame_x(omega_u);
    }
    let omega_v = normalize(cross(omega_w, omega_u));
    return mat3x3<f32>(omega_u, omega_v, cross(omega_u, omega_v));
}

// The rotation B of eq. (17) for the stretch S (crates/bounds test_space.rs test_rotation).
fn test_rotation(s: mat3x3<f32>) -> mat3x3<f32> {
    let m = max(max(abs(s[0]), abs(s[1])), abs(s[2]));
    let scale = max(m.x, max(m.y, m.z));
    let bx = s[0] / scale;
    let by = s[1] / scale;
    let len_x = length(bx);
    let len_y = length(by);
    let ux = bx / len_x;
    let uy = by / len_y;
    let z = normalize(cross(ux, uy));
    var x: vec3<f32>;
    var y: vec3<f32>;
    if len_x > len_y {
        x = ux;
        y = cross(z, ux);
    } else {
        x = cross(uy, z);
        y = uy;
    }
    return transpose(mat3x3<f32>(x, y, z));
}

fn diffuse_bound(vpl: Vpl, q: vec3<f32>, index: u32) -> Bound {
    // One-sided BRDF: nothing reflected for omega_i below the surface.
    if dot(vpl.normal_alpha.xyz, vpl.omega_i_eta.xyz) <= 0.0 {
        return empty_bound(index);
    }
    // Vpl::diffuse_lobe: around n_g with the flux times flux_scale (w) where normal-mapped.
    let n = normalize(vpl.geometric_tilt.xyz);
    let reflected = scalar(vpl.flux.xyz * vpl.geometric_tilt.w * vpl.kd.xyz);
    // sqrt(a / (pi delta xi)) as a quotient of roots: no f32 overflow or underflow in between.
    let range = sqrt(reflected / PI) / (sqrt(view.delta) * sqrt(vpl.position_xi.w));
    return sphere_bound(q, (range * DIFFUSE_OFFSET) * n, range * DIFFUSE_RADIUS, index);
}

fn glossy_bound(vpl: Vpl, q: vec3<f32>, index: u32) -> Bound {
    let n = normalize(vpl.normal_alpha.xyz);
    let wi = normalize(vpl.omega_i_eta.xyz);
    // GlossyLobe::alpha: an anisotropic lobe is bounded by the isotropic one of its larger
    // alpha, its flux times the bound factor (slc_bounds::anisotropy).
    let alpha = max(vpl.normal_alpha.w, vpl.anisotropy.w);
    let cos_i = dot(n, wi);
    // GlossyLobe::radius: the flux times the bound factor (w, 1 unless normal-mapped or
    // anisotropic).
    let peak = scalar(vpl.flux.xyz * fresnel_max(vpl, n, wi)) * vpl.geometric_tilt.w;
    if cos_i <= 0.0 || peak <= 0.0 {
        return empty_bound(index);
    }
    // r of eq. (12).
    let r = sqrt(peak * ggx_g1_over_cos(alpha, cos_i) / (4.0 * PI))
        / (sqrt(view.delta) * sqrt(vpl.position_xi.w));
    if view.glossy == GLOSSY_SPHERE {
        return sphere_bound(q, vec3<f32>(0.0), r / alpha, index);
    }
    // The spheroid of eq. (13)-(15).
    let omega_u = normalize(2.0 * cos_i * n - wi);
    let r_u = (1.0 + alpha * alpha) / (2.0 * alpha) * r;
    let offset = (1.0 - alpha * alpha) / (2.0 * alpha) * r;
    let c = offset * omega_u;
    if view.glossy == GLOSSY_ENCLOSING_SPHERE {
        return sphere_bound(q, c, r_u, index);
    }
    // Eq. (16)-(17): S = R diag(1/r_u, 1/r_v, 1/r_w) R^T with R in view space, B, BS and BS c.
    let rot = view_rotation() * spheroid_rotation(omega_u, n);
    let semi = vec3<f32>(r_u, r, r) * (1.0 + view.slack);
    let inv = vec3<f32>(1.0) / semi;
    let s = rot * mat3x3<f32>(vec3<f32>(inv.x, 0.0, 0.0), vec3<f32>(0.0, inv.y, 0.0),
                              vec3<f32>(0.0, 0.0, inv.z)) * transpose(rot);
    let bs = test_rotation(s) * s;
    let center = bs * (view_rotation() * (q + c));
    if !(finite3(bs[0]) && finite3(bs[1]) && finite3(bs[2]) && finite3(center)) {
        return overflow_bound(index);
    }
    shape = array<vec4<f32>, 2>(vec4<f32>(view_rotation() * (q + c), semi.x),
                                vec4<f32>(rot[0], semi.y));
    return Bound(array<vec4<f32>, 3>(vec4<f32>(bs[0], 0.0), vec4<f32>(bs[1], 0.0),
                                     vec4<f32>(bs[2], 0.0)),
                 vec4<f32>(center, 1.0), BOUND_ELLIPSOID, index, 0u, 0u);
}

fn max_abs(v: vec3<f32>) -> f32 {
    let a = abs(v);
    return max(a.x, max(a.y, a.z));
}

// slc_bounds::BoxBound::glossy / diffuse rotated into the view (BoxBound::rotated), for the
// camera-relative position q: its factors as the CPU forms them, with the growth of the
// boxes for the f32 rounding of R q, of the receivers' R (x - eye) and of the shader's x - q
// (16 ulps of the largest coordinates involved; tight_cull.wgsl adds the receivers').
fn box_bound(vpl: Vpl, q: vec3<f32>) -> BoxBound {
    let rot = view_rotation();
    let slack = 16.0 * 1.1920929e-7 * (max_abs(vpl.position_xi.xyz) + max_abs(view.eye.xyz));
    let delta_xi = view.delta * vpl.position_xi.w / (1.0 + PROBABILITY_SLACK);
    var b = BoxBound(vec4<f32>(rot * q, slack), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0),
                     vec4<f32>(0.0), vec4<f32>(vpl.f0.xyz, vpl.omega_i_eta.w),
                     vec4<u32>(BOX_EMPTY, vpl.info.y, 0u,
                     bitcast<u32>(delta_xi)));
    if vpl.info.x == LOBE_DIFFUSE {
        // Vpl::diffuse_lobe: around n_g, Phi k / pi with the flux times flux_scale.
        let n = normalize(vpl.geometric_tilt.xyz);
        if dot(vpl.normal_alpha.xyz, vpl.omega_i_eta.xyz) > 0.0 {
            let peak = scalar(vpl.flux.xyz * vpl.geometric_tilt.w * vpl.kd.xyz) / PI;
            b.normal_peak = vec4<f32>(normalize(rot * n), peak);
            b.info.x = BOX_DIFFUSE;
        }
        return b;
    }
    let n = normalize(vpl.normal_alpha.xyz);
    let wi = normalize(vpl.omega_i_eta.xyz);
    let alpha = max(vpl.normal_alpha.w, vpl.anisotropy.w);
    let cos_i = dot(n, wi);
    let flux = vpl.flux.xyz * vpl.geometric_tilt.w;
    let g1_i = 0.25 * ggx_g1_over_cos(alpha, cos_i);
    let peak = scalar(flux * fresnel_max(vpl, n, wi)) * g1_i / (PI * alpha * alpha);
    if !(cos_i > 0.0) {
        return b;
    }
    // G1(w_o) by the lobe's smallest alpha, or by 1 on a tilted shading normal.
    var g1_alpha = vpl.normal_alpha.w;
    if vpl.anisotropy.w > 0.0 {
        g1_alpha = min(g1_alpha, vpl.anisotropy.w);
    }
    if any(vpl.normal_alpha.xyz != vpl.geometric_tilt.xyz) {
        g1_alpha = 0.0;
    }
    b.normal_peak = vec4<f32>(normalize(rot * n), peak);
    let h_max = cos_theta_h_max(cos_i, length(cross(n, wi)));
    b.omega_i_cos_h_max = vec4<f32>(normalize(rot * wi), h_max);
    b.omega_u_g1_i = vec4<f32>(normalize(rot * (2.0 * cos_i * n - wi)), g1_i);
    b.flux_alpha = vec4<f32>(flux, alpha);
    b.info.x = BOX_GLOSSY;
    b.info.z = bitcast<u32>(g1_alpha);
    return b;
}

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = (wid.y * groups.x + wid.x) * 64u + lid;
    if i >= view.count {
        return;
    }
    let vpl = vpls[i];
    // Camera-relative position first, then the rotation (crates/cull/src/view.rs).
    let q = vpl.position_xi.xyz - view.eye.xyz;
    shape = array<vec4<f32>, 2>(vec4<f32>(0.0, 0.0, 0.0, -1.0), vec4<f32>(0.0, 0.0, 1.0, -1.0));
    var b: Bound;
    if vpl.info.x == LOBE_DIFFUSE {
        b = diffuse_bound(vpl, q, i);
    } else {
        b = glossy_bound(vpl, q, i);
    }
    b.subregion = vpl_subregion(view.seed, vpl.info.z, view.k);
    bounds[i] = b;
    if view.box_bounds != 0u {
        box_bounds[i] = box_bound(vpl, q);
    }
    if view.shapes != 0u {
        shapes[i] = shape;
    }
}
