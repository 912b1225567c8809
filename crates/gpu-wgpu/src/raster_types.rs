//! `#[repr(C)]` twins of the WGSL structs of the rasterized passes (scene upload, G-buffer,
//! RSM, VPL generation, direct light). Each names the WGSL file whose struct of the same
//! name must keep the same fields in the same order; a compile-time check holds its size,
//! and `tests::sizes_match_the_wgsl_twins` compares it with the layout naga computes. As in
//! `gpu_types`, only 4-byte scalars and 4-vectors are used, never vec3.
use bytemuck::{Pod, Zeroable};

/// No texture (`GpuMaterial::info[1]`, `info[2]`): the lookup gives 1, as
/// `Material::brdf_at` does for an absent or unknown texture.
pub const NO_TEXTURE: u32 = u32::MAX;
/// `GpuMaterial::info[0]`: `MaterialModel::Direct` or `MaterialModel::MetallicRoughness`.
pub const MATERIAL_DIRECT: u32 = 0;
pub const MATERIAL_METALLIC_ROUGHNESS: u32 = 1;
/// `GpuMaterial::info[3]` bits: two-sided, a dielectric Fresnel (`Material::eta`), an alpha
/// mask (`Material::alpha_mask`).
pub const MATERIAL_DOUBLE_SIDED: u32 = 1;
pub const MATERIAL_DIELECTRIC: u32 = 2;
pub const MATERIAL_ALPHA_MASK: u32 = 4;
/// `GpuTriangle::info[0]` bits: the mesh has per-vertex normals, texture coordinates,
/// tangents.
pub const TRIANGLE_NORMALS: u32 = 1;
pub const TRIANGLE_UVS: u32 = 2;
pub const TRIANGLE_TANGENTS: u32 = 4;

/// One mesh vertex in world space. Keep in sync with `Vertex` in `shaders/scene_types.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuVertex {
    /// Position (xyz) and texture coordinate u (w).
    pub position_u: [f32; 4],
    /// Shading normal (xyz, zero if the mesh has none) and texture coordinate v (w).
    pub normal_v: [f32; 4],
    /// Tangent (xyz) and handedness (w) (`Mesh::tangents`; zero if the mesh has none).
    pub tangent: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuVertex>() == 48);

/// One triangle of the flattened scene. Keep in sync with `Triangle` in
/// `shaders/scene_types.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuTriangle {
    /// Global vertex indices (xyz) and the material index (w).
    pub vertices: [u32; 4],
    /// [`TRIANGLE_NORMALS`] | [`TRIANGLE_UVS`] (x), unused.
    pub info: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuTriangle>() == 32);

/// A material (`slc_core::Material`) as `shaders/scene.wgsl` evaluates it. Keep in sync with
/// `SceneMaterial` in `shaders/scene_types.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// kd (direct) or the base colour (metallic-roughness), xyz.
    pub color: [f32; 4],
    /// F0 (xyz) and α (w) of a direct material.
    pub f0_alpha: [f32; 4],
    /// Metallic, roughness, η (dielectric), unused.
    pub params: [f32; 4],
    /// Model, colour texture, metallic-roughness texture ([`NO_TEXTURE`]: none), flags
    /// ([`MATERIAL_DOUBLE_SIDED`] | [`MATERIAL_DIELECTRIC`] | [`MATERIAL_ALPHA_MASK`]).
    pub info: [u32; 4],
    /// Normal-map texture, alpha-mask texture ([`NO_TEXTURE`]: none), unused, unused.
    pub maps: [u32; 4],
    /// Normal-map scale, alpha cutoff, alpha factor, unused.
    pub map_params: [f32; 4],
    /// `KHR_materials_anisotropy`: strength (0: isotropic), cos and sin of the rotation,
    /// unused (`slc_core::MaterialAnisotropy`).
    pub anisotropy: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuMaterial>() == 112);

/// Where a texture's RGB texels start in the texel array (in floats) and its size. Keep in
/// sync with `TextureInfo` in `shaders/scene_types.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuTextureInfo {
    pub offset: u32,
    pub width: u32,
    pub height: u32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuTextureInfo>() == 16);

