// Indirect dispatch arguments from a count a pass left on the GPU (src/gpu_count.rs):
// count * per_item invocations in workgroups of `workgroup`, laid out as buffers::Grid lays
// them out (x = min(groups, max_x), y = ceil(groups / x)), so that a shader's linear
// workgroup index wid.y * num_workgroups.x + wid.x is the same as with a host-sized grid.
// One invocation. The host checks that the count's capacity times per_item fits u32.

struct ArgsParams {
    per_item: u32,
    workgroup: u32,
    max_x: u32,
    // The count's index in `counts` (its byte offset / 4).
    index: u32,
}

@group(0) @binding(0) var<uniform> params: ArgsParams;
@group(0) @binding(1) var<storage, read> counts: array<u32>;
@group(0) @binding(2) var<storage, read_write> args: array<u32, 3>;

@compute @workgroup_size(1)
fn main() {
    let items = counts[params.index] * params.per_item;
    let groups = items / params.workgroup + select(0u, 1u, items % params.workgroup != 0u);
    let x = min(groups, params.max_x);
    var y = 1u;
    if x > 0u {
        y = groups / x + select(0u, 1u, groups % x != 0u);
    }
    args[0] = x;
    args[1] = y;
    args[2] = 1u;
}
