//! The frame vocabulary every backend shares: what to render ([`RenderSettings`]), what it
//! cost ([`Timings`]), what comes back ([`Shaded`], [`RenderedFrame`], a prepared frame's
//! [`PreparedData`]) and why it failed ([`RenderError`]).
mod bilateral;
pub mod counts;
mod data;
mod error;
pub mod memory;
mod output;
mod settings;
mod timings;

pub use bilateral::BilateralParams;
pub use counts::{Count, MAX_IMAGE_SIDE, MAX_RSM_SIDE, MAX_SAMPLED_LIGHTS};
pub use data::PreparedData;
pub use error::RenderError;
pub use memory::MemoryEstimate;
pub use output::{RenderedFrame, Shaded};
pub use settings::{
    DiffuseEmission, Importance, LightSampling, LobeSelection, Method, RenderSettings, Stochastic,
};
pub use timings::{merge_optional, PassTime, Timings};
