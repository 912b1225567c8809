// The GGX specular lobe's SG fit (slc_bounds::sg::specular_table, uploaded by
// crates/gpu-wgpu/src/specular_table.rs; its test holds these numbers to the Rust table's):
// per alpha (rows: 0, 1/16, ..., 1) and view (columns: sqrt(1 - cos) = 0, 1/32, ..., 1),
// [mirror weight, lambda alpha^2 (cos + alpha), integral, Fresnel's cosine]. A uniform, so that the
// lookup's dynamic index reads memory (a const array would be copied into every invocation).
const SPECULAR_ALPHA_STEPS: u32 = 17u;
const SPECULAR_VIEW_STEPS: u32 = 33u;
@group(0) @binding(20) var<uniform> specular_table: array<vec4<f32>, 561>;
