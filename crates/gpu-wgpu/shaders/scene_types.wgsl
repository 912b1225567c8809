// The flattened scene of src/scene_upload.rs (structs mirror src/raster_types.rs): every
// mesh's vertices in one array, triangles with global vertex indices and their material,
// materials, and textures as RGB float triples in one texel array. Prepended to
// scene.wgsl.

struct Vertex {
    // position (xyz), texture coordinate u (w)
    position_u: vec4<f32>,
    // shading normal (xyz, zero without normals), texture coordinate v (w)
    normal_v: vec4<f32>,
    // tangent (xyz) and handedness (w), zero without tangents
    tangent: vec4<f32>,
}

struct Triangle {
    // global vertex indices (xyz), material (w)
    vertices: vec4<u32>,
    // x: TRIANGLE_NORMALS | TRIANGLE_UVS | TRIANGLE_TANGENTS
    info: vec4<u32>,
}

struct SceneMaterial {
    // kd (direct) or base colour (metallic-roughness)
    color: vec4<f32>,
    // F0 (xyz), alpha (w) of a direct material
    f0_alpha: vec4<f32>,
    // metallic, roughness, eta, unused
    params: vec4<f32>,
    // model, colour texture, metallic-roughness texture, flags
    info: vec4<u32>,
    // normal-map texture, alpha-mask texture, unused, unused
    maps: vec4<u32>,
    // normal-map scale, alpha cutoff, alpha factor, unused
    map_params: vec4<f32>,
    // KHR_materials_anisotropy: strength (0: isotropic), cos and sin of the rotation, unused
    anisotropy: vec4<f32>,
}

struct TextureInfo {
    // first float of the texture's texels
    offset: u32,
    width: u32,
    height: u32,
    pad: u32,
}

const TRIANGLE_NORMALS: u32 = 1u;
const TRIANGLE_UVS: u32 = 2u;
const TRIANGLE_TANGENTS: u32 = 4u;
const NO_TEXTURE: u32 = 0xffffffffu;
const MATERIAL_DIRECT: u32 = 0u;
const MATERIAL_DOUBLE_SIDED: u32 = 1u;
const MATERIAL_DIELECTRIC: u32 = 2u;
const MATERIAL_ALPHA_MASK: u32 = 4u;
const ALPHA_MIN: f32 = 1e-3;
const F32_MAX: f32 = 3.40282347e38;
