//! The CPU reference renderer of slc.
pub mod direct;
pub mod gbuffer;
pub mod path;
pub mod render;
pub mod rsm;
pub mod sampling;
pub mod tracer;
pub mod vpl_shading;
pub mod vpls;

pub use render::{render, Frame, Method, RenderError, RenderSettings};
pub use tracer::Tracer;
pub use vpl_shading::VplEstimator;
pub use vpls::LobeSelection;
