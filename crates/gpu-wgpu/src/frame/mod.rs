//! The frame before culling, each pass the twin of a `slc_cpu_ref` step: the scene uploaded
//! and rasterized into the G-buffer ([`raster`]: scene, visibility buffer, G-buffer samples),
//! the lights' reflective shadow maps and the direct light with their depth as shadow maps
//! ([`light`]), and the cross bilateral filter at the end of the frame ([`denoise`]).
pub mod denoise;
pub mod light;
pub mod raster;
