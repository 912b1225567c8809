//! `#[repr(C)]` twins of the WGSL structs of the VSGL construction (`vsgl_tree.wesl`,
//! `vsgl_sums.wesl`, `vsgl_build.wesl`), in the convention of
//! every `records.rs`: a compile-time size check and a unit test against the layout naga
//! computes from the shader.
use bytemuck::{Pod, Zeroable};
use slc_core::vsgl::Quadtree;

/// The quadtree of a frame's maps ([`Quadtree`]: `faces` pyramids of resolution `n`, faces
/// of all maps numbered map by map). Keep in sync with `Tree` in `vsgl_tree.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuTree {
    pub n: u32,
    pub faces: u32,
    pub levels: u32,
    /// Texels per face, all levels.
    pub face_len: u32,
}
const _: () = assert!(std::mem::size_of::<GpuTree>() == 16);

impl GpuTree {
    /// The tree of `faces` maps of `resolution`² texels, as [`Quadtree::new`] lays it out.
    pub fn new(resolution: u32, faces: u32) -> Self {
        let q = Quadtree::new(resolution, faces);
        let one = Quadtree::new(resolution, 1);
        Self {
            n: q.resolution(),
            faces,
            levels: q.levels(),
            face_len: one.len() as u32,
        }
    }

    /// Texels of every level of every face.
    pub fn len(&self) -> usize {
        self.face_len as usize * self.faces as usize
    }

    /// Whether the tree has no texels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The side of `level`.
    pub fn size(&self, level: u32) -> u32 {
        (0..level).fold(self.n, |s, _| s.div_ceil(2))
    }
}

/// The parameters of every entry point of `vsgl_build.wesl` (each reads its own
/// fields; see `BuildParams` there). Keep in sync with it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuBuildParams {
    pub tree: GpuTree,
    pub origin: [f32; 4],
    pub forward: [f32; 4],
    pub items: u32,
    pub level: u32,
    pub first_face: u32,
    pub first_texel: u32,
    pub orthographic: u32,
    pub width: u32,
    pub count: u32,
    pub bidirectional: u32,
    pub shift: [f32; 2],
    pub sigma2_floor: f32,
    pub flags: u32,
}
const _: () = assert!(std::mem::size_of::<GpuBuildParams>() == 96);

/// `flags` bit: the diffuse lobe emits as the clamped cosine.
pub const CLAMPED_DIFFUSE: u32 = 1;
/// `flags` bit: the emitted lights are counted in the status record.
pub const COUNT_LIGHTS: u32 = 2;

/// The cluster sums of one tree texel (`Sums` in `vsgl_sums.wesl`, the f32 twin of
/// `slc_cpu_ref::vsgl::ClusterSums` with the positional buffers as a mean and a second
/// moment about it).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSums {
    /// `Σ Φ R_d` (rgb), `M2 = Σ w (|x − μ|² + s²)` (w).
    pub diffuse_m2: [f32; 4],
    /// `Σ Φ R_s` (rgb), the positional weight `Σ w` (w).
    pub specular_w: [f32; 4],
    /// `Σ w_d ξ̄_d` (xyz); the x of `Σ w_s n` (w).
    pub diffuse_mean: [f32; 4],
    /// `Σ w_s ξ̄_s` (xyz); the y of `Σ w_s n` (w).
    pub specular_mean: [f32; 4],
    /// `μ = Σ w x / Σ w` (xyz); the z of `Σ w_s n` (w), the specular-weighted normal
    /// (`ClusterSums::specular_normal`).
    pub mu: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuSums>() == 80);

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        crate::vsgl::build::SOURCE => {
            GpuTree as "Tree",
            GpuBuildParams as "BuildParams",
            GpuSums as "Sums",
        }
    }

    /// The tree's sizes and lengths are the CPU quadtree's.
    #[test]
    fn tree_matches_the_quadtree() {
        for (n, faces) in [(1, 1), (5, 2), (128, 1), (33, 6)] {
            let t = GpuTree::new(n, faces);
            let q = Quadtree::new(n, faces);
            assert_eq!(t.len(), q.len());
            assert_eq!(t.levels, q.levels());
            for level in 0..q.levels() {
                assert_eq!(t.size(level), q.size(level));
            }
        }
    }
}
