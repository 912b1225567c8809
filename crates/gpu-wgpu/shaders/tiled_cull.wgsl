// Tiled light culling with Modified HalfZ (paper sections 5.1-5.2, supplemental Listing 2),
// the GPU twin of crates/cull/src/tiled.rs + frusta.rs: one 256-thread workgroup per tile
// (tiles.wgsl, bound.wgsl and frustum_tests.wgsl prepended). Every bound of the tile's
// subregion (in the order partition.wgsl made: ascending VPL index, empty bounds left out)
// is tested against the whole tile's frustum box, then against each cluster's: spheres against the
// view-space box of the frustum, ellipsoids as the unit ball at BS c against the box of the
// frustum's image under BS. Hits are compacted in VPL order by a workgroup prefix sum into
// light lists in workgroup memory, which are flushed to the output when nearly full and at
// the end, so every list is ascending in the VPL index, like the CPU's.
// params.mode 0 (count): offsets[2 t + c] = entries of cluster c; mode 1 (write): the lists
// at the exclusive offsets scan.wgsl made of those counts, entries beyond the end of `lists`
// dropped (the buffer is sized from earlier frames; the host culls again when the scan's
// total exceeds it: src/list_room.rs).

@group(0) @binding(0) var<uniform> params: CullParams;
@group(0) @binding(1) var<storage, read> frusta: array<TileFrusta>;
@group(0) @binding(2) var<storage, read> bounds: array<Bound>;
@group(0) @binding(3) var<storage, read_write> offsets: array<u32>;
@group(0) @binding(4) var<storage, read_write> lists: array<u32>;
// The subregions' VPLs (partition.wgsl), ascending, empty bounds left out: the tile's are
// order[info.y .. info.z] of its frusta.
@group(0) @binding(5) var<storage, read> order: array<u32>;

const MODE_WRITE: u32 = 1u;
const GROUP: u32 = 256u;
// Entries per cluster list held in workgroup memory (2 x 4 KiB).
const CAPACITY: u32 = 1024u;

var<workgroup> scan: array<vec2<u32>, 256>;
var<workgroup> staged: array<array<u32, 1024>, 2>;
// Entries staged and already flushed, per cluster.
var<workgroup> staged_count: vec2<u32>;
var<workgroup> flushed_count: vec2<u32>;
var<workgroup> tile_mask: u32;
var<workgroup> sub_range: vec2<u32>;

// Copies the staged lists to the output after what was flushed before.
fn flush(t: u32, lid: u32) {
    let n = staged_count;
    let done = flushed_count;
    let end = arrayLength(&lists);
    let near = offsets[2u * t] + done.x;
    let far = offsets[2u * t + 1u] + done.y;
    for (var j = lid; j < n.x && near + j < end; j += GROUP) {
        lists[near + j] = staged[0][j];
    }
    for (var j = lid; j < n.y && far + j < end; j += GROUP) {
        lists[far + j] = staged[1][j];
    }
    workgroupBarrier();
    if lid == 0u {
        flushed_count = done + n;
        staged_count = vec2<u32>(0u);
    }
    workgroupBarrier();
}

@compute @workgroup_size(256)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let t = wid.y * groups.x + wid.x;
    if t >= params.tile_count {
        return;
    }
    let write = params.mode == MODE_WRITE;
    if lid == 0u {
        staged_count = vec2<u32>(0u);
        flushed_count = vec2<u32>(0u);
        tile_mask = frusta[t].info.x;
        sub_range = frusta[t].info.yz;
    }
    let mask = workgroupUniformLoad(&tile_mask);
    let range = workgroupUniformLoad(&sub_range);
    if mask == 0u {
        if !write && lid == 0u {
            offsets[2u * t] = 0u;
            offsets[2u * t + 1u] = 0u;
        }
        return;
    }
    let f = frusta[t];
    for (var base = range.x; base < range.y; base += GROUP) {
        let j = base + lid;
        var i = 0u;
        var hit = vec2<u32>(0u);
        if j < range.y {
            i = order[j];
            hit = tile_hits(bounds[i], f, mask);
        }
        // Inclusive prefix sum of the hits (Hillis-Steele).
        scan[lid] = hit;
        for (var d = 1u; d < GROUP; d <<= 1u) {
            workgroupBarrier();
            var v = scan[lid];
            if lid >= d {
                v += scan[lid - d];
            }
            workgroupBarrier();
            scan[lid] = v;
        }
        workgroupBarrier();
        let total = scan[GROUP - 1u];
        let before = scan[lid] - hit;
        if write {
            let at = staged_count + before;
            if hit.x != 0u {
                staged[0][at.x] = i;
            }
            if hit.y != 0u {
                staged[1][at.y] = i;
            }
        }
        workgroupBarrier();
        if lid == 0u {
            staged_count += total;
        }
        let n = workgroupUniformLoad(&staged_count);
        if write && max(n.x, n.y) + GROUP > CAPACITY {
            flush(t, lid);
        }
    }
    if write {
        flush(t, lid);
    } else if lid == 0u {
        offsets[2u * t] = staged_count.x;
        offsets[2u * t + 1u] = staged_count.y;
    }
}
