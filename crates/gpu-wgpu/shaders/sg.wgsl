// Spherical Gaussian algebra of crates/bounds/src/sg in f32 (Tokuyoshi 2015, "Virtual
// Spherical Gaussian Lights", section 2.2 and eq. 5): A(lambda) (integral.rs), the product
// and inner product (product.rs, integral.rs), the horizon-clamped irradiance (irradiance.rs,
// Hill's fit with exact limits) and the Langevin mean length (toksvig.rs). Where the CPU
// works in f64, these forms avoid the cancellations f32 would suffer instead: expm1 and the
// Langevin function by their series for small arguments, 1 - L(lambda) without forming L,
// lambda1 lambda2 / (d + lambda1 + lambda2) without overflowing. fresnel_ggx.wgsl (PI) comes
// first.

const TAU: f32 = 6.28318530717959;
const F32_MAX: f32 = 3.40282347e38;
// c0 of Hill's fit (irradiance.rs HILL_C0).
const HILL_C0: f32 = 0.36;

// c G(w; axis, sharpness) = c exp(sharpness (w.axis - 1)).
struct Sg {
    axis: vec3<f32>,
    sharpness: f32,
    amplitude: f32,
}

// Finite (NaN fails the comparison).
fn sg_finite(x: f32) -> bool {
    return abs(x) <= F32_MAX;
}

// exp(x) - 1: its Taylor series to x^10/10! below |x| = 1/2 (truncation below 3e-10 of the
// value), exp(x) - 1 above, where it does not cancel.
fn sg_expm1(x: f32) -> f32 {
    if abs(x) < 0.5 {
        var t = 1.0 / 3628800.0;
        t = fma(t, x, 1.0 / 362880.0);
        t = fma(t, x, 1.0 / 40320.0);
        t = fma(t, x, 1.0 / 5040.0);
        t = fma(t, x, 1.0 / 720.0);
        t = fma(t, x, 1.0 / 120.0);
        t = fma(t, x, 1.0 / 24.0);
        t = fma(t, x, 1.0 / 6.0);
        t = fma(t, x, 0.5);
        t = fma(t, x, 1.0);
        return t * x;
    }
    return exp(x) - 1.0;
}

// A(lambda) = 2 pi / lambda (1 - e^{-2 lambda}) (integral.rs integral_f64): 4 pi at 0,
// 2 pi / lambda above 20.
fn sg_integral(sharpness: f32) -> f32 {
    let l = max(sharpness, 0.0);
    if l == 0.0 {
        return 4.0 * PI;
    }
    if l > 20.0 {
        return TAU / l;
    }
    return -TAU * sg_expm1(-2.0 * l) / l;
}

// (L, 1 - L) for the Langevin function L = coth lambda - 1/lambda (toksvig.rs langevin):
// below 1 its series (eight terms, 2^2n B_2n lambda^(2n-1) / (2n)!, truncation below 1e-8
// of the value); up to 20 with coth = 1 + t, t = 2e/(1 - e), e = exp(-2 lambda), and
// 1 - L = 1/lambda - t formed directly (the CPU's 1 - L in f64 keeps those digits too);
// above 20, 1 - 1/lambda and 1/lambda.
fn sg_langevin(l: f32) -> vec2<f32> {
    if l < 1.0 {
        let l2 = l * l;
        var s = -2.2214608789979678e-8;
        s = fma(s, l2, 2.1925947851873778e-7);
        s = fma(s, l2, -2.1644042808063972e-6);
        s = fma(s, l2, 2.1377799155576935e-5);
        s = fma(s, l2, -2.1164021164021165e-4);
        s = fma(s, l2, 2.1164021164021165e-3);
        s = fma(s, l2, -2.2222222222222223e-2);
        s = fma(s, l2, 1.0 / 3.0);
        let mean = s * l;
        return vec2<f32>(mean, 1.0 - mean);
    }
    if l > 20.0 {
        return vec2<f32>(1.0 - 1.0 / l, 1.0 / l);
    }
    let e = exp(-2.0 * l);
    let t = 2.0 * e / (1.0 - e);
    return vec2<f32>((1.0 + t) - 1.0 / l, 1.0 / l - t);
}

