// The refinement of the tight strategies (docs/tight-bounds.md), the GPU twin of
// crates/cull/src/refine.rs: after a tiled or clustered culling with the spheroid (glossy
// VPLs) or the section-6 sphere (diffuse ones), each tile list is cut per 8 x 8 block of the
// tile, and with `halves` 2 each block's samples of a list once more at their own half depth
// (Modified HalfZ per block). A group of a block keeps a VPL of its base list only where the
// VPL's spheroid meets the view-space box of the group's receivers and its BoxBound
// (box_bound.wgsl) says p > xi may hold in it. One 64-thread workgroup per block (4 per tile,
// linear index wid.y * num_workgroups.x + wid.x), one thread per pixel; tiles.wgsl,
// bound.wgsl, fresnel_ggx.wgsl and box_bound.wgsl are prepended.
// Group g = (4 t + block) * slots + slot with slots = clusters * halves and slot = cluster *
// halves + half. params.mode 0 (count): offsets[g] = entries of group g; mode 1 (write): the
// lists at the exclusive offsets scan.wgsl made of those counts, and each pixel's list; entries beyond the end of `lists`
// are dropped (the buffer is sized from earlier frames; the host culls again when the scan's
// total exceeds it: src/list_room.rs).

struct TightParams {
    clusters: u32,
    halves: u32,
    eye_extent: f32,
    pad: u32,
}

@group(0) @binding(0) var<uniform> params: CullParams;
@group(0) @binding(1) var<uniform> tight: TightParams;
@group(0) @binding(2) var<storage, read> positions: array<vec4<f32>>;
// In: the base strategy's list of each pixel (clusters per tile, NO_LIST without a sample);
// out (write mode): its group's.
@group(0) @binding(3) var<storage, read_write> pixel_list: array<u32>;
@group(0) @binding(4) var<storage, read> base_offsets: array<u32>;
@group(0) @binding(5) var<storage, read> base_indices: array<u32>;
@group(0) @binding(6) var<storage, read> bounds: array<Bound>;
@group(0) @binding(7) var<storage, read> box_bounds: array<BoxBound>;
@group(0) @binding(8) var<storage, read_write> offsets: array<u32>;
@group(0) @binding(9) var<storage, read_write> lists: array<u32>;

const MODE_WRITE: u32 = 1u;
const BLOCK: u32 = 8u;
const GROUP: u32 = 64u;
const MAX_SLOTS: u32 = 32u;
const F32_EPSILON: f32 = 1.1920929e-7;

// Per base cluster: its samples' depth range in the block (order keys).
var<workgroup> z_lo: array<atomic<u32>, 32>;
var<workgroup> z_hi: array<atomic<u32>, 32>;
// Per slot: the box of its samples' view positions (order keys, 3 per slot), the largest
// |coordinate| of their world positions (f32 bits) and their number.
var<workgroup> box_lo: array<atomic<u32>, 96>;
var<workgroup> box_hi: array<atomic<u32>, 96>;
var<workgroup> slot_extent: array<atomic<u32>, 32>;
var<workgroup> slot_count: array<atomic<u32>, 32>;
// Slots holding a sample (bit s), and its copy for workgroupUniformLoad.
var<workgroup> occupied: atomic<u32>;
var<workgroup> occupied_mask: u32;
var<workgroup> range: vec2<u32>;
var<workgroup> written: u32;
// The entries of the round kept (bit e of word e / 32).
var<workgroup> kept: array<atomic<u32>, 2>;

// A u32 whose unsigned order is the order of the finite f32 `f`.
fn order_key(f: f32) -> u32 {
    let u = bitcast<u32>(f);
    return select(u | 0x80000000u, ~u, (u & 0x80000000u) != 0u);
}

fn from_key(k: u32) -> f32 {
    return bitcast<f32>(select(~k, k & 0x7fffffffu, (k & 0x80000000u) != 0u));
}

fn max_abs(v: vec3<f32>) -> f32 {
    let a = abs(v);
    return max(a.x, max(a.y, a.z));
}

