//! What a frame's largest buffers take, estimated from the settings before anything is
//! allocated, so a run too large for the machine is refused up front.
use super::settings::{LobeSelection, Method, RenderSettings};
use crate::framebuffer::GSample;
use crate::light::Light;
use crate::scene::Scene;
use crate::vpl::Vpl;
use glam::Vec3;
use std::mem::size_of;

/// Bytes of a frame's largest buffers. The light lists are not included: their length
/// depends on what the bounds cull (they are usually smaller than the G-buffer).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// Per pixel: the visible surface.
    pub gbuffer: u64,
    /// Per pixel: direct, indirect, total and two filter buffers, RGB f32.
    pub images: u64,
    /// Per RSM texel of every face of every light: the surface it sees and its flux.
    pub rsm: u64,
    /// One or two VPLs per RSM texel (the lobes asked for).
    pub vpls: u64,
    /// Per pixel: lights listed and false discovery rate, when metrics are measured.
    pub metrics: u64,
}

impl MemoryEstimate {
    pub fn total(&self) -> u64 {
        self.gbuffer + self.images + self.rsm + self.vpls + self.metrics
    }
}

impl Light {
    /// RSM faces the light renders: six cube faces for a point light, one otherwise.
    pub fn rsm_faces(&self) -> u64 {
        match self {
            Light::Point { .. } => 6,
            Light::Spot { .. } | Light::Directional { .. } => 1,
        }
    }
}

impl RenderSettings {
    /// The estimate of [`MemoryEstimate`] for rendering `scene` with these settings.
    pub fn memory_estimate(&self, scene: &Scene) -> MemoryEstimate {
        let pixels = u64::from(self.width) * u64::from(self.height);
        let faces: u64 = scene.lights.iter().map(Light::rsm_faces).sum();
        let texels = faces * u64::from(self.rsm_resolution).pow(2);
        let lobes = match self.lobes {
            LobeSelection::Both => 2,
            LobeSelection::Diffuse | LobeSelection::Glossy => 1,
        };
        let metrics = matches!(self.method, Method::Stochastic(s) if s.metrics);
        let sample = size_of::<Option<GSample>>() as u64;
        MemoryEstimate {
            gbuffer: pixels * sample,
            images: pixels * 5 * size_of::<Vec3>() as u64,
            rsm: texels * (sample + size_of::<Vec3>() as u64),
            vpls: texels * lobes * size_of::<Vpl>() as u64,
            metrics: if metrics { pixels * 8 } else { 0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Stochastic;
    use crate::strategy::Strategy;

    fn settings(width: u32, height: u32, rsm: u32) -> RenderSettings {
        RenderSettings {
            width,
            height,
            rsm_resolution: rsm,
            seed: 0,
            method: Method::Stochastic(Stochastic {
                delta: 1e-3,
                strategy: Strategy::Ellipsoid,
                interleave: 8,
                denoise: true,
                metrics: false,
            }),
            visibility: false,
            spp: 1,
            lobes: LobeSelection::Both,
        }
    }

    #[test]
    fn grows_with_pixels_and_texels() {
        let mut scene = Scene::default();
        scene.lights.push(Light::Point {
            position: Vec3::ZERO,
            intensity: Vec3::ONE,
        });
        let small = settings(64, 32, 16).memory_estimate(&scene);
        let wide = settings(128, 32, 16).memory_estimate(&scene);
        assert_eq!(wide.gbuffer, 2 * small.gbuffer);
        assert_eq!(wide.images, 2 * small.images);
        assert_eq!(wide.rsm, small.rsm);
        // A point light's six faces, two VPLs per texel.
        assert_eq!(small.vpls, 6 * 16 * 16 * 2 * size_of::<Vpl>() as u64);
        // The cases: 16384² and RSM 4096 with a point light need tens of GB.
        assert!(settings(16384, 16384, 16).memory_estimate(&scene).total() > 20 << 30);
        assert!(settings(64, 64, 4096).memory_estimate(&scene).total() > 20 << 30);
    }
}
