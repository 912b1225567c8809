// Exclusive prefix sum in place over values[0..n], with values[n] = the total: the list
// offsets from the per-tile counts of tiled_cull.wgsl. One 256-thread workgroup walks the
// array in chunks (Hillis-Steele within a chunk, a running carry across chunks).
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

var<workgroup> partial: array<u32, 256>;
var<workgroup> carry: u32;

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) lid: u32) {
    if lid == 0u {
        carry = 0u;
    }
    let n = params.count;
    for (var base = 0u; base < n; base += GROUP) {
        let i = base + lid;
        var v = 0u;
        if i < n {
            v = values[i];
        }
        partial[lid] = v;
        for (var d = 1u; d < GROUP; d <<= 1u) {
            workgroupBarrier();
            var s = partial[lid];
            if lid >= d {
                s += partial[lid - d];
            }
            workgroupBarrier();
            partial[lid] = s;
        }
        let c = workgroupUniformLoad(&carry);
        if i < n {
            values[i] = c + partial[lid] - v;
        }
        workgroupBarrier();
        if lid == 0u {
            let chunk = partial[GROUP - 1u];
            if c > 0xffffffffu - chunk {
                atomicStore(&status[3], 1u);
            }
            carry = c + chunk;
        }
    }
    let total = workgroupUniformLoad(&carry);
    if lid == 0u {
        values[n] = total;
        atomicStore(&status[2], total);
    }
}
