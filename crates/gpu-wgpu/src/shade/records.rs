//! `#[repr(C)]` twins of the WGSL structs of the shading passes. Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars and `[f32; 4]` / `[u32; 4]` are used (WGSL `f32`, `u32`, `vec4<f32>`,
//! `vec4<u32>`), never vec3, so the Rust and WGSL layouts agree without hidden padding.
use bytemuck::{Pod, Zeroable};

/// Parameters of the shading pass. Keep in sync with `ShadeParams` in `vpl_eval.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuShadeParams {
    pub width: u32,
    pub height: u32,
    pub pixel_count: u32,
    pub vpl_count: u32,
    /// Number of light lists (list ids at or beyond it shade nothing).
    pub list_count: u32,
    /// δ of eq. (2).
    pub delta: f32,
    /// K² of the interleaved sampling (section 6, [`slc_core::Interleaving::scale`]).
    pub scale: f32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuShadeParams>() == 32);

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        crate::shade::lists::SOURCE => {
            GpuShadeParams as "ShadeParams",
        }
    }
}