// Whether VPL i stays in the list of the box [lo, hi] (centre, half extents, bounding
// radius): a spheroid must meet the box (its image BS centre +- |BS| half in the test space
// of eq. 16-17, frusta.rs Box3::in_test_space), then the box bound must reach it.
fn reaches(i: u32, lo: vec3<f32>, hi: vec3<f32>, center: vec3<f32>, half: vec3<f32>,
           radius: f32) -> bool {
    let b = bounds[i];
    if b.kind == BOUND_ELLIPSOID {
        let bs = mat3x3<f32>(b.bs[0].xyz, b.bs[1].xyz, b.bs[2].xyz);
        let mapped = bs * center;
        let extent = abs(b.bs[0].xyz) * half.x + abs(b.bs[1].xyz) * half.y
            + abs(b.bs[2].xyz) * half.z;
        let gap = max(max(mapped - extent - b.center.xyz, b.center.xyz - mapped - extent),
                      vec3<f32>(0.0));
        if dot(gap, gap) > 1.0 {
            return false;
        }
    }
    return box_may_exceed_xi(box_bounds[i], lo, hi, center, radius);
}

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let w = wid.y * groups.x + wid.x;
    let t = w / 4u;
    let block = w % 4u;
    if t >= params.tile_count {
        return;
    }
    let write = params.mode == MODE_WRITE;
    if lid < MAX_SLOTS {
        atomicStore(&z_lo[lid], 0xffffffffu);
        atomicStore(&z_hi[lid], 0u);
        for (var axis = 0u; axis < 3u; axis++) {
            atomicStore(&box_lo[3u * lid + axis], 0xffffffffu);
            atomicStore(&box_hi[3u * lid + axis], 0u);
        }
        atomicStore(&slot_extent[lid], 0u);
        atomicStore(&slot_count[lid], 0u);
    }
    if lid == 0u {
        atomicStore(&occupied, 0u);
    }
    workgroupBarrier();
    let tile = tile_of(t, params);
    let a = (block % 2u) * BLOCK + lid % BLOCK;
    let b = (block / 2u) * BLOCK + lid / BLOCK;
    let has_pixel = a < tile.cx && b < tile.cy;
    let pixel = (tile.sy + params.k * (tile.fy + b)) * params.width
        + tile.sx + params.k * (tile.fx + a);
    var cluster = NO_LIST;
    var v = vec3<f32>(0.0);
    var extent = 0.0;
    if has_pixel {
        let list = pixel_list[pixel];
        let first = t * tight.clusters;
        if list != NO_LIST && list >= first && list - first < tight.clusters {
            cluster = list - first;
            let x = positions[pixel].xyz;
            let rot = mat3x3<f32>(params.rotation[0].xyz, params.rotation[1].xyz,
                                  params.rotation[2].xyz);
            v = rot * (x - params.eye.xyz);
            extent = max_abs(x);
            atomicMin(&z_lo[cluster], order_key(v.z));
            atomicMax(&z_hi[cluster], order_key(v.z));
        }
    }
    workgroupBarrier();
    var slot = NO_LIST;
    if cluster != NO_LIST {
        slot = cluster * tight.halves;
        let half_z = 0.5 * (from_key(atomicLoad(&z_lo[cluster]))
            + from_key(atomicLoad(&z_hi[cluster])));
        if tight.halves == 2u && !(v.z < half_z) {
            slot += 1u;
        }
        for (var axis = 0u; axis < 3u; axis++) {
            atomicMin(&box_lo[3u * slot + axis], order_key(v[axis]));
            atomicMax(&box_hi[3u * slot + axis], order_key(v[axis]));
        }
        atomicMax(&slot_extent[slot], bitcast<u32>(extent));
        atomicAdd(&slot_count[slot], 1u);
    }
    workgroupBarrier();
    let slots = tight.clusters * tight.halves;
    let first_group = (4u * t + block) * slots;
    // Empty groups get empty lists at once; the workgroup walks the occupied ones.
    if lid < slots {
        if atomicLoad(&slot_count[lid]) != 0u {
            atomicOr(&occupied, 1u << lid);
        } else if !write {
            offsets[first_group + lid] = 0u;
        }
    }
    workgroupBarrier();
    if lid == 0u {
        occupied_mask = atomicLoad(&occupied);
    }
    var remaining = workgroupUniformLoad(&occupied_mask);
    while remaining != 0u {
        let s = firstTrailingBit(remaining);
        remaining &= remaining - 1u;
        let group = first_group + s;
        if lid == 0u {
            let list = t * tight.clusters + s / tight.halves;
            range = vec2<u32>(base_offsets[list], base_offsets[list + 1u]);
            written = 0u;
        }
        let r = workgroupUniformLoad(&range);
        // The box grown for the f32 rounding of R (x - eye) (refine.rs Refiner::receivers).
        let pad = 16.0 * F32_EPSILON
            * (bitcast<f32>(atomicLoad(&slot_extent[s])) + tight.eye_extent);
        let lo = vec3<f32>(from_key(atomicLoad(&box_lo[3u * s])),
                           from_key(atomicLoad(&box_lo[3u * s + 1u])),
                           from_key(atomicLoad(&box_lo[3u * s + 2u]))) - vec3<f32>(pad);
        let hi = vec3<f32>(from_key(atomicLoad(&box_hi[3u * s])),
                           from_key(atomicLoad(&box_hi[3u * s + 1u])),
                           from_key(atomicLoad(&box_hi[3u * s + 2u]))) + vec3<f32>(pad);
        let center = 0.5 * (lo + hi);
        let half = 0.5 * (hi - lo);
        let radius = length(half) * (1.0 + 4.0 * F32_EPSILON);
        for (var base = r.x; base < r.y; base += GROUP) {
            // Each thread tests one entry and sets its bit; an entry's place is the number
            // of kept entries before it, so the lists keep the base list's order, ascending
            // in the VPL index.
            if lid < 2u {
                atomicStore(&kept[lid], 0u);
            }
            workgroupBarrier();
            let j = base + lid;
            var i = 0u;
            var keep = false;
            if j < r.y {
                i = base_indices[j];
                keep = reaches(i, lo, hi, center, half, radius);
            }
            if keep {
                atomicOr(&kept[lid / 32u], 1u << (lid % 32u));
            }
            workgroupBarrier();
            let low = atomicLoad(&kept[0]);
            let high = atomicLoad(&kept[1]);
            if write && keep {
                var before = countOneBits(low & ((1u << lid) - 1u));
                if lid >= 32u {
                    before = countOneBits(low) + countOneBits(high & ((1u << (lid - 32u)) - 1u));
                }
                let at = offsets[group] + written + before;
                if at < arrayLength(&lists) {
                    lists[at] = i;
                }
            }
            workgroupBarrier();
            if lid == 0u {
                written += countOneBits(low) + countOneBits(high);
            }
        }
        if !write && lid == 0u {
            offsets[group] = written;
        }
    }
    if write && has_pixel {
        pixel_list[pixel] = select(NO_LIST, first_group + slot, slot != NO_LIST);
    }
}
