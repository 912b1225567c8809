// Clusters of exponential depth slices (clustered shading, Olsson et al. 2012; the paper's
// section-7 comparison), shared by cluster_depth.wgsl and clustered_cull.wgsl (after
// tiles.wgsl). Mirrors GpuClusterFrusta in src/cull_types.rs.

// Depth slices per tile (crates/cull/src/depth.rs MAX_CLUSTERS).
const SLICES: u32 = 32u;

// One tile's cluster frusta: the tile's rectangle (u0, v0, u1, v1) at unit depth; info.x the
// mask of occupied slices (bit s: slice s holds a sample); ranges[s] the depth range [z0, z1]
// of slice s's samples. All grown by the frustum slack (frusta.rs set).
struct ClusterFrusta {
    rect: vec4<f32>,
    info: vec4<u32>,
    ranges: array<vec2<f32>, 32>,
}
