//! The mipmapped reflective shadow map of VSGL section 4.1.
use super::light::Vsgl;
use super::sums::ClusterSums;
use crate::rsm::Rsm;
use slc_bounds::sg::MeanMap;
use slc_bounds::BoundsError;

/// One sum-based mip pyramid of [`ClusterSums`] per face of an [`Rsm`] (VSGL section 4.1):
/// level 0 holds the texels' own sums (zero for empty texels), and texel `(x, y)` of level `l`
/// the sum of texels `(2x + i, 2y + j)`, `i, j ∈ {0, 1}`, of level `l − 1`, so it is the
/// cluster of the level-0 texels `[2^l x, 2^l (x + 1)) × [2^l y, 2^l (y + 1))`. The paper's
/// mean-filtered `B(s, l)` is this sum over `4^l` ("total of cluster = 4^l B(s, l)").
///
/// Level `l` is `⌈N/2^l⌉` texels square for an RSM of resolution `N` (children beyond the
/// edge of a level with odd size count as empty), down to the 1×1 level `⌈log2 N⌉`. Storage is
/// face-major, then level, then row-major like the RSM (row `y`, column `x`).
pub struct MipRsm {
    resolution: u32,
    faces: u32,
    map: MeanMap,
    /// Offset of each level within a face's block.
    level_offsets: Vec<usize>,
    /// Texels per face, all levels.
    face_len: usize,
    texels: Vec<ClusterSums>,
}

impl MipRsm {
    /// Builds the pyramids of `rsm`, with the lobe buffers using `map` ([`MeanMap::Toksvig`]
    /// is the paper's). Fails for an invalid BRDF in a texel.
    pub fn build(rsm: &Rsm, map: MeanMap) -> Result<Self, BoundsError> {
        let n = rsm.resolution.max(1);
        let mut level_offsets = vec![0];
        let mut size = n;
        let mut face_len = (n * n) as usize;
        while size > 1 {
            size = size.div_ceil(2);
            level_offsets.push(face_len);
            face_len += (size * size) as usize;
        }
        let mut mip = Self {
            resolution: n,
            faces: rsm.faces,
            map,
            level_offsets,
            face_len,
            texels: vec![ClusterSums::empty(map); face_len * rsm.faces as usize],
        };
        for face in 0..rsm.faces {
            for y in 0..n {
                for x in 0..n {
                    let k = ((face * n + y) * n + x) as usize;
                    if let Some(texel) = &rsm.texels[k] {
                        let index = mip.index(face, 0, x, y);
                        mip.texels[index] = ClusterSums::from_texel(texel, map)?;
                    }
                }
            }
            for level in 1..mip.levels() {
                let (size, child_size) = (mip.size(level), mip.size(level - 1));
                for y in 0..size {
                    for x in 0..size {
                        let mut sum = ClusterSums::empty(map);
                        for (cx, cy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            let (cx, cy) = (2 * x + cx, 2 * y + cy);
                            if cx < child_size && cy < child_size {
                                sum.merge(&mip.texels[mip.index(face, level - 1, cx, cy)]);
                            }
                        }
                        let index = mip.index(face, level, x, y);
                        mip.texels[index] = sum;
                    }
                }
            }
        }
        Ok(mip)
    }

    /// The RSM resolution `N` (the size of level 0).
    pub fn resolution(&self) -> u32 {
        self.resolution
    }

    /// The number of faces (pyramids).
    pub fn faces(&self) -> u32 {
        self.faces
    }

    /// The number of levels, `⌈log2 N⌉ + 1`; the last is 1×1.
    pub fn levels(&self) -> u32 {
        self.level_offsets.len() as u32
    }

    /// The side `⌈N/2^level⌉` of a level.
    pub fn size(&self, level: u32) -> u32 {
        let mut size = self.resolution;
        for _ in 0..level {
            size = size.div_ceil(2);
        }
        size
    }

    /// The mean-vector map of the lobe buffers.
    pub fn map(&self) -> MeanMap {
        self.map
    }

    /// The sums of the cluster at texel `(x, y)` (column, row) of `level` of `face`. Panics
    /// out of range.
    pub fn sums(&self, face: u32, level: u32, x: u32, y: u32) -> &ClusterSums {
        &self.texels[self.index(face, level, x, y)]
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

    fn index(&self, face: u32, level: u32, x: u32, y: u32) -> usize {
        let size = self.size(level);
        assert!(
            face < self.faces && x < size && y < size,
            "mip texel out of range"
        );
        face as usize * self.face_len + self.level_offsets[level as usize] + (y * size + x) as usize
    }
}
