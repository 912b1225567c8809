//! The frame vocabulary every backend shares: what to render ([`RenderSettings`]), what it
//! cost ([`Timings`]), what comes back ([`Shaded`], [`RenderedFrame`]) and why it failed
//! ([`RenderError`]).
mod error;
mod memory;
mod output;
mod settings;
mod timings;

pub use error::RenderError;
pub use memory::MemoryEstimate;
pub use output::{RenderedFrame, Shaded};
pub use settings::{
    DiffuseEmission, Importance, LightSampling, LobeSelection, Method, RenderSettings, Stochastic,
    MAX_IMAGE_SIDE, MAX_RSM_SIDE, MAX_SAMPLED_LIGHTS,
};
pub use timings::{merge_optional, PassTime, Timings};
