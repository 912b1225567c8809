// Clustered shading by rasterizing bounding meshes [OP16]: the "fill" pass after
// cluster_shell.wgsl. One thread per VPL slot and tile of its subregion: the VPL joins the
// linked list of every occupied slice (clusters.wgsl info.x) from the nearest to the farthest
// slice its mesh reached in the tile, the volume between its front and back surface. Nodes
// (VPL, next) are taken from one counter (status[2], GpuCullStatus.total); past the node
// buffer's capacity they are only counted, and the host refills with a larger buffer.
// bound_mesh.wgsl, bound.wgsl and clusters.wgsl are prepended.

@group(0) @binding(0) var<uniform> params: RasterParams;
@group(0) @binding(1) var<storage, read> cells: array<u32>;
@group(0) @binding(2) var<storage, read> order: array<u32>;
@group(0) @binding(3) var<storage, read> bounds: array<Bound>;
@group(0) @binding(4) var<storage, read> frusta: array<ClusterFrusta>;
// Each cluster's first node (32 t + slice; END: none).
@group(0) @binding(5) var<storage, read_write> heads: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> nodes: array<vec2<u32>>;
@group(0) @binding(7) var<storage, read_write> status: array<atomic<u32>, 4>;

@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let g = (wid.y * groups.x + wid.x) * 64u + lid;
    let per_sub = params.tiles_x * params.tiles_y;
    if g >= params.vpl_count * per_sub {
        return;
    }
    let m = cells[g];
    if m == 0u {
        return;
    }
    let i = order[g / per_sub];
    let t = bounds[i].subregion * per_sub + g % per_sub;
    let lo = firstTrailingBit(m);
    let hi = firstLeadingBit(m);
    var bits = ((0xffffffffu >> (31u - hi)) >> lo) << lo;
    bits &= frusta[t].info.x;
    while bits != 0u {
        let slice = firstTrailingBit(bits);
        bits &= bits - 1u;
        let n = atomicAdd(&status[2], 1u);
        if n == 0xffffffffu {
            // The count wraps: GpuCullStatus.total_overflow.
            atomicStore(&status[3], 1u);
        }
        if n < params.capacity {
            nodes[n] = vec2<u32>(i, atomicExchange(&heads[SLICES * t + slice], n));
        }
    }
}
