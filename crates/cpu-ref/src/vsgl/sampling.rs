//! Filtered importance sampling of texels and mip levels (VSGL section 4.2): hierarchical
//! sample warping down the quadtree of importance masses (Clarberg et al. 2005, "Wavelet
//! importance sampling", section 4.1) that stops at the level where the sample density matches
//! the cluster size.
use super::importance::ImportanceMap;
use slc_core::vsgl::ONE_BELOW;
pub use slc_core::vsgl::{point_shift, sample_points, SampleSet};

/// A cluster of the mipmapped RSMs (VSGL section 4.1): texel `(x, y)` of `level` of `face` of
/// the RSM `map` (the index of the map, one per light).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Cluster {
    pub map: u32,
    pub face: u32,
    pub level: u32,
    pub y: u32,
    pub x: u32,
}

/// A sampled cluster with its probability and Monte Carlo weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeightedCluster {
    pub cluster: Cluster,
    /// `P(C) = mass(C) / total`: the probability that one sample lands in the cluster.
    pub probability: f64,
    /// `m / (N P(C))` for a cluster hit by `m` of the `N` samples: the weight that makes the
    /// sum over the sampled clusters an unbiased estimate of the sum over all VPLs.
    pub weight: f64,
}

/// Where the warp of a sample stops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Footprint {
    /// At the mip level of VSGL section 4.2, `l = l_max − ½ log2(N p(s))`, with `p(s)` the
    /// importance density filtered over the cluster (its mass over its area) and the level
    /// rounded down: the coarsest cluster in which at most one of the `N` samples is expected
    /// (`N P(C) ≤ 1`), or level 0.
    ///
    /// With the filtered density the chosen clusters form a cut of the quadtree (every texel
    /// lies in exactly one of them, whichever texel the sample would have reached), which is
    /// what makes `1/(N P(C))` unbiased; the density of the single texel `s` gives clusters
    /// that overlap where the importance varies inside them and biases the total flux.
    Filtered,
    /// At level 0: importance sampling of single texels (VPLs), as Ritschel et al. 2011 resample
    /// VPLs from the RSM.
    Texel,
}

/// Samples clusters of one or more RSMs (all lights of a frame) in proportion to their
/// [`ImportanceMap`]s: a face is chosen by its mass, then the sample is warped down its
/// quadtree, at each level splitting first the columns, then the rows of the chosen column, by
/// their masses (hierarchical sample warping).
pub struct FilteredSampler<'a> {
    maps: &'a [ImportanceMap],
    /// (map, face, mass) of every face with a positive mass.
    faces: Vec<(u32, u32, f64)>,
    total: f64,
}

impl<'a> FilteredSampler<'a> {
    /// A sampler over every face of `maps`.
    pub fn new(maps: &'a [ImportanceMap]) -> Self {
        let faces: Vec<_> = maps
            .iter()
            .enumerate()
            .flat_map(|(m, map)| {
                (0..map.layout().faces()).map(move |f| (m as u32, f, map.face_mass(f)))
            })
            .filter(|&(_, _, mass)| mass > 0.0)
            .collect();
        let total = faces.iter().map(|f| f.2).sum();
        Self { maps, faces, total }
    }

    /// The total mass; 0 when nothing can be sampled.
    pub fn total(&self) -> f64 {
        self.total
    }

    /// The probability `P(C) = mass(C) / total` that one sample lands in `cluster`.
    pub fn probability(&self, c: &Cluster) -> f64 {
        let mass = self.maps[c.map as usize].mass(c.face, c.level, c.x, c.y);
        if self.total > 0.0 {
            mass / self.total
        } else {
            0.0
        }
    }

    /// The cluster the uniform point `u` warps to, and its probability, for a set of `count`
    /// samples; `None` when the total mass is 0.
    pub fn warp(&self, u: [f64; 2], count: u32, footprint: Footprint) -> Option<(Cluster, f64)> {
        let (map, face, face_mass, start) = self.choose_face(u[0] * self.total)?;
        let target = u[0] * self.total;
        let importance = &self.maps[map as usize];
        let layout = importance.layout();
        let mut ux = ((target - start) / face_mass).clamp(0.0, ONE_BELOW);
        let mut uy = u[1];
        let (mut level, mut x, mut y) = (layout.levels() - 1, 0, 0);
        loop {
            let probability = importance.mass(face, level, x, y) / self.total;
            let filtered_enough =
                footprint == Footprint::Filtered && f64::from(count) * probability <= 1.0;
            if level == 0 || filtered_enough {
                let cluster = Cluster {
                    map,
                    face,
                    level,
                    y,
                    x,
                };
                return Some((cluster, probability));
            }
            let size = layout.size(level - 1);
            let child = |cx: u32, cy: u32| {
                if cx < size && cy < size {
                    importance.mass(face, level - 1, cx, cy)
                } else {
                    0.0
                }
            };
            let (x0, y0) = (2 * x, 2 * y);
            let left = child(x0, y0) + child(x0, y0 + 1);
            let right = child(x0 + 1, y0) + child(x0 + 1, y0 + 1);
            let (i, next_ux) = split(ux, left, right);
            let (j, next_uy) = split(uy, child(x0 + i, y0), child(x0 + i, y0 + 1));
            (ux, uy) = (next_ux, next_uy);
            (level, x, y) = (level - 1, x0 + i, y0 + j);
        }
    }

    /// The face whose interval `[start, start + mass)` of the cumulative masses holds `target`,
    /// with its mass and start (the last face if rounding left `target` at the end).
    fn choose_face(&self, target: f64) -> Option<(u32, u32, f64, f64)> {
        let mut start = 0.0;
        for &(map, face, mass) in &self.faces {
            if target < start + mass {
                return Some((map, face, mass, start));
            }
            start += mass;
        }
        let &(map, face, mass) = self.faces.last()?;
        Some((map, face, mass, self.total - mass))
    }

    /// The clusters `points` warp to (`N = points.len()` samples), each once with weight
    /// `m / (N P(C))` for the `m` samples that reached it, sorted by [`Cluster`].
    pub fn sample(&self, points: &[[f64; 2]], footprint: Footprint) -> Vec<WeightedCluster> {
        let n = points.len() as u32;
        let mut hits: Vec<(Cluster, f64)> = points
            .iter()
            .filter_map(|&u| self.warp(u, n, footprint))
            .collect();
        hits.sort_by_key(|h| h.0);
        let mut out: Vec<WeightedCluster> = Vec::new();
        for (cluster, probability) in hits {
            match out.last_mut() {
                Some(last) if last.cluster == cluster => last.weight += 1.0,
                _ => out.push(WeightedCluster {
                    cluster,
                    probability,
                    weight: 1.0,
                }),
            }
        }
        for c in &mut out {
            c.weight /= f64::from(n) * c.probability;
        }
        out
    }
}

/// Chooses between two branches of masses `a` and `b` (not both 0) with the uniform `u`:
/// the first with probability `a / (a + b)`, never a branch of mass 0, and `u` rescaled to
/// a uniform number on the chosen branch's interval.
fn split(u: f64, a: f64, b: f64) -> (u32, f64) {
    if b <= 0.0 {
        return (0, u);
    }
    if a <= 0.0 {
        return (1, u);
    }
    let p = a / (a + b);
    if u < p {
        (0, (u / p).min(ONE_BELOW))
    } else {
        (1, ((u - p) / (1.0 - p)).clamp(0.0, ONE_BELOW))
    }
}