/// The projection the visibility pass rasterizes with: a pinhole (camera, RSM face) or an
/// orthographic view (directional light). A point p maps to x = (p − o)·right / extent_x,
/// y = (p − o)·up / extent_y at unit depth z = (p − o)·forward. Keep in sync with
/// `RasterView` in `shaders/visibility.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuRasterView {
    /// Eye, light or orthographic plane origin o (xyz).
    pub origin: [f32; 4],
    /// Right axis (xyz) and 1 / extent_x (w).
    pub right: [f32; 4],
    /// Up axis (xyz) and 1 / extent_y (w).
    pub up: [f32; 4],
    /// Forward axis (xyz) and the near plane (pinhole) or 1 / depth range (orthographic).
    pub forward: [f32; 4],
    /// NDC shift of the sub-pixel offset (xy), 1 for orthographic (z), unused.
    pub shift: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuRasterView>() == 80);

/// The camera rays of the G-buffer resolve (`slc_core::Camera::ray_direction`). Keep in sync
/// with `GbufferParams` in `shaders/gbuffer.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuGbufferParams {
    pub position: [f32; 4],
    pub forward: [f32; 4],
    pub right: [f32; 4],
    pub up: [f32; 4],
    /// (W / H, tan(yfov / 2), s, t) with (s, t) the sub-pixel offset.
    pub frame: [f32; 4],
    pub width: u32,
    pub height: u32,
    pub pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuGbufferParams>() == 96);

/// `GpuRsmParams::info[0]`: how a face's texels get their flux.
pub const RSM_POINT: u32 = 0;
pub const RSM_SPOT: u32 = 1;
pub const RSM_DIRECTIONAL: u32 = 2;

/// One face of a reflective shadow map (`slc_cpu_ref::rsm`'s `Face` with its light) for the
/// RSM resolve. Keep in sync with `RsmParams` in `shaders/rsm.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuRsmParams {
    /// Light position or orthographic plane origin (xyz), face extent e (w).
    pub origin: [f32; 4],
    /// Face axes (xyz); w: texel size 2 / n (forward), unused (right, up).
    pub forward: [f32; 4],
    pub right: [f32; 4],
    pub up: [f32; 4],
    /// Radiant intensity (point, spot) or the flux of every texel (directional), rgb.
    pub light: [f32; 4],
    /// Spot axis (xyz) and `SpotCone::h_outer` (w).
    pub spot: [f32; 4],
    /// [`RSM_POINT`], [`RSM_SPOT`] or [`RSM_DIRECTIONAL`]; resolution n; first texel of the
    /// face; unused.
    pub info: [u32; 4],
    /// `SpotCone::h_width` of the spot falloff (x), unused.
    pub falloff: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuRsmParams>() == 128);

/// What one RSM texel saw (`slc_cpu_ref::rsm::RsmTexel`, or nothing). Keep in sync with
/// `RsmTexel` in `shaders/rsm_texel.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuRsmTexel {
    /// Position (xyz), 1 where the texel holds a photon, 0 where not (w).
    pub position: [f32; 4],
    /// Unit shading normal (xyz) and GGX α (w).
    pub normal_alpha: [f32; 4],
    /// ωi towards the light (xyz) and η of a dielectric Fresnel (w).
    pub omega_i_eta: [f32; 4],
    /// Flux Φ (rgb).
    pub flux: [f32; 4],
    pub kd: [f32; 4],
    pub f0: [f32; 4],
    /// Fresnel model (`gpu_types::FRESNEL_SCHLICK`, `FRESNEL_DIELECTRIC`), unused.
    pub info: [u32; 4],
    /// Unit geometric normal on the lit side (xyz), 1 where a normal map perturbed the
    /// shading normal, 0 where not (w) (`slc_cpu_ref::rsm::RsmTexel::normal_mapped`).
    pub geometric: [f32; 4],
    /// The BRDF's anisotropy: tangent (xyz), α_t (w), zero where isotropic
    /// (`gpu_types::gpu_anisotropy`).
    pub anisotropy: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuRsmTexel>() == 144);

/// The nearest surface along one shadow-map texel's ray, whichever side it faces (the RSM's
/// depth kept as a shadow map). Keep in sync with `ShadowTexel` in `shaders/rsm.wgsl` and
/// `shaders/direct.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuShadowTexel {
    /// Hit position (xyz), 1 for a hit, 0 for none (w).
    pub position: [f32; 4],
    /// The hit triangle's unit geometric normal (xyz).
    pub normal: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuShadowTexel>() == 32);

