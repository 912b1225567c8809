// Exclusive prefix sum in place over values[0..n], with values[n] = the total: the list
// offsets from the per-tile counts of tiled_cull.wgsl, the partition's offsets. One 256-thread
// workgroup: each invocation sums its own run of about n / 256 consecutive values, the
// workgroup scans the 256 run sums (Hillis-Steele), and each invocation writes its run's
// offsets from its run's start. About 16 barriers whatever n is (a workgroup walking n in
// chunks of 256 took 16 per chunk).
// Structs mirror src/gpu_types.rs (GpuScanParams, GpuCullStatus).

struct ScanParams {
    count: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> params: ScanParams;
@group(0) @binding(1) var<storage, read_write> values: array<u32>;
// [2] total, [3] 1 if the total overflowed u32.
@group(0) @binding(2) var<storage, read_write> status: array<atomic<u32>, 4>;

const GROUP: u32 = 256u;
const U32_MAX: u32 = 0xffffffffu;

var<workgroup> partial: array<u32, 256>;
var<workgroup> overflowed: atomic<u32>;

// a + b, flagging a sum beyond u32 (the sum is then wrong, and the status says so).
fn add(a: u32, b: u32) -> u32 {
    if a > U32_MAX - b {
        atomicStore(&overflowed, 1u);
    }
    return a + b;
}

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) lid: u32) {
    let n = params.count;
    let per = (n + GROUP - 1u) / GROUP;
    let lo = min(lid * per, n);
    let hi = min(lo + per, n);
    var sum = 0u;
    for (var i = lo; i < hi; i++) {
        sum = add(sum, values[i]);
    }
    partial[lid] = sum;
    for (var d = 1u; d < GROUP; d <<= 1u) {
        workgroupBarrier();
        var s = partial[lid];
        if lid >= d {
            s = add(s, partial[lid - d]);
        }
        workgroupBarrier();
        partial[lid] = s;
    }
    workgroupBarrier();
    // partial[lid] is now the inclusive sum of runs 0..=lid.
    var offset = partial[lid] - sum;
    for (var i = lo; i < hi; i++) {
        let v = values[i];
        values[i] = offset;
        offset += v;
    }
    if lid == 0u {
        let total = partial[GROUP - 1u];
        values[n] = total;
        atomicStore(&status[2], total);
        if atomicLoad(&overflowed) != 0u {
            atomicStore(&status[3], 1u);
        }
    }
}
