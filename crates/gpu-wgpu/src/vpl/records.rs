//! `#[repr(C)]` twins of the WGSL structs of the RNG check, VPL generation and every pass that reads VPLs. Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars, `[f32; 4]` / `[u32; 4]` (WGSL `f32`, `u32`, `vec4<f32>`, `vec4<u32>`) and
//! `[f32; 3]` followed by a 4-byte scalar (a WGSL `vec3<f32>`, 16-byte aligned, and the scalar
//! in its last 4 bytes) are used, so the Rust and WGSL layouts agree without hidden padding.
use crate::device::GpuError;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use slc_bounds::shading_normal::flux_scale;
use slc_bounds::{Anisotropy, Fresnel, StochasticParams};
use slc_core::{Vpl, VplLobe};

/// Parameters of the RNG conformance pass. Keep in sync with `RngParams` in
/// `rng_eval.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct RngParams {
    pub seed: u32,
    pub stream: u32,
    pub counter: u32,
    /// Interleaving factor K (K x K subregions).
    pub k: u32,
    pub count: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<RngParams>() == 32);
/// What the RNG pass writes per index i. Keep in sync with `RngSample` in
/// `rng_eval.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct RngSample {
    /// `pcg_hash(i ^ seed)`.
    pub pcg: u32,
    /// `hash4(seed, i, stream, counter)`.
    pub hash: u32,
    /// The bits of `uniform(seed, i, stream, counter)`.
    pub uniform_bits: u32,
    /// `Interleaving { k, seed }.vpl_subregion(i)`.
    pub subregion: u32,
}
const _: () = assert!(std::mem::size_of::<RngSample>() == 16);
/// `GpuVpl::lobe`: the VPL's lobe.
pub const LOBE_DIFFUSE: u32 = 0;
pub const LOBE_GLOSSY: u32 = 1;
/// `GpuVpl::fresnel`: the Fresnel model of eq. (6) (supplemental eq. 1 or 3-5).
pub const FRESNEL_SCHLICK: u32 = 0;
pub const FRESNEL_DIELECTRIC: u32 = 1;
/// A VPL ([`slc_core::Vpl`]) as the shaders read it. Keep in sync with `Vpl` in
/// `gvpl.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuVpl {
    /// Position q (xyz) and the Russian-roulette number ξ of eq. (3) (w).
    pub position_xi: [f32; 4],
    /// Normal n (xyz) and GGX roughness α (w).
    pub normal_alpha: [f32; 4],
    /// Incoming direction ωi (xyz) and the relative index η of a dielectric Fresnel (w).
    pub omega_i_eta: [f32; 4],
    /// RGB flux Φ.
    pub flux: [f32; 3],
    /// Lobe ([`LOBE_DIFFUSE`], [`LOBE_GLOSSY`]).
    pub lobe: u32,
    /// Diffuse reflectance kd.
    pub kd: [f32; 3],
    /// Fresnel model ([`FRESNEL_SCHLICK`], [`FRESNEL_DIELECTRIC`]).
    pub fresnel: u32,
    /// Schlick F0.
    pub f0: [f32; 3],
    /// The VPL's id.
    pub id: u32,
    /// The geometric normal n_g (xyz) and the bound factor (w): `flux_scale` of
    /// `slc_bounds::shading_normal` for a diffuse VPL, `GlossyLobe::bound_factor` for a
    /// glossy one (tilted shading normal, anisotropy), 1 where neither applies.
    pub geometric_tilt: [f32; 4],
    /// The anisotropy's tangent (xyz) and α_t (w), zero where the lobe is isotropic
    /// (`slc_bounds::Anisotropy`).
    pub anisotropy: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuVpl>() == 128);
pub(crate) fn vec4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}
/// An anisotropy as the shaders store it: the tangent (xyz) and α_t (w); zero if isotropic.
pub fn gpu_anisotropy(a: Option<Anisotropy>) -> [f32; 4] {
    a.map_or([0.0; 4], |a| vec4(a.tangent, a.alpha_t))
}
/// The anisotropy of [`gpu_anisotropy`]'s form (α_t = 0: isotropic).
pub fn anisotropy_from_gpu(a: [f32; 4]) -> Option<Anisotropy> {
    (a[3] > 0.0).then(|| Anisotropy {
        tangent: Vec3::new(a[0], a[1], a[2]),
        alpha_t: a[3],
    })
}
impl GpuVpl {
    /// Packs VPL `index` after validating it exactly as the CPU culler does
    /// (`slc_cull`'s `VplBound::new`): finite position and ωi, δ and ξ valid for eq. (2)-(3),
    /// and a valid lobe (unit normal, α in (0, 1], non-negative flux, valid Fresnel); a diffuse
    /// VPL lit from below (ωi·n <= 0) is accepted without the lobe checks, its bound is empty.
    pub fn new(vpl: &Vpl, index: usize, delta: f32) -> Result<Self, GpuError> {
        let invalid = |e: &dyn std::fmt::Display| GpuError::Input(format!("VPL {index}: {e}"));
        if !(vpl.position.is_finite() && vpl.omega_i.is_finite()) {
            return Err(GpuError::Input(format!(
                "VPL {index} has a non-finite position or incoming direction"
            )));
        }
        StochasticParams::new(delta, vpl.xi).map_err(|e| invalid(&e))?;
        let (lobe, tilt) = match vpl.lobe {
            VplLobe::Diffuse => {
                if vpl.normal.dot(vpl.omega_i) > 0.0 {
                    vpl.diffuse_lobe().map_err(|e| invalid(&e))?;
                }
                let scale = flux_scale(vpl.normal, vpl.geometric_normal, vpl.omega_i);
                (LOBE_DIFFUSE, scale)
            }
            VplLobe::Glossy => {
                let lobe = vpl.glossy_lobe().map_err(|e| invalid(&e))?;
                (LOBE_GLOSSY, lobe.bound_factor())
            }
        };
        let (fresnel, f0, eta) = match vpl.brdf.fresnel {
            Fresnel::Schlick(f0) => (FRESNEL_SCHLICK, f0, 0.0),
            Fresnel::Dielectric(eta) => (FRESNEL_DIELECTRIC, Vec3::ZERO, eta),
        };
        Ok(Self {
            position_xi: vec4(vpl.position, vpl.xi),
            normal_alpha: vec4(vpl.normal, vpl.brdf.alpha),
            omega_i_eta: vec4(vpl.omega_i, eta),
            flux: vpl.flux.to_array(),
            lobe,
            kd: vpl.brdf.kd.to_array(),
            fresnel,
            f0: f0.to_array(),
            id: vpl.id,
            geometric_tilt: vec4(vpl.geometric_normal, tilt),
            anisotropy: gpu_anisotropy(vpl.brdf.anisotropy),
        })
    }
}
/// Parameters of VPL generation. Keep in sync with `VplGenParams` in `vpl_gen.wesl`.
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
    /// `cull::records::CULL_COUNT` or `CULL_WRITE`.
    pub mode: u32,
    /// `cos_theta_h_max(1, 0)` of `Fresnel::max_over_half_vectors(1, 0)`.
    pub cos_h_max: f32,
    pub pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuVplGenParams>() == 32);

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        crate::vpl::rng::SOURCE => {
            RngParams as "RngParams",
            RngSample as "RngSample",
        }
        crate::cull::bounds::SOURCE => {
            GpuVpl as "Vpl",
        }
        crate::shade::lists::SOURCE => {
            GpuVpl as "Vpl",
        }
        crate::vpl::generate::SOURCE => {
            GpuVpl as "Vpl",
            GpuVplGenParams as "VplGenParams",
        }
    }
}
