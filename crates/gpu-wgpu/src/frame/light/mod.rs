//! The lights: reflective shadow maps by rasterization, whose depth doubles as the shadow map
//! ([`rsm`], `rsm.wesl`, `rsm_texel.wesl`, `solid_angle.wesl`), and the direct light of every
//! G-buffer pixel from them ([`direct`]), with their records ([`records`]).
pub mod direct;
pub mod records;
pub mod rsm;
