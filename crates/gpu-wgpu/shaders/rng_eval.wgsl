// Evaluates rng.wgsl (prepended) for indices 0..count: the conformance pass of rng_pass.rs.
// Structs mirror src/gpu_types.rs (RngParams, RngSample).

struct RngParams {
    seed: u32,
    stream: u32,
    counter: u32,
    k: u32,
    count: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

struct RngSample {
    pcg: u32,
    hash: u32,
    uniform_bits: u32,
    subregion: u32,
}

@group(0) @binding(0) var<uniform> params: RngParams;
@group(0) @binding(1) var<storage, read_write> samples: array<RngSample>;

const WORKGROUP: u32 = 64u;

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    // Linear index across a 2-D grid (buffers::Grid).
    let i = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if i >= params.count {
        return;
    }
    let h = hash4(params.seed, i, params.stream, params.counter);
    samples[i] = RngSample(
        pcg_hash(i ^ params.seed),
        h,
        bitcast<u32>(uniform_number(params.seed, i, params.stream, params.counter)),
        vpl_subregion(params.seed, i, params.k),
    );
}
