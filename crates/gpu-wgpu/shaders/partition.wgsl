// The VPLs of each interleaved subregion (paper section 6, Fig. 8), the GPU twin of
// crates/cull/src/partition.rs: a stable counting sort of the non-empty bounds by subregion
// (bound.wgsl prepended). One 256-thread workgroup per subregion walks the bounds in VPL
// order and compacts its own with a workgroup prefix sum, so each subregion's indices
// ascend, like the CPU's. params.mode 0 (count): sub_offsets[s] = number of bounds; mode 1
// (write): order[sub_offsets[s] ..] = their VPL indices, after scan.wgsl turned the counts
// into offsets. Bounds that overflowed f32 are recorded in status[1] (GpuCullStatus).

struct PartitionParams {
    vpl_count: u32,
    subregions: u32,
    mode: u32,
    pad: u32,
}

@group(0) @binding(0) var<uniform> params: PartitionParams;
@group(0) @binding(1) var<storage, read> bounds: array<Bound>;
@group(0) @binding(2) var<storage, read_write> sub_offsets: array<u32>;
@group(0) @binding(3) var<storage, read_write> order: array<u32>;
@group(0) @binding(4) var<storage, read_write> status: array<atomic<u32>, 4>;

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
    let s = wid.y * groups.x + wid.x;
    if s >= params.subregions {
        return;
    }
    let write = params.mode == MODE_WRITE;
    if lid == 0u {
        written = 0u;
    }
    var start = 0u;
    if write {
        start = sub_offsets[s];
    }
    for (var base = 0u; base < params.vpl_count; base += GROUP) {
        let i = base + lid;
        var mine = 0u;
        if i < params.vpl_count {
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
        sub_offsets[s] = total;
    }
}
