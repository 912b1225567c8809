// The VPLs of each interleaved subregion (paper section 6, Fig. 8), the GPU twin of
// crates/cull/src/partition.rs: a stable counting sort of the non-empty bounds by subregion
// (bound.wgsl prepended). The VPLs are split into params.chunks runs of params.chunk; one
// 256-thread workgroup per (subregion s, run c) walks its run in VPL order and compacts
// subregion s's bounds with a workgroup prefix sum, so each subregion's indices ascend, like
// the CPU's. params.mode 0 (count): counts[s chunks + c] = the run's bounds of s; mode 1
// (write), after scan.wgsl turned the counts (s-major) into offsets: order[counts[s chunks +
// c] ..] = their VPL indices, and sub_offsets[s] = counts[s chunks] (the first run of each
// subregion; sub_offsets[K^2] = the scan's total). Bounds that overflowed f32 are recorded in
// status[1] (GpuCullStatus).

struct PartitionParams {
    vpl_count: u32,
    subregions: u32,
    mode: u32,
    chunks: u32,
    chunk: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> params: PartitionParams;
@group(0) @binding(1) var<storage, read> bounds: array<Bound>;
// subregions * chunks + 1 u32: the counts, then (after the scan) the offsets and the total.
@group(0) @binding(2) var<storage, read_write> counts: array<u32>;
@group(0) @binding(3) var<storage, read_write> order: array<u32>;
@group(0) @binding(4) var<storage, read_write> status: array<atomic<u32>, 4>;
// subregions + 1 u32: where each subregion's VPLs start in order, and the total.
@group(0) @binding(5) var<storage, read_write> sub_offsets: array<u32>;

const MODE_WRITE: u32 = 1u;
const GROUP: u32 = 256u;

var<workgroup> scan: array<u32, 256>;
var<workgroup> written: u32;

@compute @workgroup_size(256)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let w = wid.y * groups.x + wid.x;
    if w >= params.subregions * params.chunks {
        return;
    }
    let s = w / params.chunks;
    let c = w % params.chunks;
    let write = params.mode == MODE_WRITE;
    if lid == 0u {
        written = 0u;
    }
    var start = 0u;
    if write {
        start = counts[w];
        if lid == 0u && c == 0u {
            sub_offsets[s] = start;
            if s == 0u {
                sub_offsets[params.subregions] = counts[params.subregions * params.chunks];
            }
        }
    }
    let first = c * params.chunk;
    let end = min(first + params.chunk, params.vpl_count);
    for (var base = first; base < end; base += GROUP) {
        let i = base + lid;
        var mine = 0u;
        if i < end {
            let b = bounds[i];
            if b.kind == BOUND_OVERFLOW {
                if s == 0u {
                    atomicMin(&status[1], i);
                }
            } else if b.kind != BOUND_EMPTY && b.subregion == s {
                mine = 1u;
            }
        }
        scan[lid] = mine;
        for (var d = 1u; d < GROUP; d <<= 1u) {
            workgroupBarrier();
            var v = scan[lid];
            if lid >= d {
                v += scan[lid - d];
            }
            workgroupBarrier();
            scan[lid] = v;
        }
        let n = workgroupUniformLoad(&written);
        if write && mine != 0u {
            order[start + n + scan[lid] - 1u] = i;
        }
        workgroupBarrier();
        if lid == 0u {
            written = n + scan[GROUP - 1u];
        }
    }
    let total = workgroupUniformLoad(&written);
    if !write && lid == 0u {
        counts[w] = total;
    }
}
