// Stochastic VPL shading from light lists (paper eq. 3 with interleaved sampling), the GPU
// twin of crates/cpu-ref/src/vpl_shading.rs shade_lists without visibility: each pixel with a
// sample sums, over the VPLs of its list,
//   f_x(n, w_l, w_o) I(w) / l^2 cos theta_x K^2 / p   when p > xi,
// with I the VPL's intensity of eq. (4) (crates/core/src/vpl.rs) and p = min(I / (delta l^2), 1)
// of eq. (2) on the largest channel of I. brdf.wgsl is prepended. Structs mirror
// src/gpu_types.rs; one invocation per pixel, linear workgroup index wid.y * num_workgroups.x
// + wid.x (buffers::Grid).

@group(0) @binding(0) var<uniform> params: ShadeParams;
@group(0) @binding(1) var<storage, read> samples: array<Sample>;
@group(0) @binding(2) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(3) var<storage, read> offsets: array<u32>;
@group(0) @binding(4) var<storage, read> indices: array<u32>;
@group(0) @binding(5) var<storage, read> pixel_list: array<u32>;
// RGB per pixel.
@group(0) @binding(6) var<storage, read_write> image: array<f32>;
// The G-buffer positions [x, y, z, 1] (gsample.wgsl).
@group(0) @binding(7) var<storage, read> positions: array<vec4<f32>>;

const NO_LIST: u32 = 0xffffffffu;
const WORKGROUP: u32 = 64u;

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if pixel >= params.pixel_count {
        return;
    }
    let s = samples[pixel];
    let x = positions[pixel].xyz;
    var sum = vec3<f32>(0.0);
    let list = pixel_list[pixel];
    if sample_present(s) && list != NO_LIST && list < params.list_count {
        let r = receiver(s, x);
        let end = offsets[list + 1u];
        for (var e = offsets[list]; e < end; e++) {
            let k = indices[e];
            if k < params.vpl_count {
                let c = vpl_contribution(r, vpls[k], params.delta);
                if any(c != vec3<f32>(0.0)) {
                    sum += c * params.scale;
                }
            }
        }
    }
    image[3u * pixel] = sum.x;
    image[3u * pixel + 1u] = sum.y;
    image[3u * pixel + 2u] = sum.z;
}
