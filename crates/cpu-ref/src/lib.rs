//! # slc-cpu-ref
//!
//! The CPU reference renderer of slc: the images every faster strategy is measured against.
//! Everything is ray traced with an obvhs BVH and a watertight triangle test, in parallel with
//! rayon:
//!
//! - a G-buffer of primary rays ([`gbuffer`]), through pixel centres or jittered (box filter);
//! - reflective shadow maps traced from each light ([`rsm`]): six cube faces for a point light,
//!   one face for a spot light, an orthographic map for a directional light, each texel
//!   carrying the exact flux of its solid angle (or area);
//! - one diffuse and one glossy VPL per lit texel with its Russian-roulette ξ ([`vpls`]);
//! - direct light with shadow rays ([`direct`]);
//! - shading by every VPL, exactly or with the stochastic estimator of eq. (3), with or without
//!   VPL-to-pixel shadow rays ([`vpl_shading`]);
//! - a path-traced one-bounce reference ([`path`]);
//! - virtual spherical Gaussian lights (Tokuyoshi 2015) from mipmapped RSMs, sampled by
//!   filtered importance and shaded analytically, and VPLs sampled by the same importance at
//!   equal count ([`vsgl`], [`sampled_lights`]).
//!
//! [`CpuRenderer`] is the CPU backend of the renderer API (`slc_core::Renderer`): every step
//! of the frame, the references and shadow rays included; [`render()`] runs a whole frame on
//! it, and [`prepare()`] makes a frame's G-buffer, RSMs, VPLs and direct light. A renderer kept
//! from frame to frame shades each frame into the noisy image its filter consumed the frame
//! before ([`vpl_shading::shade_lists_into`]), so a loop of frames allocates no image to
//! shade into. Its images
//! agree with an independent path tracer (Mitsuba 3) within noise: see
//! `tests/reference_cornell_a.rs` at the workspace root.
//!
//! ```
//! use slc_core::builtin;
//! use slc_core::frame::{LobeSelection, Method, RenderSettings, Stochastic};
//! use slc_core::Strategy;
//! use slc_cpu_ref::render;
//!
//! let scene = builtin("default").unwrap();
//! let settings = RenderSettings {
//!     width: 32, height: 32, rsm_resolution: 4, seed: 7,
//!     method: Method::Stochastic(Stochastic {
//!         delta: 1e-3, strategy: Strategy::Ellipsoid, interleave: 4, denoise: true, metrics: false,
//!     }),
//!     visibility: false, spp: 1, lobes: LobeSelection::Both,
//! };
//! let frame = render(&scene, &settings, &|_pixels_done| {})?;
//! assert!(frame.vpl_count > 0);
//! assert!(frame.indirect.mean().max_element() > 0.0);
//! # Ok::<(), slc_core::RenderError>(())
//! ```
mod blocks;
pub mod denoise;
pub mod direct;
mod frame_images;
pub mod gbuffer;
mod list_ranks;
mod listed_vpls;
pub mod path;
pub mod prepare;
pub mod received_lanes;
pub mod renderer;
pub mod rsm;
pub mod sampled_lights;
pub mod sampling;
pub mod tracer;
pub mod vpl_shading;
pub mod vpls;
pub mod vsgl;
pub mod watertight;

pub use prepare::{prepare, CpuPrepared};
pub use renderer::{render, CpuRenderer};
pub use tracer::Tracer;
pub use vpl_shading::VplEstimator;
