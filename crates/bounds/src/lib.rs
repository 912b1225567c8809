//! Closed-form math of stochastic light culling for VPLs on GGX microsurfaces.
pub mod brdf;
pub mod fresnel;
pub mod ggx;

pub use brdf::Brdf;
pub use fresnel::Fresnel;
