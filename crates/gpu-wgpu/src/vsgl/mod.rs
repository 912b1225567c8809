//! Virtual spherical Gaussian lights (Tokuyoshi 2015) on the GPU: built from the RSMs where
//! they lie ([`build`]: mipmaps, importance, filtered importance sampling), shaded
//! analytically ([`shade`]: SG receiver, one VSGL's radiance, the specular table), with
//! visibility from imperfect shadow maps ([`ism`]); [`readback`] brings RSMs to the CPU and
//! CPU VSGLs to the shading pass.
pub mod build;
pub mod ism;
pub mod readback;
pub mod shade;
