// One VSGL prepared for shading (crates/cpu-ref/src/vsgl/shading.rs Emitter; GpuVsgl in
// src/vsgl_types.rs) and the radiance it sends a receiver (Emitter::radiance, VSGL eq. 2-5).
// sg.wgsl and sg_surface.wgsl come first.

// The fault record of a VSGL frame (GpuVsglStatus in src/vsgl_types.rs), written by its
// construction (src/vsgl_build_pass.rs) and its shading, read once after the shading.
// u32::MAX: none. bad_pixel: smallest pixel whose surface is outside the SG math's domain;
// overflow_vsgl: smallest VSGL whose lambda_sigma or SG product left f32 at some pixel;
// lights: the distinct clusters sampled; bad_texel: smallest RSM texel (over the maps in
// order) whose BRDF is outside that domain; bad_vsgl: smallest light whose VSGL left f32;
// bad_view: smallest texel whose bidirectional importance left f32; bad_camera_vsgl: the
// same as bad_vsgl for the camera-side VSGLs of the bidirectional importance.
struct VsglStatus {
    bad_pixel: atomic<u32>,
    overflow_vsgl: atomic<u32>,
    lights: atomic<u32>,
    bad_texel: atomic<u32>,
    bad_vsgl: atomic<u32>,
    bad_view: atomic<u32>,
    bad_camera_vsgl: atomic<u32>,
    pad: u32,
}

// mu_v and sigma_v^2, and per lobe c_v (rgb, zero for a lobe left out) and the emitted lobe's
// axis -xi_v with lambda_v.
struct Vsgl {
    mu_sigma2: vec4<f32>,
    // c_v of the diffuse lobe (xyz), 1 / (2 pi sigma_v^2) of eq. (1) and (5) (w).
    diffuse_c_density: vec4<f32>,
    diffuse_lobe: vec4<f32>,
    specular_c: vec4<f32>,
    specular_lobe: vec4<f32>,
    // The specular lobe's stretch (slc_bounds::sg::LobeStretch): the tangent in the plane of
    // incidence (xyz) and cos θ (w), the bitangent (xyz) and 1 / cos θ (w); all zero but the
    // cosines (1) for none.
    stretch_tangent: vec4<f32>,
    stretch_bitangent: vec4<f32>,
}

// slc_bounds::sg::STRETCH_MIN_COS and STRETCH_SHARPNESS (a test of src/vsgl_shade_pass.rs
// holds these to them).
const STRETCH_MIN_COS: f32 = 0.2;
const STRETCH_SHARPNESS: f32 = 10.0;

// LobeStretch::new: the stretch of a lobe of unit `axis` and `sharpness` reflected off a
// surface of `normal` (unit or zero), as [tangent, cos θ], [bitangent, 1 / cos θ].
fn lobe_stretch(axis: vec3<f32>, sharpness: f32, normal: vec3<f32>) -> array<vec4<f32>, 2> {
    let c = abs(dot(normal, axis));
    let along = normal - dot(normal, axis) * axis;
    let len = length(along);
    if !(sharpness >= MIXTURE_FROM && sg_finite(sharpness) && len > 1e-4 && sg_finite(c)) {
        return array<vec4<f32>, 2>(vec4<f32>(0.0, 0.0, 0.0, 1.0), vec4<f32>(0.0, 0.0, 0.0, 1.0));
    }
    let t = along / len;
    let b = normalize(cross(axis, t));
    let p = sharpness / (sharpness + STRETCH_SHARPNESS);
    let cos = pow(clamp(c, STRETCH_MIN_COS, 1.0), p);
    return array<vec4<f32>, 2>(vec4<f32>(t, cos), vec4<f32>(b, 1.0 / cos));
}

// LobeStretch::factor: k(ω) = (u² cos θ + v² / cos θ) / (u² + v²), 1 without a stretch.
fn stretch_factor(e: Vsgl, w: vec3<f32>) -> f32 {
    let u = dot(e.stretch_tangent.xyz, w);
    let v = dot(e.stretch_bitangent.xyz, w);
    let r2 = u * u + v * v;
    if r2 > 0.0 {
        return (u * u * e.stretch_tangent.w + v * v * e.stretch_bitangent.w) / r2;
    }
    return 1.0;
}

// LobeStretch::amplitude_factor: the amplitude of the isotropic stand-in of sharpness l k in
// a product with a lobe of sharpness `other`, as sqrt((q/x)(q/y)) (no overflow).
fn stretch_amplitude(e: Vsgl, l: f32, k: f32, other: f32) -> f32 {
    let q = l * k + other;
    let x = l * e.stretch_tangent.w + other;
    let y = l * e.stretch_bitangent.w + other;
    return sqrt((q / x) * (q / y));
}

