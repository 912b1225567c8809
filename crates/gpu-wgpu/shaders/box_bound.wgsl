// One VPL's bound of p(w_o, l) of eq. (2) over boxes of receivers, the GPU twin of
// slc_bounds::BoxBound (crates/bounds/src/box_bound.rs, docs/tight-bounds.md), in the culling
// view: written by bounds.wgsl, tested by tight_cull.wgsl (fresnel_ggx.wgsl prepended to
// both). Mirrors GpuBoxBound in src/cull_types.rs.
//
// The CPU forms the bound in f64 and covers only the shader's f32 rounding; here the bound
// itself is formed in f32, so besides the CPU's slacks every cosine it compares grows by
// COS_SLACK towards the side that keeps more (its f32 rounding is about 1e-7), and every box
// grows by the VPL's q_slack.w for the rounding of the positions it is formed from.

struct BoxBound {
    q_slack: vec4<f32>,
    normal_peak: vec4<f32>,
    omega_i_cos_h_max: vec4<f32>,
    omega_u_g1_i: vec4<f32>,
    flux_alpha: vec4<f32>,
    f0_eta: vec4<f32>,
    // (kind, Fresnel model, bits of the alpha of G1(w_o) (0.0: bounded by 1), bits of
    // delta xi / (1 + PROBABILITY_SLACK))
    info: vec4<u32>,
}

const BOX_EMPTY: u32 = 0u;
const BOX_DIFFUSE: u32 = 1u;
const BOX_GLOSSY: u32 = 2u;
// slc_bounds::box_bound::CONE_SLACK and PROBABILITY_SLACK.
const CONE_SLACK: f32 = 1e-5;
const PROBABILITY_SLACK: f32 = 1e-3;
const COS_SLACK: f32 = 1e-6;

// The cone of directions from the origin to the ball of `radius` around `center`: axis,
// cos and sin of its half-angle grown by CONE_SLACK; unbounded where the ball reaches the
// origin.
struct Cone {
    axis: vec3<f32>,
    cos_b: f32,
    sin_b: f32,
    bounded: bool,
}

fn cone_around(center: vec3<f32>, radius: f32) -> Cone {
    let distance = length(center);
    let sin_b = radius / distance + CONE_SLACK;
    if !(sin_b < 1.0) {
        return Cone(vec3<f32>(0.0), -1.0, 1.0, false);
    }
    return Cone(center / distance, sqrt(1.0 - sin_b * sin_b), sin_b, true);
}

// The largest cosine between unit `u` and a direction of the cone, cos(max(0, angle - beta)),
// plus COS_SLACK.
fn cone_max_cos(c: Cone, u: vec3<f32>) -> f32 {
    let cos_g = clamp(dot(u, c.axis), -1.0, 1.0);
    if !c.bounded || cos_g >= c.cos_b {
        return 1.0;
    }
    // The sine as |u x axis|: sqrt(1 - cos^2) would turn the cosine's f32 rounding into an
    // angle off by up to 6e-4 near cos = +-1, far beyond the slacks.
    let v = cos_g * c.cos_b + length(cross(u, c.axis)) * c.sin_b;
    return min(v + COS_SLACK, 1.0);
}

// The smallest cosine between unit `u` and a direction of the cone, cos(min(pi, angle +
// beta)), minus COS_SLACK.
fn cone_min_cos(c: Cone, u: vec3<f32>) -> f32 {
    let cos_g = clamp(dot(u, c.axis), -1.0, 1.0);
    if !c.bounded || cos_g <= -c.cos_b {
        return -1.0;
    }
    let v = cos_g * c.cos_b - length(cross(u, c.axis)) * c.sin_b;
    return max(v - COS_SLACK, -1.0);
}

// BoxBound::may_exceed_xi: whether p > xi may hold at a receiver of the view-space box
// [box_lo, box_hi] (bounding ball: `center`, `radius`). The box is grown by the VPL's slack.
// The inputs are finite (the tile passes refuse non-finite samples, the bounds pass
// non-finite VPLs); an overflow to infinity or NaN on the way reaches a rejection written as
// a comparison that NaN fails, so it keeps the VPL.
fn box_may_exceed_xi(b: BoxBound, box_lo: vec3<f32>, box_hi: vec3<f32>, center: vec3<f32>,
                     radius: f32) -> bool {
    let q = b.q_slack.xyz;
    let slack = b.q_slack.w;
    let lo = box_lo - q - vec3<f32>(slack);
    let hi = box_hi - q + vec3<f32>(slack);
    let gap = max(max(lo, -hi), vec3<f32>(0.0));
    let l2_min = dot(gap, gap);
    if !(l2_min > 0.0) {
        return true;
    }
    let threshold = bitcast<f32>(b.info.w) * l2_min;
    // The distance against the largest intensity (the r/alpha sphere of section 7).
    if b.normal_peak.w <= threshold {
        return false;
    }
    // The tangent plane: h, the largest n.d over the box (at a corner); w_o.n <= h/|d|.
    let n = b.normal_peak.xyz;
    let h = dot(max(n * lo, n * hi), vec3<f32>(1.0));
    let far = max(abs(lo), abs(hi));
    if h < 0.0 && h * h >= CONE_SLACK * CONE_SLACK * dot(far, far) {
        return false;
    }
    let cone = cone_around(center - q, radius + 1.7320508 * slack);
    let plane_cos = max(h, 0.0) / sqrt(l2_min) + CONE_SLACK;
    let cos_o = min(cone_max_cos(cone, n), plane_cos);
    if cos_o <= 0.0 {
        return false;
    }
    if b.info.x == BOX_DIFFUSE {
        return !(b.normal_peak.w * cos_o <= threshold);
    }
    // D(cos(theta_min / 2)) of eq. (7) with sin^2(theta/2) = (1 - cos theta) / 2.
    let sin2 = 0.5 * (1.0 - cone_max_cos(cone, b.omega_u_g1_i.xyz));
    let a2 = b.flux_alpha.w * b.flux_alpha.w;
    let denom = a2 + (1.0 - a2) * sin2;
    let d = a2 / (PI * denom * denom);
    // G1(w_o) <= G1(cos_o) of the lobe's smallest alpha (eq. 8), or 1.
    let g1_alpha = bitcast<f32>(b.info.z);
    var g1_o = 1.0;
    if g1_alpha > 0.0 {
        let c = min(cos_o, 1.0);
        g1_o = ggx_g1_over_cos(g1_alpha, c) * c;
    }
    // The smallest w_i.w_h over the cone, no smaller than cos theta_h_max.
    let cos_h = max(sqrt(max(0.5 * (1.0 + cone_min_cos(cone, b.omega_i_cos_h_max.xyz)), 0.0)),
                    b.omega_i_cos_h_max.w);
    let f = scalar(b.flux_alpha.xyz
                   * fresnel_max_from(b.info.y, b.f0_eta.xyz, b.f0_eta.w, cos_h));
    return !(f * b.omega_u_g1_i.w * g1_o * d <= threshold);
}
