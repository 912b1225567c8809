//! The rasterized G-buffer: the scene in storage buffers ([`scene`], `scene.wesl`,
//! `scene_types.wesl`), the nearest triangle per pixel by rasterization ([`visibility`]) and
//! the G-buffer resolved from it by the pixel's own ray ([`gbuffer`], `gsample.wesl`: the
//! sample every later pass reads), with their records ([`records`]).
pub mod gbuffer;
pub mod records;
pub mod scene;
pub mod visibility;
