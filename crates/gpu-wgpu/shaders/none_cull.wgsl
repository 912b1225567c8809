// No culling (crates/cull/src/strategies/none.rs): every pixel with a sample gets every VPL
// of its interleaved subregion (paper section 6). rng.wgsl, bound.wgsl and gvpl.wgsl
// prepended; one invocation per VPL or pixel, whichever are more:
// - VPL i becomes a bound that reaches everything (a sphere of infinite radius) recording
//   its subregion, vpl_subregion(seed, id, K), so that partition.wgsl groups all VPLs by
//   subregion in ascending order: subregion s's list is the partition's segment s;
// - pixel (x, y) gets list (y mod K) K + x mod K (Interleaving::pixel_subregion) if it has a
//   sample, NO_LIST otherwise.
// Mirrors GpuNoneParams in src/cull_types.rs.

struct NoneParams {
    vpl_count: u32,
    pixel_count: u32,
    width: u32,
    k: u32,
    seed: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> params: NoneParams;
// The VPLs (gvpl.wgsl): their ids, info.z (Vpl::id).
@group(0) @binding(1) var<storage, read> vpls: array<Vpl>;
// The G-buffer positions [x, y, z, 1], zero where the pixel has no sample.
@group(0) @binding(2) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> bounds: array<Bound>;
@group(0) @binding(4) var<storage, read_write> pixel_list: array<u32>;

const NO_LIST: u32 = 0xffffffffu;

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = (wid.y * groups.x + wid.x) * 64u + lid;
    if i < params.vpl_count {
        let zero = vec4<f32>(0.0);
        let everywhere = vec4<f32>(0.0, 0.0, 0.0, bitcast<f32>(0x7f800000u));
        bounds[i] = Bound(array<vec4<f32>, 3>(zero, zero, zero), everywhere, BOUND_SPHERE, i,
                          vpl_subregion(params.seed, vpls[i].info.z, params.k), 0u);
    }
    if i < params.pixel_count {
        let x = i % params.width;
        let y = i / params.width;
        let subregion = (y % params.k) * params.k + x % params.k;
        pixel_list[i] = select(NO_LIST, subregion, positions[i].w != 0.0);
    }
}
