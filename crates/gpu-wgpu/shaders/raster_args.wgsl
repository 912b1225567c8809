// The raster baselines' indirect draws, sized on the GPU (bound_mesh.wgsl prepended): one per
// interleaved subregion s, its VPLs as instances (partition.wgsl's sub_offsets) and
// first_vertex = s * mesh_vertices, so the vertex shader finds s without a per-draw binding
// (first_instance must stay 0 without INDIRECT_FIRST_INSTANCE).

@group(0) @binding(0) var<uniform> params: RasterParams;
@group(0) @binding(1) var<storage, read> sub_offsets: array<u32>;
// wgpu::util::DrawIndirectArgs per subregion.
@group(0) @binding(2) var<storage, read_write> args: array<vec4<u32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = gid.x;
    if s >= params.k * params.k {
        return;
    }
    args[s] = vec4<u32>(params.mesh_vertices, sub_offsets[s + 1u] - sub_offsets[s],
                        s * params.mesh_vertices, 0u);
}
