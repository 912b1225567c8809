// The buffers of VSGL Fig. 4 for one cluster of VPLs (crates/cpu-ref/src/vsgl/sums.rs
// ClusterSums) in f32, summable over any set of texels as mip levels do, and the sums of one
// RSM texel's VPL (ClusterSums::from_texel with TexelLobes::new, Toksvig's mean map).
//
// The CPU keeps the position buffers as plain sums Σ w x and Σ w (|x|^2 + s^2) in f64, whose
// difference Σ w |x|^2 / Σ w - |μ|^2 would cancel in f32 for small clusters far from the
// origin. Here each cluster keeps its weighted mean μ and its second moment about it,
// M2 = Σ w (|x - μ|^2 + s^2), merged by the pairwise update of Chan, Golub and LeVeque
// (1979): μ = μa + δ wb / w, M2 = M2a + M2b + |δ|^2 wa wb / w with δ = μb - μa. The same
// σ_v^2 = M2 / Σ w, free of that cancellation. sg.wgsl and sg_surface.wgsl come first.

struct Sums {
    // (a) Σ Φ R_d (rgb) and M2 (w).
    diffuse_m2: vec4<f32>,
    // (b) Σ Φ R_s (rgb) and the positional weight Σ w, w = the RGB total of Φ (R_d + R_s) (w).
    specular_w: vec4<f32>,
    // (c) Σ w_d ξ̄_d, w_d the RGB total of Φ R_d and ξ̄_d the diffuse lobe's mean vector (xyz).
    // w: the x of (g).
    diffuse_mean: vec4<f32>,
    // (d) Σ w_s ξ̄_s, the same for the specular lobe (xyz). w: the y of (g).
    specular_mean: vec4<f32>,
    // μ = Σ w x / Σ w (xyz; zero for an empty cluster). w: the z of (g).
    mu: vec4<f32>,
}

// (g) Σ w_s n, the specular-weighted shading normal (the plane of incidence of the specular
// lobe's stretch), kept in the w components of (c), (d) and μ so that the pyramid keeps its
// five arrays (and bindings).
fn sums_specular_normal(s: Sums) -> vec3<f32> {
    return vec3<f32>(s.diffuse_mean.w, s.specular_mean.w, s.mu.w);
}

// cosine.rs COSINE_LOBE_SHARPNESS: the SG fit of the clamped cosine.
const COSINE_LOBE_SHARPNESS: f32 = 2.133;
// sums.rs MIN_FOOTPRINT_COS: a patch is stretched at most 100 times.
const MIN_FOOTPRINT_COS: f32 = 0.01;

fn sums_zero() -> Sums {
    return Sums(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
}

// ClusterSums::merge: every field a sum but μ and M2, merged as the header says (the w of μ,
// part of (g), is a sum).
fn sums_merge(a: Sums, b: Sums) -> Sums {
    let wa = a.specular_w.w;
    let wb = b.specular_w.w;
    let w = wa + wb;
    var mu = a.mu.xyz;
    var m2 = a.diffuse_m2.w + b.diffuse_m2.w;
    if w > 0.0 {
        let d = b.mu.xyz - a.mu.xyz;
        let t = wb / w;
        mu = a.mu.xyz + d * t;
        m2 += dot(d, d) * (wa * t);
    }
    return Sums(
        vec4<f32>(a.diffuse_m2.xyz + b.diffuse_m2.xyz, m2),
        vec4<f32>(a.specular_w.xyz + b.specular_w.xyz, w),
        a.diffuse_mean + b.diffuse_mean,
        a.specular_mean + b.specular_mean,
        vec4<f32>(mu, a.mu.w + b.mu.w),
    );
}

// toksvig.rs toksvig_mean_length: λ / (λ + 1), the paper's mean-vector length.
fn toksvig_mean_length(sharpness: f32) -> f32 {
    let l = max(sharpness, 0.0);
    return l / (l + 1.0);
}

// One texel's VPL as ClusterSums::from_texel takes it: where it lies, the geometric normal of
// its patch, its flux, its beam's cross-section a^2 and its surface seen from the light
// (omega_o = ω'_i, the photon's direction towards the light).
struct TexelIn {
    position: vec3<f32>,
    geometric_normal: vec3<f32>,
    flux: vec3<f32>,
    cross_section: f32,
    surface: SurfaceIn,
}

// sums.rs footprint_variance: the patch's positional variance a^2 (1 + 1/c^2) / 12, c the
// cosine |n_g . ω_i| (at least MIN_FOOTPRINT_COS).
fn footprint_variance(t: TexelIn) -> f32 {
    let a2 = max(t.cross_section, 0.0);
    let c = max(abs(dot(t.geometric_normal, t.surface.omega_o)), MIN_FOOTPRINT_COS);
    return a2 * (1.0 + 1.0 / (c * c)) / 12.0;
}

// ClusterSums::from_texel for a texel inside the SG domain (valid_surface): R_d = kd and
// R_s = the integral of the fitted GGX lobe of SpecularLobeSg seen from ω'_i (both zero for a
// photon below the shading normal, TexelLobes::new), their lobes' Toksvig mean vectors
// weighted by the RGB totals of Φ R, and the texel's position with the variance of its patch.
fn texel_sums(t: TexelIn) -> Sums {
    let surface = make_surface(t.surface);
    var r_d = vec3<f32>(0.0);
    var r_s = vec3<f32>(0.0);
    if dot(t.surface.normal, t.surface.omega_o) > 0.0 {
        r_d = t.surface.kd;
        r_s = surface.weight * (surface.lobe.amplitude * sg_integral(surface.lobe.sharpness));
    }
    let diffuse = t.flux * r_d;
    let specular = t.flux * r_s;
    let w_d = diffuse.x + diffuse.y + diffuse.z;
    let w_s = specular.x + specular.y + specular.z;
    let rgb = diffuse + specular;
    let w = rgb.x + rgb.y + rgb.z;
    let diffuse_mean = surface.normal * (w_d * toksvig_mean_length(COSINE_LOBE_SHARPNESS));
    let specular_mean = surface.lobe.axis * (w_s * toksvig_mean_length(surface.lobe.sharpness));
    let specular_normal = surface.normal * w_s;
    return Sums(
        vec4<f32>(diffuse, w * footprint_variance(t)),
        vec4<f32>(specular, w),
        vec4<f32>(diffuse_mean, specular_normal.x),
        vec4<f32>(specular_mean, specular_normal.y),
        vec4<f32>(t.position, specular_normal.z),
    );
}
