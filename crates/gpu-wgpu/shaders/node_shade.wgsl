// Stochastic VPL shading from linked lists in a node buffer (the raster baselines' lists,
// cluster_fill.wgsl [OP16]): each pixel with a sample walks the list of its cluster
// (pixel_list) and sums the VPLs' contributions (vpl_eval.wgsl). The nodes' order is the
// order the GPU appended them in, so sums may differ in the last bits from run to run.
// brdf.wgsl, gsample.wgsl, gvpl.wgsl and vpl_eval.wgsl are prepended.

@group(0) @binding(0) var<uniform> params: ShadeParams;
@group(0) @binding(1) var<storage, read> samples: array<Sample>;
@group(0) @binding(2) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(3) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> pixel_list: array<u32>;
@group(0) @binding(5) var<storage, read> heads: array<u32>;
@group(0) @binding(6) var<storage, read> nodes: array<vec2<u32>>;
// RGB per pixel, every pixel written.
@group(0) @binding(7) var<storage, read_write> image: array<f32>;

const END: u32 = 0xffffffffu;

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * 64u + lid;
    if pixel >= params.pixel_count {
        return;
    }
    let s = samples[pixel];
    let list = pixel_list[pixel];
    var sum = vec3<f32>(0.0);
    if sample_present(s) && list != END && list < params.list_count {
        let r = receiver(s, positions[pixel].xyz);
        var n = heads[list];
        while n != END {
            let node = nodes[n];
            let c = vpl_contribution(r, vpls[node.x], params.delta);
            if any(c != vec3<f32>(0.0)) {
                sum += c * params.scale;
            }
            n = node.y;
        }
    }
    image[3u * pixel] = sum.x;
    image[3u * pixel + 1u] = sum.y;
    image[3u * pixel + 2u] = sum.z;
}
