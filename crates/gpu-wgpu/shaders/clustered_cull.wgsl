// Clustered light culling, the GPU twin of crates/cull/src/tiled.rs (Worker::cull_tile with
// Clustering::ExponentialSlices) + frusta.rs: one 256-thread workgroup per tile (tiles.wgsl,
// clusters.wgsl, bound.wgsl and frustum_tests.wgsl prepended). Every bound of the tile's
// subregion (in the order partition.wgsl made: ascending VPL index, empty bounds left out)
// is tested against the whole tile's frustum box (its nearest to its farthest occupied
// slice), then, if more than one slice is occupied, against each occupied slice's: spheres
// against the view-space box, ellipsoids as the unit ball at BS c against the box of the
// frustum's image under BS (frustum_tests.wgsl).
//
// The bounds go in chunks of 256, one per thread, each thread's hits a 32-bit slice mask.
// Lists are compacted in VPL order: the 8 threads of slice s (s = lid / 8) count slice s's
// hits in 8 runs of 32 masks each, and each writes its run's hits after the hits of the runs
// before it and of the chunks before, so every list ascends in the VPL index, like the CPU's.
// params.mode 0 (count): offsets[32 t + s] = entries of slice s; mode 1 (write): the lists at
// the exclusive offsets scan.wgsl made of those counts; entries beyond the end of `lists`
// are dropped (the buffer is sized from earlier frames; the host culls again when the scan's
// total exceeds it: src/list_room.rs).

@group(0) @binding(0) var<uniform> params: CullParams;
@group(0) @binding(1) var<storage, read> frusta: array<ClusterFrusta>;
@group(0) @binding(2) var<storage, read> bounds: array<Bound>;
@group(0) @binding(3) var<storage, read_write> offsets: array<u32>;
@group(0) @binding(4) var<storage, read_write> lists: array<u32>;
// The subregions' VPLs (partition.wgsl): subregion s holds order[sub_offsets[s] ..
// sub_offsets[s + 1]], ascending, empty bounds left out.
@group(0) @binding(5) var<storage, read> sub_offsets: array<u32>;
@group(0) @binding(6) var<storage, read> order: array<u32>;

const MODE_WRITE: u32 = 1u;
const GROUP: u32 = 256u;
// Threads per slice, and masks each of them walks (RUNS x RUN = GROUP).
const RUNS: u32 = 8u;
const RUN: u32 = 32u;

var<workgroup> tile: ClusterFrusta;
var<workgroup> tile_mask: u32;
var<workgroup> sub_range: vec2<u32>;
var<workgroup> masks: array<u32, 256>;
var<workgroup> ids: array<u32, 256>;
// Hits of slice s in run j: runs[s * RUNS + j].
var<workgroup> runs: array<u32, 256>;
// Entries of each slice's list so far.
var<workgroup> written: array<u32, 32>;

// The slices (bit mask) the bound may touch: the whole tile first, then each occupied slice
// (frusta.rs sphere_hits and ellipsoid_hits).
fn hits(b: Bound, occupied: u32) -> u32 {
    var test: BoundBox;
    if !bound_box(b, tile.rect, &test) {
        return 0u;
    }
    let whole = vec2<f32>(tile.ranges[firstTrailingBit(occupied)].x,
                          tile.ranges[firstLeadingBit(occupied)].y);
    if !box_meets(test, whole) {
        return 0u;
    }
    if countOneBits(occupied) == 1u {
        return occupied;
    }
    var out = 0u;
    var rest = occupied;
    while rest != 0u {
        let s = firstTrailingBit(rest);
        if box_meets(test, tile.ranges[s]) {
            out |= 1u << s;
        }
        rest &= rest - 1u;
    }
    return out;
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
        tile = frusta[t];
        tile_mask = tile.info.x;
        let s = t / (params.tiles_x * params.tiles_y);
        sub_range = vec2<u32>(sub_offsets[s], sub_offsets[s + 1u]);
    }
    if lid < SLICES {
        written[lid] = 0u;
    }
    let occupied = workgroupUniformLoad(&tile_mask);
    let range = workgroupUniformLoad(&sub_range);
    // The 8 threads of slice `slice` count and write its hits; thread `run` of them walks
    // masks[run * 32 ..][..32].
    let slice = lid / RUNS;
    let run = lid % RUNS;
    for (var base = range.x; occupied != 0u && base < range.y; base += GROUP) {
        let j = base + lid;
        var mask = 0u;
        var id = 0u;
        if j < range.y {
            id = order[j];
            mask = hits(bounds[id], occupied);
        }
        masks[lid] = mask;
        ids[lid] = id;
        workgroupBarrier();
        var n = 0u;
        for (var i = 0u; i < RUN; i++) {
            n += (masks[run * RUN + i] >> slice) & 1u;
        }
        runs[lid] = n;
        workgroupBarrier();
        var before = written[slice];
        var total = 0u;
        for (var r = 0u; r < RUNS; r++) {
            let m = runs[slice * RUNS + r];
            if r < run {
                before += m;
            }
            total += m;
        }
        if write && n != 0u {
            var at = offsets[SLICES * t + slice] + before;
            for (var i = 0u; i < RUN; i++) {
                let k = run * RUN + i;
                if ((masks[k] >> slice) & 1u) != 0u {
                    if at < arrayLength(&lists) {
                        lists[at] = ids[k];
                    }
                    at += 1u;
                }
            }
        }
        workgroupBarrier();
        if run == 0u {
            written[slice] += total;
        }
    }
    workgroupBarrier();
    if !write && lid < SLICES {
        offsets[SLICES * t + lid] = written[lid];
    }
}
