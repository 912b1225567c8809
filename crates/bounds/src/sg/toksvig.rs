//! Toksvig filtering of spherical Gaussian lobes through their mean vectors (VSGL section
//! 3.1.1): lobe → mean vector, weighted average, mean vector → lobe.
use crate::check;
use crate::error::BoundsError;
use crate::sg::integral::integral_f64;
use crate::sg::lobe::SphericalGaussian;
use glam::{DVec3, Vec3};

/// The largest mean-vector length accepted by the inverse maps, the largest `f32` below 1
/// (`1 − 2⁻²⁴`); longer vectors (only by rounding: every lobe's mean is shorter than 1) are
/// clamped to it. It bounds the sharpness at `r/(1 − r) ≈ 1.7e7`.
const MAX_MEAN_LENGTH: f32 = 1.0 - f32::EPSILON / 2.0;

/// The paper's mean-vector length of a normalized lobe, `|ξ̄| = λ/(λ + 1)` (VSGL section 3.1.1,
/// Toksvig's filtering). An approximation of [`exact_mean_length`]: equal to it up to
/// `O(1/λ²)` for sharp lobes (both are `1 − 1/λ + O(1/λ²)`), but `λ` instead of `λ/3` for
/// broad ones. Negative or NaN sharpness is treated as 0.
#[inline]
pub fn toksvig_mean_length(sharpness: f32) -> f32 {
    let l = sharpness.max(0.0);
    l / (l + 1.0)
}

/// The inverse of [`toksvig_mean_length`], `λ = r/(1 − r)` (VSGL section 3.1.1). `r` is clamped
/// to `[0, 1 − 2⁻²⁴]` (NaN to 0): r → 0 gives λ → 0, a uniform lobe; r → 1 at most λ ≈ 1.7e7.
#[inline]
pub fn toksvig_sharpness(mean_length: f32) -> f32 {
    let r = clamp_length(mean_length);
    r / (1.0 - r)
}

/// The exact mean-vector length of a normalized lobe, `|∫ ω G(ω; ξ, λ)/A(λ) dω| = coth λ − 1/λ`
/// (the Langevin function; derived from `∫_{−1}^{1} z e^{λ(z−1)} dz / ∫_{−1}^{1} e^{λ(z−1)} dz`),
/// evaluated in `f64` with its series `λ/3 − λ³/45` below λ = 1e-3. Negative or NaN sharpness
/// is treated as 0.
#[inline]
pub fn exact_mean_length(sharpness: f32) -> f32 {
    langevin(f64::from(sharpness.max(0.0))) as f32
}

/// The inverse of [`exact_mean_length`]: the sharpness of the normalized lobe whose mean
/// vector has length `r` (clamped like [`toksvig_sharpness`]). Newton's method in `f64` from
/// the approximation `r(3 − r²)/(1 − r²)` of Banerjee et al. 2005 ("Clustering on the unit
/// hypersphere using von Mises-Fisher distributions", JMLR 6, eq. 4.4), to full precision.
pub fn exact_sharpness(mean_length: f32) -> f32 {
    let r = f64::from(clamp_length(mean_length));
    let mut l = r * (3.0 - r * r) / (1.0 - r * r);
    for _ in 0..50 {
        // The Langevin function is increasing and concave: after one step the iterates rise
        // monotonically to the root; the floor keeps a first overshoot positive.
        let next = (l - (langevin(l) - r) / langevin_slope(l)).max(0.1 * l);
        let done = (next - l).abs() <= 1e-14 * next;
        l = next;
        if done {
            break;
        }
    }
    l as f32
}

/// `r` clamped to `[0, MAX_MEAN_LENGTH]`, NaN to 0.
fn clamp_length(r: f32) -> f32 {
    if r > 0.0 {
        r.min(MAX_MEAN_LENGTH)
    } else {
        0.0
    }
}

/// `coth λ − 1/λ`, with its series below 1e-3 where the difference cancels; above λ = 20,
/// `coth λ = 1 + 2e^{−2λ} + …` is 1 to `f64` precision.
pub(crate) fn langevin(l: f64) -> f64 {
    if l < 1e-3 {
        l / 3.0 - l * l * l / 45.0
    } else if l > 20.0 {
        1.0 - 1.0 / l
    } else {
        1.0 / l.tanh() - 1.0 / l
    }
}

