//! `#[repr(C)]` twins of the WGSL structs of the rasterized G-buffer: the scene upload, the visibility pass and the G-buffer samples every later pass reads. Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars and `[f32; 4]` / `[u32; 4]` are used (WGSL `f32`, `u32`, `vec4<f32>`,
//! `vec4<u32>`), never vec3, so the Rust and WGSL layouts agree without hidden padding.
use crate::vpl::records::vec4;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use slc_bounds::{Anisotropy, Brdf, Fresnel};
use slc_core::GSample;

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
/// One mesh vertex in world space. Keep in sync with `Vertex` in `scene_types.wesl`.
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
/// `scene_types.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuTriangle {
    /// Global vertex indices (xyz) and the material index (w).
    pub vertices: [u32; 4],
    /// [`TRIANGLE_NORMALS`] | [`TRIANGLE_UVS`] (x), unused.
    pub info: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuTriangle>() == 32);
/// A material (`slc_core::Material`) as `scene.wesl` evaluates it. Keep in sync with
/// `SceneMaterial` in `scene_types.wesl`.
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
/// sync with `TextureInfo` in `scene_types.wesl`.
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
/// `RasterView` in `visibility.wesl`.
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
/// with `GbufferParams` in `gbuffer.wesl`.
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
/// `GpuSample::present`: whether the pixel holds a G-buffer sample (0: empty, e.g. sky).
/// `GpuSample::flags`: bit 0 set where the pixel has a sample, bit 1 for a dielectric Fresnel.
pub const SAMPLE_EMPTY: u32 = 0;
pub const SAMPLE_PRESENT: u32 = 1;
pub const SAMPLE_DIELECTRIC: u32 = 2;
/// One G-buffer pixel ([`slc_core::GSample`] or an empty pixel) as the shading pass reads it.
/// Keep in sync with `Sample` in `gsample.wesl` (64 bytes: a 1920 x 1080 G-buffer fits
/// lavapipe's 128 MiB storage binding).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuSample {
    /// Unit shading normal (xyz) and GGX roughness α (w; along the bitangent where
    /// anisotropic).
    pub normal_alpha: [f32; 4],
    /// Unit direction towards the camera ωo (xyz) and an anisotropy's tangent as its angle
    /// around the normal (w; `slc_bounds::Anisotropy::angle`).
    pub omega_o_phi: [f32; 4],
    /// Diffuse reflectance kd (xyz) and an anisotropy's α_t (w; 0 where isotropic).
    pub kd_alpha_t: [f32; 4],
    /// Schlick F0 (xyz), or the relative index η of a dielectric Fresnel (x).
    pub f0_eta: [f32; 3],
    /// [`SAMPLE_PRESENT`] | [`SAMPLE_DIELECTRIC`]; [`SAMPLE_EMPTY`] for an empty pixel.
    pub flags: u32,
}
const _: () = assert!(std::mem::size_of::<GpuSample>() == 64);
impl GpuSample {
    /// An empty pixel: shaded black.
    pub const EMPTY: Self = Self {
        normal_alpha: [0.0; 4],
        omega_o_phi: [0.0; 4],
        kd_alpha_t: [0.0; 4],
        f0_eta: [0.0; 3],
        flags: SAMPLE_EMPTY,
    };

    /// Packs a G-buffer sample (its position goes to the separate positions array,
    /// [`gpu_position`]); `None` (nothing seen) gives [`Self::EMPTY`].
    pub fn new(sample: Option<&GSample>) -> Self {
        let Some(g) = sample else {
            return Self::EMPTY;
        };
        let (flags, f0_eta) = match g.brdf.fresnel {
            Fresnel::Schlick(f0) => (SAMPLE_PRESENT, f0),
            Fresnel::Dielectric(eta) => (SAMPLE_PRESENT | SAMPLE_DIELECTRIC, Vec3::X * eta),
        };
        let (phi, alpha_t) = g
            .brdf
            .anisotropy
            .map_or((0.0, 0.0), |a| (a.angle(g.normal), a.alpha_t));
        Self {
            normal_alpha: vec4(g.normal, g.brdf.alpha),
            omega_o_phi: vec4(g.omega_o, phi),
            kd_alpha_t: vec4(g.brdf.kd, alpha_t),
            f0_eta: f0_eta.to_array(),
            flags,
        }
    }

    /// Whether the pixel has a sample.
    pub fn is_present(&self) -> bool {
        self.flags & SAMPLE_PRESENT != 0
    }

    /// The sample's BRDF (the inverse of [`Self::new`]'s packing, the tangent rebuilt from
    /// its angle).
    pub fn brdf(&self) -> Brdf {
        let normal = Vec3::new(
            self.normal_alpha[0],
            self.normal_alpha[1],
            self.normal_alpha[2],
        );
        Brdf {
            kd: Vec3::new(self.kd_alpha_t[0], self.kd_alpha_t[1], self.kd_alpha_t[2]),
            fresnel: match self.flags & SAMPLE_DIELECTRIC != 0 {
                true => Fresnel::Dielectric(self.f0_eta[0]),
                false => Fresnel::Schlick(Vec3::from_array(self.f0_eta)),
            },
            alpha: self.normal_alpha[3],
            anisotropy: (self.kd_alpha_t[3] > 0.0)
                .then(|| Anisotropy::from_angle(normal, self.omega_o_phi[3], self.kd_alpha_t[3])),
        }
    }
}
/// A G-buffer sample's entry in the positions array every pass reads beside the
/// [`GpuSample`]s: `[x, y, z, 1]`, zero where the pixel has no sample.
pub fn gpu_position(sample: Option<&GSample>) -> [f32; 4] {
    sample.map_or([0.0; 4], |s| s.position.extend(1.0).to_array())
}

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        crate::frame::raster::gbuffer::SOURCE => {
            GpuVertex as "Vertex",
            GpuTriangle as "Triangle",
            GpuMaterial as "SceneMaterial",
            GpuTextureInfo as "TextureInfo",
            GpuGbufferParams as "GbufferParams",
            GpuSample as "Sample",
        }
        crate::frame::raster::visibility::SOURCE => {
            GpuRasterView as "RasterView",
        }
        crate::shade::lists::SOURCE => {
            GpuSample as "Sample",
        }
        crate::frame::light::direct::SOURCE => {
            GpuSample as "Sample",
        }
    }
}
