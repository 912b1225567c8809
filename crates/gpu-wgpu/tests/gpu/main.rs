//! GPU conformance tests: the GPU passes against the CPU crates for identical inputs.
//!
//! They need a wgpu adapter (CI: Mesa's lavapipe, installed by `.ci/run`). Without one,
//! each test fails when the `CI` environment variable is set, and otherwise prints a notice
//! and returns (see [`common::gpu`]).
mod binned;
mod bounds;
mod clustered;
mod common;
mod culler;
mod denoise;
mod faults;
mod ism;
mod limits;
mod profile;
mod raster_baselines;
mod raster_common;
mod raster_frame;
mod raster_gbuffer;
mod raster_rsm;
mod readback;
mod rng;
mod scan;
mod shade;
mod tight;
mod tiled;
mod tiled_shade;
mod vpl_buffers;
mod vsgl;
mod vsgl_build;
mod vsgl_visibility;
