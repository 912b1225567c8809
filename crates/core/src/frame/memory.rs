//! What a run holds at its peak, estimated from the settings and the loaded scene before
//! anything is allocated, so a run too large for the machine is refused up front. The
//! coefficients are measured: `tools/memory/grid.py` runs `slc render` over a grid of sizes,
//! scenes, shaders and lobes and compares each run's peak RSS with this estimate
//! (`docs/memory.md` holds the table; every peak is below its estimate).
use super::settings::{Method, RenderSettings};
use crate::framebuffer::GSample;
use crate::light::Light;
use crate::scene::Scene;
use glam::{Vec2, Vec3, Vec4};
use std::mem::size_of;

/// The process before any scene or frame: code, libraries, the thread pool, the allocator's
/// arenas (a 1 x 1 render holds 12 MiB).
pub const BASELINE_BYTES: u64 = 24 << 20;
/// Per pixel besides the G-buffer: the direct, indirect and total images, the filter's
/// buffers (its planes 52 bytes), the per-pixel lists' heads, the images written (PNG and EXR
/// encoders, the multi-layer EXR) — 15 RGB `f32` values (measured: 200–252 bytes a pixel with
/// the 104 of the G-buffer, the most at 2048x2048 and above; estimated: 284).
pub const IMAGE_BYTES_PER_PIXEL: u64 = 15 * size_of::<Vec3>() as u64;
/// Per RSM texel: the traced surface and its flux, and the VSGL shader's mipmaps of them
/// (measured: about 115 bytes).
pub const RSM_BYTES_PER_TEXEL: u64 = 128;
/// Per VPL: the VPL, its culling bound in the test space, its place in the lists and the
/// sort that builds them (measured: 440 bytes a diffuse VPL, 550 a glossy one, 610 with the
/// clustered strategy).
pub const VPL_BYTES: u64 = 640;
/// Per vertex a mesh holds at most (position, normal, texture coordinate, tangent) and per
/// triangle (three indices).
pub const MESH_BYTES_PER_VERTEX: u64 =
    (2 * size_of::<Vec3>() + size_of::<Vec2>() + size_of::<Vec4>()) as u64;
pub const MESH_BYTES_PER_TRIANGLE: u64 = 3 * 4;
/// Per triangle, what the CPU backend builds of the scene: its copy of the triangle
/// (obvhs `Triangle`, 48 bytes), the reference back to the mesh, and the BVH with what its
/// build holds at once, with the loader's copies (measured: up to 370 bytes, on a generated
/// OBJ of 320,000 triangles).
pub const BVH_BYTES_PER_TRIANGLE: u64 = 384;

/// Bytes of `vertices` and `triangles` placed in a scene, with the BVH over them.
pub fn geometry_bytes(vertices: u64, triangles: u64) -> u64 {
    vertices * MESH_BYTES_PER_VERTEX
        + triangles * (MESH_BYTES_PER_TRIANGLE + BVH_BYTES_PER_TRIANGLE)
}

/// Bytes of memory available to a new allocation (`MemAvailable` of `/proc/meminfo`), where
/// the OS says.
pub fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Bytes a run holds at its peak, by what holds them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// [`BASELINE_BYTES`].
    pub baseline: u64,
    /// The scene as loaded: meshes and textures ([`Scene::memory_bytes`]).
    pub scene: u64,
    /// The CPU backend's BVH and triangle copies ([`BVH_BYTES_PER_TRIANGLE`]).
    pub bvh: u64,
    /// Per pixel: the visible surface.
    pub gbuffer: u64,
    /// Per pixel: [`IMAGE_BYTES_PER_PIXEL`].
    pub images: u64,
    /// Per RSM texel of every face of every light: [`RSM_BYTES_PER_TEXEL`].
    pub rsm: u64,
    /// One or two VPLs per RSM texel (the lobes asked for), [`VPL_BYTES`] each.
    pub vpls: u64,
    /// Per pixel: lights listed and false discovery rate, when metrics are measured.
    pub metrics: u64,
}

impl MemoryEstimate {
    pub fn total(&self) -> u64 {
        self.baseline
            + self.scene
            + self.bvh
            + self.gbuffer
            + self.images
            + self.rsm
            + self.vpls
            + self.metrics
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

impl Scene {
    /// Bytes the scene's meshes and textures hold.
    pub fn memory_bytes(&self) -> u64 {
        let meshes: usize = self
            .meshes
            .iter()
            .map(|m| {
                m.positions.len() * size_of::<Vec3>()
                    + m.normals
                        .as_ref()
                        .map_or(0, |v| v.len() * size_of::<Vec3>())
                    + m.uvs.as_ref().map_or(0, |v| v.len() * size_of::<Vec2>())
                    + m.tangents
                        .as_ref()
                        .map_or(0, |v| v.len() * size_of::<Vec4>())
                    + m.triangles.len() * size_of::<[u32; 3]>()
            })
            .sum();
        let textures: usize = self
            .textures
            .iter()
            .map(|t| t.texels.len() * size_of::<Vec3>())
            .sum();
        (meshes + textures) as u64
    }
}

impl RenderSettings {
    /// The estimate of [`MemoryEstimate`] for rendering `scene` with these settings. Every VPL
    /// a texel could make is counted (texels that see nothing make none).
    pub fn memory_estimate(&self, scene: &Scene) -> MemoryEstimate {
        let pixels = u64::from(self.width) * u64::from(self.height);
        let faces: u64 = scene.lights.iter().map(Light::rsm_faces).sum();
        let texels = faces * u64::from(self.rsm_resolution).pow(2);
        let lobes = match (self.method, self.lobes) {
            (Method::Path, _) => 0,
            (_, lobes) => u64::from(lobes.per_texel()),
        };
        let metrics = matches!(self.method, Method::Stochastic(s) if s.metrics);
        MemoryEstimate {
            baseline: BASELINE_BYTES,
            scene: scene.memory_bytes(),
            bvh: scene.triangle_count() as u64 * BVH_BYTES_PER_TRIANGLE,
            gbuffer: pixels * size_of::<Option<GSample>>() as u64,
            images: pixels * IMAGE_BYTES_PER_PIXEL,
            rsm: texels * RSM_BYTES_PER_TEXEL,
            vpls: texels * lobes * VPL_BYTES,
            metrics: if metrics { pixels * 8 } else { 0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Stochastic;

    fn settings(width: u32, height: u32, rsm: u32) -> RenderSettings {
        RenderSettings::new(width, height, rsm, Method::Stochastic(Stochastic::PAPER))
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
        assert_eq!(small.vpls, 6 * 16 * 16 * 2 * VPL_BYTES);
        assert_eq!(small.baseline, BASELINE_BYTES);
        // The cases: 16384² and RSM 4096 with a point light need tens of GB.
        assert!(settings(16384, 16384, 16).memory_estimate(&scene).total() > 20 << 30);
        assert!(settings(64, 64, 4096).memory_estimate(&scene).total() > 20 << 30);
    }
}