/// The derivative `1/λ² − 1/sinh² λ` of [`langevin`], with its series below 1e-3.
fn langevin_slope(l: f64) -> f64 {
    if l < 1e-3 {
        1.0 / 3.0 - l * l / 15.0
    } else {
        1.0 / (l * l) - 1.0 / l.sinh().powi(2)
    }
}

/// Which mean-vector length a [`ToksvigSum`] uses for a lobe of sharpness λ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MeanMap {
    /// The paper's `λ/(λ + 1)` and its inverse `r/(1 − r)` (VSGL section 3.1.1).
    #[default]
    Toksvig,
    /// The exact `coth λ − 1/λ` and its inverse: the filtered lobe keeps the mixture's mean.
    Exact,
}

impl MeanMap {
    /// The mean-vector length of a normalized lobe of this sharpness.
    #[inline]
    pub fn length(self, sharpness: f32) -> f32 {
        match self {
            Self::Toksvig => toksvig_mean_length(sharpness),
            Self::Exact => exact_mean_length(sharpness),
        }
    }

    /// The sharpness of the normalized lobe with this mean-vector length.
    #[inline]
    pub fn sharpness(self, mean_length: f32) -> f32 {
        match self {
            Self::Toksvig => toksvig_sharpness(mean_length),
            Self::Exact => exact_sharpness(mean_length),
        }
    }
}

impl SphericalGaussian {
    /// The mean vector `ξ̄ = λ/(λ + 1) ξ` of the normalized lobe, the paper's Toksvig form
    /// (VSGL section 3.1.1); the amplitude plays no part.
    #[inline]
    pub fn mean_vector(&self) -> Vec3 {
        self.axis * toksvig_mean_length(self.sharpness)
    }

    /// The exact mean vector `∫ ω G/A dω = (coth λ − 1/λ) ξ` of the normalized lobe.
    #[inline]
    pub fn exact_mean_vector(&self) -> Vec3 {
        self.axis * exact_mean_length(self.sharpness)
    }
}

/// A running Toksvig filter of lobes (VSGL section 3.1.1): each lobe `c_i G(ω; ξ_i, λ_i)` is
/// weighted by its integral `c_i A(λ_i)` (the paper's `Φ_i R_i`), its mean vector is averaged
/// with that weight, and [`ToksvigSum::to_lobe`] turns the average back into one lobe with the
/// same total integral. Sums merge, as mipmap levels do. Accumulated in `f64`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToksvigSum {
    map: MeanMap,
    weighted_mean: DVec3,
    weight: f64,
}

impl ToksvigSum {
    /// An empty sum using the given mean-vector map.
    pub fn new(map: MeanMap) -> Self {
        Self {
            map,
            ..Self::default()
        }
    }

    /// Adds a lobe with weight `c A(λ)`.
    pub fn add(&mut self, lobe: &SphericalGaussian) {
        let weight = f64::from(lobe.amplitude) * integral_f64(f64::from(lobe.sharpness));
        let mean = f64::from(self.map.length(lobe.sharpness));
        self.weighted_mean += lobe.axis.as_dvec3() * (weight * mean);
        self.weight += weight;
    }

    /// Adds every lobe of another sum (made with the same map).
    pub fn merge(&mut self, other: &Self) {
        self.weighted_mean += other.weighted_mean;
        self.weight += other.weight;
    }

    /// The total weight `Σ c_i A(λ_i)`.
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// The mean-vector map the sum was made with.
    pub fn map(&self) -> MeanMap {
        self.map
    }

    /// The weighted average mean vector `ξ̄_v = Σ w_i ξ̄_i / Σ w_i`; zero for an empty sum.
    pub fn mean_vector(&self) -> Vec3 {
        if self.weight > 0.0 {
            (self.weighted_mean / self.weight).as_vec3()
        } else {
            Vec3::ZERO
        }
    }

