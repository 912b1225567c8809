//! Spherical Gaussian (SG) algebra for virtual spherical Gaussian lights (Tokuyoshi 2015,
//! "Virtual Spherical Gaussian Lights for Real-time Glossy Indirect Illumination", section 2.2,
//! 3.1 and 3.2; "VSGL" below).
//!
//! - [`SphericalGaussian`]: `c G(ω; ξ, λ) = c exp(λ(ω·ξ − 1))` (VSGL section 2.2), its
//!   integral [`sg_integral`] `A(λ)` and normalization, scaling, the product of two SGs (the form
//!   of VSGL eq. 5) and their inner product.
//! - [`ggx_mixture`]: a GGX lobe's SG (peak and integral) as three SGs on its axis that follow
//!   GGX's heavy tails ([`GGX_MIXTURE`]), the specular emission of a VSGL, and
//!   [`LobeStretch`], the anisotropy of a reflected lobe (narrower across the plane of
//!   incidence).
//! - [`ToksvigSum`]: Toksvig filtering of a set of lobes into one (VSGL section 3.1.1) through
//!   mean vectors, with the paper's length `λ/(λ+1)` ([`toksvig_mean_length`]) and the exact
//!   one `coth λ − 1/λ` ([`exact_mean_length`]), and their inverses.
//! - [`clamped_cosine_sg`]: the SG fit of the clamped cosine (its sharpness shapes the diffuse
//!   lobe of a VPL's radiant intensity).
//! - [`SphericalGaussian::irradiance`] ([`normalized_sg_irradiance`]): the diffuse receiver's
//!   `∫ L_in(ω) max(ω·n, 0) dω` for an SG light, clamped at the horizon (Hill's fit with exact
//!   limits), and [`SpecularLobeSg`], its GGX specular lobe for a view direction (an SG through the
//!   true lobe's peak with its integral, [`SpecularFit`], tabulated by quadrature), combined by [`SgSurface`] into the analytic shading of VSGL eq. (2)
//!   with the incoming radiance of eq. (5); the same shading in `f32` for inner loops, one
//!   light or eight per vector ([`SgLanes`], [`SgSurface::radiance_lanes`], `single.rs`, the
//!   forms of the GPU's `sg.wgsl`).
mod cosine;
mod integral;
mod irradiance;
mod lobe;
mod mixture;
mod product;
#[cfg(test)]
mod quadrature;
mod shading;
mod single;
mod specular;
mod specular_fit;
pub mod specular_table;
mod stretch;
mod toksvig;

pub use cosine::{clamped_cosine_sg, COSINE_LOBE_AMPLITUDE, COSINE_LOBE_SHARPNESS};
pub use integral::sg_integral;
pub use irradiance::normalized_sg_irradiance;
pub use lobe::SphericalGaussian;
pub use mixture::{ggx_mixture, mixture_scale, MixtureSg, GGX_MIXTURE, MIXTURE_FROM};
pub use shading::SgSurface;
pub use single::{finite, splat3, IrradianceFit, SgLanes};
pub use specular::{ggx_ndf_sg, SpecularLobeSg};
pub use specular_fit::{
    fit_lobe, table_node, SpecularFit, ALPHA_STEPS, TABLE_MIN_ALPHA, TABLE_MIN_COS, VIEW_STEPS,
};
pub use stretch::{LobeStretch, STRETCH_MIN_COS, STRETCH_SHARPNESS};
pub use toksvig::{
    exact_mean_length, exact_sharpness, toksvig_mean_length, toksvig_sharpness, MeanMap, ToksvigSum,
};
