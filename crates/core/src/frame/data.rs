//! A prepared frame's data where the CPU can read it: what a backend hands to the passes only
//! the CPU has (the brute-force metrics, the references, the VSGL sweeps).
use crate::camera::Camera;
use crate::frame::Timings;
use crate::framebuffer::{GBuffer, Image};
use crate::rsm::Rsm;
use crate::vpl::Vpl;

/// The G-buffer, the RSMs (one per light, in the scene's order), the VPLs and the direct
/// light of a frame, with the camera it was seen from and its passes' times.
#[derive(Clone, Debug)]
pub struct PreparedData {
    pub camera: Camera,
    pub gbuffer: GBuffer,
    pub maps: Vec<Rsm>,
    pub vpls: Vec<Vpl>,
    pub direct: Image,
    pub timings: Timings,
}
