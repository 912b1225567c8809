//! The buffers of VSGL Fig. 4 for one cluster of VPLs, as sums over its texels.
use super::texel::TexelLobes;
use crate::rsm::RsmTexel;
use glam::DVec3;
use slc_bounds::sg::MeanMap;
use slc_bounds::{BoundsError, SphericalGaussian, ToksvigSum};

/// The sums over a cluster `S` of the buffers of VSGL Fig. 4, in `f64` (the variance
/// `Σw|x|²/Σw − |μ|²` cancels badly in `f32` for small clusters far from the origin):
///
/// - (a) diffuse weight `Σ Φ_i R_{d,i}` and (b) specular weight `Σ Φ_i R_{s,i}` (RGB);
/// - (c) diffuse lobe and (d) specular lobe: [`ToksvigSum`]s holding `Σ w_i ξ̄_i` and `Σ w_i`
///   with the scalar weight `w_i` the total of the RGB channels of (a) resp. (b) ("for
///   simplicity", Fig. 4), `ξ̄_i` the lobe's mean vector under the chosen [`MeanMap`];
/// - (e) weighted position `Σ w_i x_i` and (f) weighted squared norm `Σ w_i (|x_i|² + s_i²)`,
///   with `w_i` the total of the RGB channels of `Φ_i (R_{d,i} + R_{s,i})` (section 3.1.2) and
///   `s_i²` the variance of the surface patch texel `i` stands for ([`footprint_variance`]):
///   by the law of total variance, `σ_v²` is then the variance of the cluster's patches, not
///   only of its texel centres, and a single texel is a small area light rather than a point;
/// - (g) the specular-weighted normal `Σ w_{s,i} n_i` (not in the paper), whose direction with
///   the specular lobe's axis gives the plane of incidence of the lobe's stretch
///   ([`slc_bounds::sg::LobeStretch`]).
///
/// Every field is a plain sum, so clusters add ([`ClusterSums::merge`]) as mip levels do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClusterSums {
    /// (a) `Σ Φ_i R_{d,i}` per channel.
    pub diffuse_weight: DVec3,
    /// (b) `Σ Φ_i R_{s,i}` per channel.
    pub specular_weight: DVec3,
    /// (c) the Toksvig sum of the diffuse lobes, weighted by the totals of (a).
    pub diffuse_lobe: ToksvigSum,
    /// (d) the Toksvig sum of the specular lobes, weighted by the totals of (b).
    pub specular_lobe: ToksvigSum,
    /// (e) `Σ w_i x_i`.
    pub weighted_position: DVec3,
    /// (f) `Σ w_i |x_i|²`.
    pub weighted_squared_norm: f64,
    /// (g) `Σ w_{s,i} n_i`, `w_s` the totals of (b) and `n_i` the shading normal.
    pub specular_normal: DVec3,
}

impl ClusterSums {
    /// The empty cluster (every sum zero), whose lobe sums use `map`.
    pub fn empty(map: MeanMap) -> Self {
        Self {
            diffuse_weight: DVec3::ZERO,
            specular_weight: DVec3::ZERO,
            diffuse_lobe: ToksvigSum::new(map),
            specular_lobe: ToksvigSum::new(map),
            weighted_position: DVec3::ZERO,
            weighted_squared_norm: 0.0,
            specular_normal: DVec3::ZERO,
        }
    }

    /// The sums of one texel's VPL (a level-0 texel of the mipmap). Fails for an invalid BRDF
    /// or a lobe weight beyond the `f32` range.
    pub fn from_texel(texel: &RsmTexel, map: MeanMap) -> Result<Self, BoundsError> {
        let lobes = TexelLobes::new(texel)?;
        let diffuse_weight = (texel.flux * lobes.diffuse_reflectance).as_dvec3();
        let specular_weight = (texel.flux * lobes.specular_reflectance).as_dvec3();
        let mut sums = Self::empty(map);
        sums.diffuse_lobe
            .add(&weighted(lobes.diffuse_lobe, diffuse_weight.element_sum())?);
        sums.specular_lobe.add(&weighted(
            lobes.specular_lobe,
            specular_weight.element_sum(),
        )?);
        let w = (diffuse_weight + specular_weight).element_sum();
        let x = texel.position.as_dvec3();
        sums.diffuse_weight = diffuse_weight;
        sums.specular_weight = specular_weight;
        sums.weighted_position = w * x;
        sums.weighted_squared_norm = w * (x.length_squared() + footprint_variance(texel));
        sums.specular_normal = specular_weight.element_sum() * texel.normal.as_dvec3();
        Ok(sums)
    }

    /// Adds every VPL of `other` (made with the same map).
    pub fn merge(&mut self, other: &Self) {
        self.diffuse_weight += other.diffuse_weight;
        self.specular_weight += other.specular_weight;
        self.diffuse_lobe.merge(&other.diffuse_lobe);
        self.specular_lobe.merge(&other.specular_lobe);
        self.weighted_position += other.weighted_position;
        self.weighted_squared_norm += other.weighted_squared_norm;
        self.specular_normal += other.specular_normal;
    }

    /// The positional weight `Σ w_i`, the total of the RGB channels of (a) + (b).
    pub fn weight(&self) -> f64 {
        (self.diffuse_weight + self.specular_weight).element_sum()
    }
}

/// The smallest cosine of incidence of [`footprint_variance`]: a patch is stretched at most
/// 100 times (grazing texels would otherwise have an unbounded variance).
const MIN_FOOTPRINT_COS: f64 = 0.01;

/// The positional variance of the surface patch an RSM texel stands for: its beam's square
/// cross-section `a²` ([`RsmTexel::cross_section`]) meets the surface at the cosine
/// `c = |n_g · ω_i|` (at least `MIN_FOOTPRINT_COS`), a rectangle of sides `a` and `a/c`,
/// whose uniform distribution has the variance `(a² + a²/c²)/12` (the sum of `side²/12` over
/// its two axes).
pub fn footprint_variance(texel: &RsmTexel) -> f64 {
    let a2 = f64::from(texel.cross_section.max(0.0));
    let c = f64::from(texel.geometric_normal.dot(texel.omega_i).abs()).max(MIN_FOOTPRINT_COS);
    a2 * (1.0 + 1.0 / (c * c)) / 12.0
}

/// The normalized `lobe` scaled to integral `weight` (a zero weight adds nothing).
fn weighted(lobe: SphericalGaussian, weight: f64) -> Result<SphericalGaussian, BoundsError> {
    lobe.scaled(weight as f32)
}
