//! # slc-bounds
//!
//! The closed-form math of stochastic light culling for virtual point lights (VPLs) on GGX
//! microsurfaces (Tokuyoshi and Harada, "Stochastic Light Culling for VPLs on GGX
//! Microsurfaces", with its supplemental material; equation numbers refer to the main paper).
//! Pure math on `glam` types: nothing here knows about scenes or renderers.
//!
//! A VPL is accepted at a shading point with probability p = min(I/(δ l²), 1) (eq. 2) against
//! one random number ξ per VPL (eq. 3), so it can only contribute within the random range
//! l_max(ωo) = sqrt(I(ωo)/(δ ξ)) (eq. 5). The crate bounds that range so a culler can skip
//! the VPL wherever the bound does not reach:
//!
//! - [`StochasticParams`]: δ and ξ, p, l_max and the estimator weight (eq. 2, 3, 5);
//!   [`scalar_intensity`] turns RGB into the scalar used for p (largest channel).
//! - [`GlossyLobe`] and [`Spheroid`]: a glossy VPL and its GGX bounding spheroid (eq. 12-15),
//!   using [`ggx`], [`Fresnel`] maxima (supplemental eq. 2, 6) and the [`Brdf`] of eq. (6).
//! - [`DiffuseLobe`] and [`Sphere`]: the diffuse VPL sphere (section 6) and the two glossy
//!   baseline spheres (section 7).
//! - [`TestSpace`], [`TileFrustum`] and [`Aabb`]: the stretched and rotated space of eq.
//!   (16)-(17) in which a spheroid is a unit sphere, tested against the boxes of tile frusta
//!   as in Modified HalfZ tiled culling (section 5).
//! - [`sg`]: spherical Gaussian algebra for virtual spherical Gaussian lights (Tokuyoshi 2015):
//!   [`SphericalGaussian`] products and integrals, Toksvig filtering ([`ToksvigSum`]) and
//!   analytic SG-light shading of this BRDF ([`SgSurface`]).
//!
//! Constructors validate their inputs and report out-of-domain values as [`BoundsError`];
//! nothing panics or produces NaN or infinity.
//!
//! ```
//! use glam::{Affine3A, Quat, Vec2, Vec3};
//! use slc_bounds::{Fresnel, GlossyLobe, Spheroid, StochasticParams, TestSpace, TileFrustum};
//!
//! // A glossy VPL at the origin on a floor (n = +z), lit from 60° off the normal.
//! let omega_i = Vec3::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos());
//! let lobe = GlossyLobe::new(Vec3::ZERO, Vec3::Z, omega_i, 0.1, Vec3::splat(2.0),
//!                            Fresnel::Schlick(Vec3::splat(0.04)))?;
//! let params = StochasticParams::new(1e-3, 0.5)?; // δ and this VPL's ξ
//! let spheroid = Spheroid::new(&lobe, &params)?;
//!
//! // The point at the random range along the mirror direction is inside; farther is not.
//! let omega_u = lobe.reflection();
//! let l_max = params.range(lobe.intensity(omega_u));
//! assert!(spheroid.contains(omega_u * (0.99 * l_max)));
//! assert!(!spheroid.contains(-omega_u * l_max));
//!
//! // Tiled culling: a camera 5 units behind that inside point, looking at it along +x (world
//! // +x becomes view +z), sees the spheroid in its central tile at depths 4..6.
//! let inside = omega_u * (0.5 * l_max);
//! let rotation = Quat::from_rotation_y(-core::f32::consts::FRAC_PI_2);
//! let view = Affine3A::from_rotation_translation(rotation, -(rotation * (inside - 5.0 * Vec3::X)));
//! let space = TestSpace::from_spheroid(&spheroid, view)?;
//! let tile = TileFrustum::new(Vec2::splat(-0.01), Vec2::splat(0.01), 4.0, 6.0)?;
//! assert!(space.intersects(&tile));
//! # Ok::<(), slc_bounds::BoundsError>(())
//! ```
pub mod aabb;
pub mod anisotropy;
pub mod basis;
pub mod box_bound;
pub mod brdf;
mod check;
pub mod diffuse;
pub mod error;
pub mod fresnel;
pub mod frustum;
pub mod ggx;
pub mod glossy;
pub mod lanes;
#[cfg(target_arch = "x86_64")]
pub mod lanes_avx;
#[cfg(target_arch = "x86_64")]
pub mod lanes_avx512;
pub mod sg;
pub mod shading_normal;
pub mod sphere;
pub mod spheroid;
pub mod stochastic;
pub mod test_space;
#[cfg(test)]
mod test_util;

pub use aabb::Aabb;
pub use anisotropy::Anisotropy;
pub use basis::Basis;
pub use box_bound::lanes::BoxBoundLanes;
pub use box_bound::{BoxBound, ReceiverBox, SchlickLobes};
pub use brdf::Brdf;
pub use diffuse::DiffuseLobe;
pub use error::BoundsError;
pub use fresnel::Fresnel;
pub use frustum::TileFrustum;
pub use glossy::GlossyLobe;
pub use sg::{SgSurface, SphericalGaussian, ToksvigSum};
pub use sphere::Sphere;
pub use spheroid::Spheroid;
pub use stochastic::{scalar_intensity, StochasticParams};
pub use test_space::TestSpace;
