// One VPL's bound in the culling view, written by bounds.wgsl and read by tiled_cull.wgsl
// (prepended to both). Mirrors GpuBound in src/gpu_types.rs.
// - BOUND_SPHERE: center = view-space centre (xyz), squared radius (w);
// - BOUND_ELLIPSOID: bs = columns of BS (eq. 16-17), center = BS c (xyz): the ellipsoid is
//   the unit ball around BS c in that space;
// - BOUND_EMPTY: nothing reflected, never listed; BOUND_OVERFLOW: does not fit in f32.
struct Bound {
    bs: array<vec4<f32>, 3>,
    center: vec4<f32>,
    kind: u32,
    index: u32,
    subregion: u32,
    pad: u32,
}

const BOUND_EMPTY: u32 = 0u;
const BOUND_SPHERE: u32 = 1u;
const BOUND_ELLIPSOID: u32 = 2u;
const BOUND_OVERFLOW: u32 = 3u;
