//! `#[repr(C)]` twins of the WGSL structs of the reflective shadow maps and the direct light. Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars, `[f32; 4]` / `[u32; 4]` (WGSL `f32`, `u32`, `vec4<f32>`, `vec4<u32>`) and
//! `[f32; 3]` followed by a 4-byte scalar (a WGSL `vec3<f32>`, 16-byte aligned, and the scalar
//! in its last 4 bytes) are used, so the Rust and WGSL layouts agree without hidden padding.
use bytemuck::{Pod, Zeroable};
use slc_core::Light;

/// `GpuRsmParams::info[0]`: how a face's texels get their flux.
pub const RSM_POINT: u32 = 0;
pub const RSM_SPOT: u32 = 1;
pub const RSM_DIRECTIONAL: u32 = 2;
/// One face of a reflective shadow map ([`slc_core::rsm::RsmFace`] with its light) for the
/// RSM resolve. Keep in sync with `RsmParams` in `rsm.wesl`.
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
/// A light's spot cone as the RSM and direct-light kernels read it: the axis with
/// `SpotCone::h_outer` (w), and `SpotCone::h_width`; zero and 1 for lights without a cone.
pub fn gpu_spot(light: &Light) -> ([f32; 4], f32) {
    light.spot_cone().map_or(([0.0; 4], 1.0), |(axis, cone)| {
        (axis.extend(cone.h_outer).to_array(), cone.h_width)
    })
}
/// What one RSM texel saw ([`slc_core::rsm::RsmTexel`], or nothing). Keep in sync with
/// `RsmTexel` in `rsm_texel.wesl`.
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
    pub flux: [f32; 3],
    /// Fresnel model (`vpl::records::FRESNEL_SCHLICK`, `FRESNEL_DIELECTRIC`).
    pub fresnel: u32,
    pub kd: [f32; 4],
    pub f0: [f32; 4],
    /// Unit geometric normal on the lit side (xyz), 1 where a normal map perturbed the
    /// shading normal, 0 where not (w) (`slc_core::rsm::RsmTexel::normal_mapped`).
    pub geometric: [f32; 4],
    /// The BRDF's anisotropy: tangent (xyz), α_t (w), zero where isotropic
    /// (`vpl::records::gpu_anisotropy`).
    pub anisotropy: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuRsmTexel>() == 128);
/// The nearest surface along one shadow-map texel's ray, whichever side it faces (the RSM's
/// depth kept as a shadow map). Keep in sync with `ShadowTexel` in `rsm.wesl` and
/// `direct.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuShadowTexel {
    /// Hit position (xyz), 1 for a hit, 0 for none (w).
    pub position: [f32; 4],
    /// The hit triangle's unit geometric normal (xyz).
    pub normal: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuShadowTexel>() == 32);
/// `GpuDirectParams::info[0]`: the light's kind.
pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_SPOT: u32 = 1;
pub const LIGHT_DIRECTIONAL: u32 = 2;
/// One light and its shadow map for the direct-light pass. Keep in sync with `DirectParams`
/// in `direct.wesl`.
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

    wgsl_twins! {
        crate::frame::light::rsm::SOURCE => {
            GpuRsmParams as "RsmParams",
            GpuRsmTexel as "RsmTexel",
            GpuShadowTexel as "ShadowTexel",
        }
        crate::vpl::generate::SOURCE => {
            GpuRsmTexel as "RsmTexel",
        }
        crate::frame::light::direct::SOURCE => {
            GpuDirectParams as "DirectParams",
            GpuShadowTexel as "ShadowTexel",
        }
    }
}