/// Parameters of VPL generation. Keep in sync with `VplGenParams` in `shaders/vpl_gen.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuVplGenParams {
    /// Texels of this map.
    pub texel_count: u32,
    /// Texels of the maps before it (VPL ids 2 (base + k), 2 (base + k) + 1).
    pub base: u32,
    /// Seed of ξ (`rng::vpl_xi`).
    pub seed: u32,
    /// Bit 0: diffuse VPLs wanted, bit 1: glossy.
    pub lobes: u32,
    /// `gpu_types::CULL_COUNT` or `CULL_WRITE`.
    pub mode: u32,
    /// `cos_theta_h_max(1, 0)` of `Fresnel::max_over_half_vectors(1, 0)`.
    pub cos_h_max: f32,
    pub pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuVplGenParams>() == 32);

/// `GpuDirectParams::info[0]`: the light's kind.
pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_SPOT: u32 = 1;
pub const LIGHT_DIRECTIONAL: u32 = 2;

/// One light and its shadow map for the direct-light pass. Keep in sync with `DirectParams`
/// in `shaders/direct.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuDirectParams {
    /// Light position (point, spot) or travel direction (directional), xyz.
    pub light: [f32; 4],
    /// Spot axis (xyz) and `SpotCone::h_outer` (w).
    pub spot: [f32; 4],
    /// Intensity or irradiance (rgb) and `SpotCone::h_width` (w).
    pub radiometry: [f32; 4],
    /// Shadow-map origin (xyz) and face extent (w).
    pub origin: [f32; 4],
    /// Forward, right and up of each face (at most six).
    pub axes: [[f32; 4]; 18],
    /// Kind ([`LIGHT_POINT`], [`LIGHT_SPOT`], [`LIGHT_DIRECTIONAL`]), faces, resolution,
    /// pixel count.
    pub info: [u32; 4],
    /// Absolute shadow bias (x), relative shadow bias (y), 1 for an orthographic map (z).
    pub shadow: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuDirectParams>() == 384);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu_types::wgsl_size;

    /// Every Rust struct has the size of its WGSL twin as the shader compiler lays it out.
    #[test]
    fn sizes_match_the_wgsl_twins() {
        use std::mem::size_of;
        let gbuffer = crate::gbuffer_pass::SOURCE;
        let rsm = crate::rsm_pass::SOURCE;
        let vpl_gen = crate::vpl_gen_pass::SOURCE;
        let direct = crate::direct_pass::SOURCE;
        let cases = [
            (gbuffer, "Vertex", size_of::<GpuVertex>()),
            (gbuffer, "Triangle", size_of::<GpuTriangle>()),
            (gbuffer, "SceneMaterial", size_of::<GpuMaterial>()),
            (gbuffer, "TextureInfo", size_of::<GpuTextureInfo>()),
            (gbuffer, "GbufferParams", size_of::<GpuGbufferParams>()),
            (gbuffer, "Sample", size_of::<crate::gpu_types::GpuSample>()),
            (
                crate::visibility_pass::SOURCE,
                "RasterView",
                size_of::<GpuRasterView>(),
            ),
            (rsm, "RsmParams", size_of::<GpuRsmParams>()),
            (rsm, "RsmTexel", size_of::<GpuRsmTexel>()),
            (rsm, "ShadowTexel", size_of::<GpuShadowTexel>()),
            (vpl_gen, "RsmTexel", size_of::<GpuRsmTexel>()),
            (vpl_gen, "VplGenParams", size_of::<GpuVplGenParams>()),
            (vpl_gen, "Vpl", size_of::<crate::gpu_types::GpuVpl>()),
            (direct, "DirectParams", size_of::<GpuDirectParams>()),
            (direct, "ShadowTexel", size_of::<GpuShadowTexel>()),
            (direct, "Sample", size_of::<crate::gpu_types::GpuSample>()),
        ];
        for (source, name, size) in cases {
            assert_eq!(wgsl_size(source, name), size, "{name}");
        }
    }
}
