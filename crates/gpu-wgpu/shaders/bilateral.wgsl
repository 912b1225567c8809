// The cross bilateral filter (paper section 6, after Petschnigg et al. 2004 and Eisemann and
// Durand 2004), the GPU twin of crates/cpu-ref/src/denoise.rs cross_bilateral: one pass of
// the separable kernel per dispatch, along x (params.axis 0) then along y (axis 1), one
// invocation per pixel (linear workgroup index wid.y * num_workgroups.x + wid.x,
// buffers::Grid). fresnel_ggx.wgsl is prepended. Structs mirror src/denoise_types.rs.
//
// A pixel with a sample averages its 2r + 1 taps along the pass's axis that lie inside the
// image and have a sample, each weighted by
//   exp(-d^2 / (2 sigma_s^2)) max(n.n', 0)^(2^k) exp(-dz^2 / (2 sigma_z^2)),
//   dz = (z' - z) / max(z, 1e-6),
// with z the sample's linear view depth (position - eye).forward (GSample::depth). The filter
// works on demodulated radiance: the x pass divides each tap by its reflectance
// max(kd + F(1), 1e-3), the y pass multiplies the result by the pixel's own. A pixel without a
// sample keeps its value in both passes.

struct BilateralParams {
    eye: vec4<f32>,
    forward: vec4<f32>,
    width: u32,
    height: u32,
    radius: u32,
    normal_squarings: u32,
    // 1 / (2 sigma_s^2), 1 / (2 sigma_z^2).
    inv_2ss: f32,
    inv_2sd: f32,
    axis: u32,
    pad: u32,
}

@group(0) @binding(0) var<uniform> params: BilateralParams;
@group(0) @binding(1) var<storage, read> samples: array<Sample>;
// RGB per pixel: the image (axis 0) or the x pass's output (axis 1).
@group(0) @binding(2) var<storage, read> values: array<f32>;
@group(0) @binding(3) var<storage, read_write> filtered: array<f32>;
// The G-buffer positions [x, y, z, 1] (gsample.wgsl).
@group(0) @binding(4) var<storage, read> positions: array<vec4<f32>>;

const WORKGROUP: u32 = 64u;

fn value(p: u32) -> vec3<f32> {
    return vec3<f32>(values[3u * p], values[3u * p + 1u], values[3u * p + 2u]);
}

// kd + F(1) of eq. (6) (Fresnel::eval(1.0)), at least 1e-3 per channel (denoise.rs
// reflectance).
fn reflectance(s: Sample) -> vec3<f32> {
    var f = vec3<f32>(fresnel_dielectric(s.f0_eta.x, 1.0));
    if sample_fresnel_kind(s) == FRESNEL_SCHLICK {
        f = fresnel_schlick(s.f0_eta, 1.0);
    }
    return max(s.kd_alpha_t.xyz + f, vec3<f32>(1e-3));
}

fn depth(p: u32) -> f32 {
    return dot(positions[p].xyz - params.eye.xyz, params.forward.xyz);
}

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let p = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if p >= params.width * params.height {
        return;
    }
    let g = samples[p];
    var out = value(p);
    if sample_present(g) {
        let x = i32(p % params.width);
        let y = i32(p / params.width);
        let step = select(vec2<i32>(0, 1), vec2<i32>(1, 0), params.axis == 0u);
        let r = i32(params.radius);
        let z = depth(p);
        let n = g.normal_alpha.xyz;
        var sum = vec3<f32>(0.0);
        var weight = 0.0;
        for (var d = -r; d <= r; d++) {
            let xx = x + d * step.x;
            let yy = y + d * step.y;
            if xx < 0 || yy < 0 || xx >= i32(params.width) || yy >= i32(params.height) {
                continue;
            }
            let q = u32(yy) * params.width + u32(xx);
            let gq = samples[q];
            if !sample_present(gq) {
                continue;
            }
            let dz = (depth(q) - z) / max(z, 1e-6);
            var wn = max(dot(n, gq.normal_alpha.xyz), 0.0);
            for (var i = 0u; i < params.normal_squarings; i++) {
                wn *= wn;
            }
            let spatial = exp(-f32(d * d) * params.inv_2ss);
            let wq = spatial * wn * exp(-dz * dz * params.inv_2sd);
            var v = value(q);
            if params.axis == 0u {
                v = v / reflectance(gq);
            }
            sum += v * wq;
            weight += wq;
        }
        // The centre tap has weight 1 (up to the rounding of n.n), so weight > 0.
        out = sum / weight;
        if params.axis == 1u {
            out *= reflectance(g);
        }
    }
    filtered[3u * p] = out.x;
    filtered[3u * p + 1u] = out.y;
    filtered[3u * p + 2u] = out.z;
}
