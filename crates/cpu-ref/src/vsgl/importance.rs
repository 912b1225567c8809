//! The importance `p(s)` of VSGL section 4.2 over an RSM's texels, as a sum pyramid for
//! hierarchical sample warping.
use super::error::VsglError;
use super::mip::MipRsm;
use super::sums::ClusterSums;
use crate::rsm::Rsm;
use slc_bounds::sg::MeanMap;
use slc_core::vsgl::Quadtree;

/// Unnormalized importance masses of one RSM's texels, summed up a [`Quadtree`] per face: the
/// mass of a texel of level `l` is the importance of the cluster of VPLs it covers (VSGL section
/// 4.1), and `mass / total` over every map sampled together is the probability that a sample
/// lands in it (section 4.2, [`super::FilteredSampler`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ImportanceMap {
    layout: Quadtree,
    masses: Vec<f64>,
}

impl ImportanceMap {
    /// The pyramid of the level-0 masses `level0`, given in RSM order (face, row, column) for
    /// `faces` maps of `resolution`² texels. Fails unless there is one finite, non-negative mass
    /// per texel.
    pub fn from_texels(resolution: u32, faces: u32, level0: &[f64]) -> Result<Self, VsglError> {
        let layout = Quadtree::new(resolution, faces);
        let n = layout.resolution();
        if level0.len() != (faces * n * n) as usize {
            return Err(VsglError::Importance(format!(
                "{} masses for {faces} faces of {n}² texels",
                level0.len()
            )));
        }
        if let Some(bad) = level0.iter().find(|m| !(m.is_finite() && **m >= 0.0)) {
            return Err(VsglError::Importance(format!(
                "mass {bad} is not finite and non-negative"
            )));
        }
        let mut masses = vec![0.0; layout.len()];
        for (k, &m) in level0.iter().enumerate() {
            let k = k as u32;
            let (face, y, x) = (k / (n * n), (k / n) % n, k % n);
            masses[layout.index(face, 0, x, y)] = m;
        }
        layout.fill_levels(&mut masses, &0.0, |a, b| *a += b);
        Ok(Self { layout, masses })
    }

    /// The paper's default `p(s) ∝ Φ_i (R_{d,i} + R_{s,i})` (VSGL section 4.2), the total of the
    /// RGB channels: the positional weight of [`ClusterSums`]. Fails for an invalid BRDF.
    pub fn flux(rsm: &Rsm) -> Result<Self, VsglError> {
        let level0 = rsm
            .texels
            .iter()
            .map(|t| match t {
                Some(t) => Ok(ClusterSums::from_texel(t, MeanMap::Toksvig)?.weight()),
                None => Ok(0.0),
            })
            .collect::<Result<Vec<_>, VsglError>>()?;
        Self::from_texels(rsm.resolution, rsm.faces, &level0)
    }

    /// [`ImportanceMap::flux`] read from the level-0 weights of an already built mipmap.
    pub fn from_mip(mip: &MipRsm) -> Self {
        let layout = mip.layout().clone();
        let mut masses = vec![0.0; layout.len()];
        let n = layout.resolution();
        for face in 0..layout.faces() {
            for y in 0..n {
                for x in 0..n {
                    masses[layout.index(face, 0, x, y)] = mip.sums(face, 0, x, y).weight();
                }
            }
        }
        layout.fill_levels(&mut masses, &0.0, |a, b| *a += b);
        Self { layout, masses }
    }

    /// The quadtree of the pyramids.
    pub fn layout(&self) -> &Quadtree {
        &self.layout
    }

    /// The mass of texel `(x, y)` of `level` of `face`. Panics out of range.
    pub fn mass(&self, face: u32, level: u32, x: u32, y: u32) -> f64 {
        self.masses[self.layout.index(face, level, x, y)]
    }

    /// The mass of a whole face (its 1×1 top level).
    pub fn face_mass(&self, face: u32) -> f64 {
        self.mass(face, self.layout.levels() - 1, 0, 0)
    }
}