// b(lambda) = E(lambda, -1) = e^{-l} (1 - e^{-l}(1 + l)) / (l (1 - e^{-2l})) (irradiance.rs
// away_facing): 1/4 - l/6 below 1e-3, the closed form from 1 on, and between them the
// numerator 1 - e^{-l}(1 + l) = l^2 sum_{k>=2} (-1)^k (k - 1)/k! l^(k-2) by its series to
// k = 12 (truncation below 1e-8 of the value), which f32 would otherwise lose to cancellation.
fn sg_away_facing(l: f32) -> f32 {
    if l < 1e-3 {
        return 0.25 - l / 6.0;
    }
    let e = exp(-l);
    if l >= 1.0 {
        return e * (1.0 - e * (1.0 + l)) / (l * (1.0 - e * e));
    }
    var s = 2.296443268665491e-8;
    s = fma(s, l, -2.505210838544172e-7);
    s = fma(s, l, 2.48015873015873e-6);
    s = fma(s, l, -2.2045855379188714e-5);
    s = fma(s, l, 1.7361111111111112e-4);
    s = fma(s, l, -1.1904761904761906e-3);
    s = fma(s, l, 6.944444444444444e-3);
    s = fma(s, l, -3.333333333333333e-2);
    s = fma(s, l, 0.125);
    s = fma(s, l, -1.0 / 3.0);
    s = fma(s, l, 0.5);
    // e n / (l (1 - e^{-2l})) with n = l^2 s.
    return e * (l * s) / -sg_expm1(-2.0 * l);
}

// E(lambda, mu) = L y(mu) + b(lambda), Hill's fit with exact limits (irradiance.rs
// normalized_sg_irradiance), clamped to [0, 1].
fn sg_normalized_irradiance(sharpness: f32, mu_in: f32) -> f32 {
    let l = max(sharpness, 0.0);
    let mu = clamp(mu_in, -1.0, 1.0);
    let lv = sg_langevin(l);
    let x = sqrt(max(lv.y, 0.0));
    let switch_x = 4.0 * HILL_C0 * HILL_C0;
    var y: f32;
    if x >= switch_x {
        let a = 0.25 + 0.25 * (x - switch_x) / (1.0 - switch_x);
        y = a + 0.5 * mu + (0.5 - a) * mu * mu;
    } else {
        let x0 = HILL_C0 * mu;
        let x1 = x / (4.0 * HILL_C0);
        if x > 0.0 && abs(x0) <= x1 {
            y = (x0 + x1) * (x0 + x1) / x;
        } else {
            y = max(mu, 0.0);
        }
    }
    return clamp(lv.x * y + sg_away_facing(l), 0.0, 1.0);
}

// The irradiance c A(lambda) E(lambda, axis.n) on unit normal n, saturated at F32_MAX
// (SphericalGaussian::irradiance).
fn sg_irradiance(g: Sg, n: vec3<f32>) -> f32 {
    let e = sg_normalized_irradiance(g.sharpness, dot(g.axis, n));
    return min(g.amplitude * sg_integral(g.sharpness) * e, F32_MAX);
}

// The combined lobe of a and b (product.rs Merged): lambda_a xi_a + lambda_b xi_b, its length
// d (scaled by the larger sharpness first, so squares cannot overflow) and the exponent
// d - lambda_a - lambda_b = -lambda_a (lambda_b / (d + lambda_a + lambda_b)) |xi_a - xi_b|^2,
// free of cancellation. The axes are unit already (the CPU renormalizes them in f64).
struct Merged {
    axis_sum: vec3<f32>,
    sharpness: f32,
    log_scale: f32,
}

fn sg_merge(a: Sg, b: Sg) -> Merged {
    let la = a.sharpness;
    let lb = b.sharpness;
    let axis_sum = a.axis * la + b.axis * lb;
    let m = max(la, lb);
    var d = 0.0;
    if m > 0.0 {
        d = m * length(a.axis * (la / m) + b.axis * (lb / m));
    }
    let total = d + la + lb;
    var log_scale = 0.0;
    if total > 0.0 {
        let dx = a.axis - b.axis;
        log_scale = -la * (lb / total) * dot(dx, dx);
    }
    return Merged(axis_sum, d, log_scale);
}

// The product a b as one SG (VSGL eq. 5, product.rs): axis (la xa + lb xb)/d, sharpness d,
// amplitude ca cb e^{d - la - lb}; the constant c with axis a.axis where d vanishes. The
// caller checks that sharpness and amplitude are finite (the CPU's Overflow errors).
fn sg_product(a: Sg, b: Sg) -> Sg {
    let m = sg_merge(a, b);
    let amplitude = a.amplitude * b.amplitude * exp(m.log_scale);
    var axis = a.axis;
    var sharpness = 0.0;
    if m.sharpness > 0.0 {
        let v = normalize(m.axis_sum / m.sharpness);
        if sg_finite(v.x) && sg_finite(v.y) && sg_finite(v.z) {
            axis = v;
        }
        sharpness = m.sharpness;
    }
    return Sg(axis, sharpness, amplitude);
}

// The inner product ca cb e^{d - la - lb} A(d) (integral.rs inner_product), saturated at
// F32_MAX.
fn sg_inner_product(a: Sg, b: Sg) -> f32 {
    let m = sg_merge(a, b);
    return min(a.amplitude * b.amplitude * exp(m.log_scale) * sg_integral(m.sharpness), F32_MAX);
}
