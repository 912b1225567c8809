//! The mipmapped reflective shadow map of VSGL section 4.1.
use super::light::Vsgl;
use super::sums::ClusterSums;
use crate::rsm::Rsm;
use slc_bounds::sg::MeanMap;
use slc_bounds::BoundsError;
use slc_core::vsgl::Quadtree;

/// One sum-based mip pyramid of [`ClusterSums`] per face of an [`Rsm`] (VSGL section 4.1),
/// laid out by a [`Quadtree`]: level 0 holds the texels' own sums (zero for empty texels), and
/// each texel of level `l` the sum of its children, so it is the cluster of the up to `4^l`
/// level-0 texels it covers. The paper's mean-filtered `B(s, l)` is this sum over `4^l`
/// ("total of cluster = 4^l B(s, l)").
pub struct MipRsm {
    layout: Quadtree,
    map: MeanMap,
    texels: Vec<ClusterSums>,
}

impl MipRsm {
    /// Builds the pyramids of `rsm`, with the lobe buffers using `map` ([`MeanMap::Toksvig`]
    /// is the paper's). Fails for an invalid BRDF in a texel.
    pub fn build(rsm: &Rsm, map: MeanMap) -> Result<Self, BoundsError> {
        let layout = Quadtree::new(rsm.resolution, rsm.faces);
        let n = layout.resolution();
        let zero = ClusterSums::empty(map);
        let mut texels = vec![zero; layout.len()];
        for face in 0..rsm.faces {
            for y in 0..n {
                for x in 0..n {
                    let k = ((face * n + y) * n + x) as usize;
                    if let Some(texel) = &rsm.texels[k] {
                        texels[layout.index(face, 0, x, y)] = ClusterSums::from_texel(texel, map)?;
                    }
                }
            }
        }
        layout.fill_levels(&mut texels, &zero, ClusterSums::merge);
        Ok(Self {
            layout,
            map,
            texels,
        })
    }

    /// The quadtree of the pyramids.
    pub fn layout(&self) -> &Quadtree {
        &self.layout
    }

    /// The RSM resolution `N` (the size of level 0).
    pub fn resolution(&self) -> u32 {
        self.layout.resolution()
    }

    /// The number of faces (pyramids).
    pub fn faces(&self) -> u32 {
        self.layout.faces()
    }

    /// The number of levels, `⌈log2 N⌉ + 1`; the last is 1×1.
    pub fn levels(&self) -> u32 {
        self.layout.levels()
    }

    /// The side `⌈N/2^level⌉` of a level.
    pub fn size(&self, level: u32) -> u32 {
        self.layout.size(level)
    }

    /// The mean-vector map of the lobe buffers.
    pub fn map(&self) -> MeanMap {
        self.map
    }

    /// The sums of the cluster at texel `(x, y)` (column, row) of `level` of `face`. Panics
    /// out of range.
    pub fn sums(&self, face: u32, level: u32, x: u32, y: u32) -> &ClusterSums {
        &self.texels[self.layout.index(face, level, x, y)]
    }

    /// The VSGL of that cluster ([`Vsgl::from_sums`], `σ_v²` at least `sigma2_floor`).
    pub fn vsgl(
        &self,
        face: u32,
        level: u32,
        x: u32,
        y: u32,
        sigma2_floor: f32,
    ) -> Result<Vsgl, BoundsError> {
        Vsgl::from_sums(self.sums(face, level, x, y), sigma2_floor)
    }
}