// slc_bounds::sg::GGX_MIXTURE and MIXTURE_FROM (crates/bounds/src/sg/mixture.rs; a test of
// src/vsgl_shade_pass.rs holds these to them): the sharpness scale and weight of the three SGs
// that stand for a specular lobe of sharpness MIXTURE_FROM or more (GGX's tails).
const GGX_MIXTURE = array<vec2<f32>, 3>(vec2<f32>(2.254, 0.7082), vec2<f32>(0.5566, 0.2742), vec2<f32>(0.09101, 0.01758));
const MIXTURE_FROM: f32 = 3.0;

// slc_bounds::sg::mixture_scale: A(l) / sum_k w_k A(c_k l), so that the mixture has the
// lobe's integral (applied to c when a VSGL is packed, vsgl_pack).
fn mixture_scale(l: f32) -> f32 {
    var sum = 0.0;
    for (var m = 0u; m < 3u; m++) {
        sum += GGX_MIXTURE[m].y * sg_integral(GGX_MIXTURE[m].x * l);
    }
    return sg_integral(l) / sum;
}

// The radiance VSGL e reflects at the receiver at x (xyz); w = 1 when its positional SG
// (lambda_sigma) or an SG product left f32, where the CPU fails with an overflow. The lobe
// loop sets a flag rather than returning: an exit from inside the loop measured 1.7x slower
// on lavapipe (its SIMD lanes lose the loop's shape).
fn vsgl_contribution(surface: Surface, x: vec3<f32>, e: Vsgl) -> vec4<f32> {
    let sigma2 = e.mu_sigma2.w;
    let density = e.diffuse_c_density.w;
    // Emitter::radiance: the positional SG of eq. (4); constant at mu_v itself.
    let d = e.mu_sigma2.xyz - x;
    let r2 = dot(d, d);
    var position = Sg(vec3<f32>(0.0, 0.0, 1.0), 0.0, density);
    if r2 > 0.0 {
        position = Sg(d / sqrt(r2), r2 / sigma2, density);
        if !sg_finite(position.sharpness) {
            return vec4<f32>(0.0, 0.0, 0.0, 1.0);
        }
    }
    var radiance = vec3<f32>(0.0);
    var overflow = 0.0;
    let lobes = array<vec4<f32>, 2>(e.diffuse_lobe, e.specular_lobe);
    let colours = array<vec3<f32>, 2>(e.diffuse_c_density.xyz, e.specular_c.xyz);
    let clamped = e.specular_c.w != 0.0;
    for (var k = 0u; k < 2u; k++) {
        let c = colours[k];
        if all(c == vec3<f32>(0.0)) || (clamped && k == 0u) {
            continue;
        }
        // The specular lobe as GGX's mixture (slc_bounds::sg::ggx_mixture).
        let lambda = lobes[k].w;
        // The mixture's scale s(λ) is in the packed c (GpuVsgl::new, vsgl_pack).
        var count = 1u;
        var stretch = 1.0;
        if k == 1u && lambda >= MIXTURE_FROM {
            count = 3u;
            stretch = stretch_factor(e, position.axis);
        }
        for (var m = 0u; m < count; m++) {
            var emitted = Sg(lobes[k].xyz, lambda, 1.0);
            if count == 3u {
                // Emitter::radiance_in: each SG of the mixture stretched towards the receiver.
                let l = GGX_MIXTURE[m].x * lambda;
                let a = stretch_amplitude(e, l, stretch, position.sharpness);
                emitted = Sg(lobes[k].xyz, l * stretch, GGX_MIXTURE[m].y * a);
            }
            let light = sg_product(emitted, position);
            if !(sg_finite(light.sharpness) && sg_finite(light.amplitude)) {
                overflow = 1.0;
            }
            radiance += c * surface_radiance(surface, light);
        }
    }
    // The clamped-cosine diffuse intensity (DiffuseEmission::ClampedCosine): the
    // peak times the vMF-convolved clamped cosine towards the receiver (a quarter
    // at mu_v itself), carried by the positional SG.
    let peak = e.diffuse_c_density.xyz;
    if clamped && any(peak != vec3<f32>(0.0)) {
        var towards = 0.25;
        if r2 > 0.0 {
            towards = sg_normalized_irradiance(e.diffuse_lobe.w, -dot(e.diffuse_lobe.xyz, position.axis));
        }
        if towards > 0.0 {
            radiance += peak * towards * surface_radiance(surface, position);
        }
    }
    return vec4<f32>(radiance, overflow);
}
