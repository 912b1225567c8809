// The VSGL of a cluster (crates/cpu-ref/src/vsgl/light.rs Vsgl::from_sums, scaled by its
// sample's weight) packed for shading as src/vsgl_types.rs GpuVsgl::new packs it, in f32.
// sg.wgsl, sg_surface.wgsl, vsgl_light.wgsl and vsgl_sums.wgsl come first.

// toksvig.rs MAX_MEAN_LENGTH, the largest f32 below 1.
const MAX_MEAN_LENGTH: f32 = 0.99999994;

// toksvig.rs clamp_length: r clamped to [0, MAX_MEAN_LENGTH], NaN to 0.
fn clamp_length(r: f32) -> f32 {
    if r > 0.0 {
        return min(r, MAX_MEAN_LENGTH);
    }
    return 0.0;
}

// toksvig.rs toksvig_sharpness: λ = r / (1 - r).
fn toksvig_sharpness(r_in: f32) -> f32 {
    let r = clamp_length(r_in);
    return r / (1.0 - r);
}

// toksvig.rs exact_sharpness: the λ whose Langevin mean length coth λ - 1/λ is r. With
// q = 1 - r: above λ = 20 (q <= 1/20) 1 - L = 1/λ to f32 precision, so λ = 1/q; below, Newton
// on 1 - L(λ) = q (sg_langevin forms 1 - L without cancelling) from Banerjee's start
// r (3 - r^2) / (1 - r^2), the slope L' = 1/λ^2 - 1/sinh^2 λ by its series below 1 (where
// that difference cancels) and 1/λ^2 - 4e/(1 - e)^2, e = e^{-2λ}, above.
fn exact_sharpness(r_in: f32) -> f32 {
    let r = clamp_length(r_in);
    let q = 1.0 - r;
    if q <= 0.05 {
        return 1.0 / q;
    }
    var l = r * (3.0 - r * r) / (1.0 - r * r);
    for (var i = 0; i < 30; i++) {
        var slope: f32;
        if l < 1.0 {
            let l2 = l * l;
            slope = 1.0 / 3.0 + l2 * (-1.0 / 15.0 + l2 * (2.0 / 189.0 - l2 / 675.0));
        } else {
            let e = exp(-2.0 * l);
            slope = 1.0 / (l * l) - 4.0 * e / ((1.0 - e) * (1.0 - e));
        }
        // (1 - L) falls with λ: λ moves by (1 - L - q) / L'.
        let next = max(l + (sg_langevin(l).y - q) / slope, 0.1 * l);
        let done = abs(next - l) <= 1e-7 * next;
        l = next;
        if done {
            break;
        }
    }
    return l;
}

// One lobe buffer turned back into a lobe (toksvig.rs ToksvigSum::to_lobe and light.rs
// filtered): axis ξ̄/|ξ̄| (+z for a zero mean), sharpness r/(1 - r) of r = |ξ̄|, and
// c = Σ Φ R / A(λ) per channel; ξ̄ = Σ w ξ̄ / Σ w with Σ w the RGB total (zero when empty).
struct Lobe {
    axis: vec3<f32>,
    sharpness: f32,
    c: vec3<f32>,
    // |ξ̄|, the mean length (the diffuse lobe's gives the normals' concentration).
    mean_length: f32,
}

fn filtered_lobe(mean_sum: vec3<f32>, rgb: vec3<f32>) -> Lobe {
    let weight = rgb.x + rgb.y + rgb.z;
    var mean = vec3<f32>(0.0);
    if weight > 0.0 {
        mean = mean_sum / weight;
    }
    let r = length(mean);
    var axis = vec3<f32>(0.0, 0.0, 1.0);
    if r > 0.0 {
        axis = normalize(mean / r);
    }
    let sharpness = toksvig_sharpness(r);
    return Lobe(axis, sharpness, rgb / sg_integral(sharpness), r);
}

// A packed VSGL and whether it is inside the shading's domain (GpuVsgl::new's checks, and
// every coefficient inside f32 as Vsgl::from_sums requires).
struct Packed {
    vsgl: Vsgl,
    ok: bool,
}

// The VSGL of cluster `s` times `factor` (Vsgl::from_sums, Vsgl::scaled), σ_v^2 at least
// `sigma2_floor`, packed with the diffuse lobe as the clamped cosine of the normals'
// concentration (`clamped`) or as the SG.
fn vsgl_pack(s: Sums, factor: f32, sigma2_floor: f32, clamped: bool) -> Packed {
    let diffuse = filtered_lobe(s.diffuse_mean.xyz, s.diffuse_m2.xyz);
    let specular = filtered_lobe(s.specular_mean.xyz, s.specular_w.xyz);
    let w = s.specular_w.w;
    var mu = vec3<f32>(0.0);
    var sigma2 = 0.0;
    if w > 0.0 {
        mu = s.mu.xyz;
        sigma2 = max(s.diffuse_m2.w / w, 0.0);
    }
    sigma2 = max(sigma2, sigma2_floor);
    let density = 1.0 / (TAU * sigma2);
    var ok = sigma2 > 0.0 && sg_finite(density) && finite3(mu);
    let c_d = diffuse.c * factor;
    let c_s = specular.c * factor;
    ok = ok && finite3(c_d) && finite3(c_s) && all(c_d >= vec3<f32>(0.0)) && all(c_s >= vec3<f32>(0.0));
    var diffuse_c = vec3<f32>(0.0);
    var diffuse_lobe = vec4<f32>(0.0);
    if any(c_d != vec3<f32>(0.0)) {
        if clamped {
            // light.rs normal_concentration: |ξ̄_d| over one texel's mean length.
            let kappa = exact_sharpness(diffuse.mean_length / toksvig_mean_length(COSINE_LOBE_SHARPNESS));
            diffuse_c = c_d * (sg_integral(diffuse.sharpness) * (1.0 / PI));
            diffuse_lobe = vec4<f32>(diffuse.axis, kappa);
            ok = ok && finite3(diffuse_c);
        } else {
            diffuse_c = c_d;
            diffuse_lobe = vec4<f32>(-diffuse.axis, diffuse.sharpness);
        }
    }
    var specular_lobe = vec4<f32>(0.0);
    var specular_c = c_s;
    var stretch = array<vec4<f32>, 2>(vec4<f32>(0.0, 0.0, 0.0, 1.0), vec4<f32>(0.0, 0.0, 0.0, 1.0));
    if any(c_s != vec3<f32>(0.0)) {
        specular_lobe = vec4<f32>(-specular.axis, specular.sharpness);
        // GpuVsgl::new: the mixture's scale s(λ) in c, once per VSGL.
        if specular.sharpness >= MIXTURE_FROM {
            specular_c = c_s * mixture_scale(specular.sharpness);
            ok = ok && finite3(specular_c);
        }
        // light.rs Vsgl::specular_stretch: the direction of Σ w_s n (zero where it is zero).
        let n_sum = sums_specular_normal(s);
        var normal = vec3<f32>(0.0);
        if any(n_sum != vec3<f32>(0.0)) {
            normal = normalize(n_sum);
        }
        stretch = lobe_stretch(specular.axis, specular.sharpness, normal);
    }
    let vsgl = Vsgl(
        vec4<f32>(mu, sigma2),
        vec4<f32>(diffuse_c, density),
        diffuse_lobe,
        vec4<f32>(specular_c, select(0.0, 1.0, clamped)),
        specular_lobe,
        stretch[0],
        stretch[1],
    );
    return Packed(vsgl, ok);
}