    /// The filtered lobe: axis `ξ̄_v/|ξ̄_v|`, sharpness from `|ξ̄_v|` by the map's inverse
    /// (`λ_v = |ξ̄_v|/(1 − |ξ̄_v|)` for the paper's) and amplitude `c_v = Σ w_i / A(λ_v)`.
    /// A zero mean vector gives a uniform lobe (λ = 0) about +z; an empty sum a zero lobe.
    /// Fails with [`BoundsError::Overflow`] if `c_v` exceeds the `f32` range.
    pub fn to_lobe(&self) -> Result<SphericalGaussian, BoundsError> {
        let mean = if self.weight > 0.0 {
            self.weighted_mean / self.weight
        } else {
            DVec3::ZERO
        };
        let r = mean.length();
        let axis = if r > 0.0 {
            (mean / r).as_vec3().normalize()
        } else {
            Vec3::Z
        };
        let sharpness = self.map.sharpness(r as f32);
        let amplitude = check::fits(
            self.weight / integral_f64(f64::from(sharpness)),
            "filtered SG amplitude",
        )?;
        Ok(SphericalGaussian {
            axis,
            sharpness,
            amplitude,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sg::quadrature::{eval64, sphere_integral, width};
    use crate::test_util::{log_angles, Rng};

    /// `∫ ω G(ω)/A dω` by quadrature.
    fn numeric_mean(sg: &SphericalGaussian) -> DVec3 {
        let w = width(f64::from(sg.sharpness));
        let axis = sg.axis.as_dvec3();
        let total = sphere_integral(axis, w, |v| eval64(sg, v));
        DVec3::new(
            sphere_integral(axis, w, |v| v.x * eval64(sg, v)),
            sphere_integral(axis, w, |v| v.y * eval64(sg, v)),
            sphere_integral(axis, w, |v| v.z * eval64(sg, v)),
        ) / total
    }

    #[test]
    fn exact_mean_matches_quadrature_and_paper_form_is_its_sharp_limit() {
        let mut report = Vec::new();
        for l in log_angles(1e-3, 1e4, 15) {
            let sg = SphericalGaussian::new(Vec3::new(0.6, 0.0, 0.8), l as f32, 1.0).unwrap();
            let numeric = numeric_mean(&sg);
            let exact = sg.exact_mean_vector().as_dvec3();
            assert!(
                (numeric - exact).length() <= 1e-5 * exact.length(),
                "λ {l}: {numeric} vs {exact}"
            );
            // The paper's λ/(λ+1) vs the exact length, relative error measured 2.0 (3x too long) at λ = 1e-3, 0.60 at λ = 1, 0.105 at λ = 3.2,
            // 1.0e-2 at λ = 10, 1.0e-4 at λ = 100, 1.0e-6 at λ = 1000: the paper approximates the sharp-lobe limit.
            let paper = f64::from(toksvig_mean_length(l as f32));
            let rel = paper / exact.length() - 1.0;
            let asymptotic = 1.0 / (l * (l + 1.0)); // 1/λ − 1/(λ+1), the O(1/λ²) gap
            if l >= 10.0 {
                assert!(
                    (rel - asymptotic).abs() < 0.1 * asymptotic + 1e-6,
                    "λ {l}: {rel}"
                );
            }
            report.push((l, rel));
        }
        assert!((report[0].1 - 2.0).abs() < 1e-2, "λ → 0: ratio 3");
        assert!(report.windows(2).all(|p| p[1].1 < p[0].1), "{report:?}");
    }

    #[test]
    fn inverse_maps_round_trip() {
        for l in log_angles(1e-4, 1e6, 41) {
            let l = l as f32;
            let t = toksvig_sharpness(toksvig_mean_length(l));
            let e = exact_sharpness(exact_mean_length(l));
            // f32 lengths near 1 resolve λ only to λ² · 6e-8.
            let tol = 1e-5 + 1.2e-7 * l;
            assert!((t / l - 1.0).abs() < tol, "λ {l}: {t}");
            assert!((e / l - 1.0).abs() < tol, "λ {l}: {e}");
        }
        for r in [0.0, -1.0, f32::NAN] {
            assert_eq!(toksvig_sharpness(r), 0.0);
            assert_eq!(exact_sharpness(r), 0.0);
        }
        for r in [1.0, 2.0, f32::INFINITY] {
            assert!((toksvig_sharpness(r) - 1.6777215e7).abs() < 2.0, "{r}");
            assert!(exact_sharpness(r).is_finite() && exact_sharpness(r) > 1e7);
        }
        assert_eq!(toksvig_mean_length(f32::MAX), 1.0);
        assert_eq!(exact_mean_length(f32::MAX), 1.0);
        assert_eq!(exact_mean_length(0.0), 0.0);
    }

    #[test]
    fn filtering_one_lobe_returns_it() {
        for map in [MeanMap::Toksvig, MeanMap::Exact] {
            for l in [0.01f32, 1.0, 30.0, 1e4] {
                let sg = SphericalGaussian::new(Vec3::new(0.0, -0.6, 0.8), l, 2.5).unwrap();
                let mut sum = ToksvigSum::new(map);
                sum.add(&sg);
                sum.add(&sg.scaled(3.0).unwrap());
                let f = sum.to_lobe().unwrap();
                assert!((f.axis - sg.axis).length() < 1e-6);
                assert!(
                    (f.sharpness / l - 1.0).abs() < 1e-4 + 1.2e-7 * l,
                    "{map:?} {l}: {f:?}"
                );
                assert!((f.integral() / (4.0 * sg.integral()) - 1.0).abs() < 1e-4);
            }
        }
    }

    #[test]
    fn exact_map_keeps_the_mixture_mean_and_total() {
        let mut rng = Rng::new(61);
        let (mut worst_exact, mut worst_paper) = (0.0f64, 0.0f64);
        for _ in 0..6 {
            let lobes: Vec<_> = (0..4)
                .map(|_| {
                    let axis = (Vec3::Z + 0.5 * rng.unit()).normalize();
                    SphericalGaussian::new(axis, rng.range(1.0, 50.0), rng.f32()).unwrap()
                })
                .collect();
            let (mut exact, mut paper, mut half) = (
                ToksvigSum::new(MeanMap::Exact),
                ToksvigSum::new(MeanMap::Toksvig),
                ToksvigSum::new(MeanMap::Exact),
            );
            lobes.iter().for_each(|g| exact.add(g));
            lobes.iter().for_each(|g| paper.add(g));
            lobes[..2].iter().for_each(|g| half.add(g));
            let mut rest = ToksvigSum::new(MeanMap::Exact);
            lobes[2..].iter().for_each(|g| rest.add(g));
            half.merge(&rest);
            assert!((half.mean_vector() - exact.mean_vector()).length() < 1e-6);
            // The first moment of the mixture Σ c_i G_i, by quadrature.
            let total: f64 = lobes.iter().map(|g| f64::from(g.integral())).sum();
            let moment: DVec3 = lobes
                .iter()
                .map(|g| numeric_mean(g) * f64::from(g.integral()))
                .sum();
            let target = moment / total;
            for (sum, worst) in [(&exact, &mut worst_exact), (&paper, &mut worst_paper)] {
                let f = sum.to_lobe().unwrap();
                assert!((f64::from(f.integral()) / total - 1.0).abs() < 1e-5);
                let got = numeric_mean(&f);
                *worst = worst.max((got - target).length() / target.length());
            }
        }
        // Measured: 6.6e-8 with the exact map; 3.0e-2 with the paper's.
        assert!(worst_exact < 1e-5, "{worst_exact}");
        assert!(worst_paper > 1e-3 && worst_paper < 0.1, "{worst_paper}");
    }

    #[test]
    fn empty_and_cancelling_sums() {
        let empty = ToksvigSum::new(MeanMap::Toksvig);
        assert_eq!(empty.mean_vector(), Vec3::ZERO);
        let lobe = empty.to_lobe().unwrap();
        assert_eq!((lobe.sharpness, lobe.amplitude), (0.0, 0.0));
        let mut sum = ToksvigSum::default();
        let g = SphericalGaussian::new(Vec3::X, 5.0, 1.0).unwrap();
        sum.add(&g);
        sum.add(&SphericalGaussian {
            axis: -Vec3::X,
            ..g
        });
        let u = sum.to_lobe().unwrap();
        assert!(u.sharpness < 1e-6 && u.axis.is_finite());
        assert!((u.integral() / (2.0 * g.integral()) - 1.0).abs() < 1e-5);
        assert!((sum.weight() / f64::from(2.0 * g.integral()) - 1.0).abs() < 1e-6);
        let mut bright = ToksvigSum::default();
        let big = SphericalGaussian::new(Vec3::X, 0.0, f32::MAX).unwrap();
        bright.add(&big);
        bright.add(&SphericalGaussian {
            axis: -Vec3::X,
            ..big
        });
        assert_eq!(
            bright.to_lobe(),
            Err(BoundsError::Overflow("filtered SG amplitude"))
        );
    }
}
