//! The fit of one spherical Gaussian to the reflected GGX lobe `ρ_s(ωo, ω) ⟨ω, n⟩` (with
//! `F = 1`) by its peak and its integral, computed by quadrature ([`fit_lobe`]); tabulated over
//! α and the view angle in `specular_table.rs` (written by `cargo run -p slc-bounds --example
//! specular_table`) and looked up by [`SpecularFit::lookup`] for [`crate::sg::SpecularLobeSg`].
//!
//! Why the peak: GGX's tails are heavy, so a fit of the mean vector (the lobe's first moment,
//! as Toksvig filtering would) comes out 3-7x broader than the lobe's core; the SG through
//! the true peak, with the sharpness that gives it the true integral, follows the core and
//! the energy, and bends towards the normal where the true lobe does (at α = 1 its peak is the
//! normal for every view).
use crate::ggx::{d_f64, g1_f64};
use crate::sg::integral::integral_f64;
use crate::sg::specular_table::TABLE;
use core::f64::consts::{FRAC_PI_2, PI};

/// Rows of the table: α from 0 to 1 in steps of 1/16.
pub const ALPHA_STEPS: usize = 17;
/// Columns of the table: `√(1 − cos θo)` from 0 to 1 in steps of 1/32 (about 2.5° near the
/// normal, 3.6° at grazing views).
pub const VIEW_STEPS: usize = 33;
/// The α of the table's first row, which stands for α → 0 (the lobe's shape scales with α
/// there, except at views within a few α of grazing, where the row is its value at α = 1/1024).
pub const TABLE_MIN_ALPHA: f64 = 1.0 / 1024.0;
/// The view cosine of the table's last column (a grazing view): more grazing views are fitted
/// as this one.
pub const TABLE_MIN_COS: f64 = 1e-6;

/// Panels of the composite Gauss-Legendre rule in θh, for each of its two pieces, and the
/// midpoints in φ over half the circle.
const QUADRATURE_PANELS: usize = 64;
const QUADRATURE_PHI: usize = 256;
/// Nodes and weights of the 4-point Gauss-Legendre rule on [-1, 1] (also the tests' sphere
/// quadrature's).
pub(crate) const GAUSS: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
];
/// Steps of the peak search per unit of `tan θh / α` and its span in these units.
const PEAK_STEPS_PER_ALPHA: f64 = 64.0;
const PEAK_SPAN_ALPHAS: f64 = 24.0;

/// One SG `amplitude · G(ω; axis, λ)` fitted to the GGX specular lobe seen from a view at polar
/// angle θo: its axis lies in the plane of the normal and the view, at the lobe's peak,
/// `normalize(w r + (1 − w) n)` with `w = mirror_weight` and the mirror direction r;
/// `integral` is the true lobe's `∫ ρ_s ⟨ω, n⟩ dω` with `F = 1` (the directional albedo of the
/// specular term, the SG's amplitude being `integral / A(λ)`), `fresnel_cos` where to evaluate
/// Fresnel, and `scaled_sharpness = λ α² (cos θo + α)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpecularFit {
    /// The weight of the mirror direction r in the peak's direction `w r + (1 − w) n`: 1 for
    /// smooth lobes (the peak is the mirror direction), 0 where the peak is the normal (α = 1).
    /// A blend of the two directions keeps the axis as well conditioned as r itself (an angle
    /// or a tangent would need inverse trigonometry, and a tangent is noise at normal views).
    pub mirror_weight: f64,
    /// `λ α² (cos θo + α)`: about 1/2 for smooth lobes at every view (λ ≈ 1/(2α² cos θo) while
    /// `cos θo ≫ α`, ≈ 0.64/α³ at grazing views, `cos θo ≪ α`), so the table's cells need not
    /// resolve the change between the two regimes, which happens at `cos θo ~ α`.
    pub scaled_sharpness: f64,
    /// `∫ ρ_s(ωo, ω) ⟨ω, n⟩ dω` with `F = 1`.
    pub integral: f64,
    /// The cosine `x` at which Schlick's Fresnel equals its mean over the lobe:
    /// `(1 − x)⁵ = ∫ (1 − ⟨ωo, h⟩)⁵ ρ_s ⟨ω, n⟩ dω / integral`, so that `F(x) · integral` is the
    /// lobe's integral with Schlick's `F(⟨ωo, h⟩)` for every F0 (the dielectric's exact Fresnel
    /// is evaluated at the same cosine).
    pub fresnel_cos: f64,
}

impl SpecularFit {
    /// The SG's sharpness λ for roughness α (`cos θo` floored at [`TABLE_MIN_COS`]).
    pub fn sharpness(&self, alpha: f64, cos_o: f64) -> f64 {
        self.scaled_sharpness / alpha / alpha / (cos_o.max(TABLE_MIN_COS) + alpha)
    }

    /// The fit for α in (0, 1] and `cos θo` in [0, 1], bilinear in the table's cells (α in steps
    /// of 1/16 from α → 0; `√(1 − cos θo)` in steps of 1/32). Values outside are clamped to the table.
    pub fn lookup(alpha: f64, cos_o: f64) -> Self {
        let a = (alpha.clamp(0.0, 1.0) * (ALPHA_STEPS - 1) as f64).min((ALPHA_STEPS - 1) as f64);
        let i = cell(a, ALPHA_STEPS);
        let fa = a - i as f64;
        // The column coordinate t = 32 √(1 − c) and its distance from the grazing end,
        // r = 32 − t = 32 c / (1 + √(1 − c)): the weights of a cell's nodes are t − j and
        // r − (31 − j), so that near grazing views, where the last cell's nodes differ by
        // orders of magnitude, the weight of the far node is not a difference of nearly equal
        // numbers (the GPU's f32 lookup does the same).
        let last = (VIEW_STEPS - 1) as f64;
        let c = cos_o.clamp(0.0, 1.0);
        let r = last * c / (1.0 + (1.0 - c).sqrt());
        let t = last - r;
        let j = cell(t, VIEW_STEPS);
        let (w_hi, w_lo) = (t - j as f64, r - (VIEW_STEPS - 2 - j) as f64);
        let at = |i: usize, j: usize| TABLE[i * VIEW_STEPS + j].map(f64::from);
        let (e00, e01, e10, e11) = (at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
        let mix = |k: usize| {
            let lo = e00[k] * w_lo + e01[k] * w_hi;
            let hi = e10[k] * w_lo + e11[k] * w_hi;
            lo * (1.0 - fa) + hi * fa
        };
        Self {
            mirror_weight: mix(0),
            scaled_sharpness: mix(1),
            integral: mix(2),
            fresnel_cos: mix(3),
        }
    }
}

/// The α and `cos θo` of the table's node at row `i` and column `j`: α = i/16 (the first row at
/// [`TABLE_MIN_ALPHA`]) and `cos θo = 1 − (j/32)²` (the last column at [`TABLE_MIN_COS`]).
pub fn table_node(i: usize, j: usize) -> (f64, f64) {
    let alpha = if i == 0 {
        TABLE_MIN_ALPHA
    } else {
        i as f64 / (ALPHA_STEPS - 1) as f64
    };
    let x = j as f64 / (VIEW_STEPS - 1) as f64;
    (alpha, (1.0 - x * x).max(TABLE_MIN_COS))
}

/// The lower node of the cell holding grid coordinate `x` in a grid of `steps` nodes.
fn cell(x: f64, steps: usize) -> usize {
    (x.floor().max(0.0) as usize).min(steps - 2)
}

/// The fit at α in (0, 1] and `cos θo` in (0, 1] by quadrature (the generator of the table;
/// about 0.13 M evaluations of the lobe).
///
/// The integral over half vectors: with `ω = 2⟨ωo, h⟩h − ωo` and `dω = 4⟨ωo, h⟩ dh`,
/// `∫ D G1(ω) G1(ωo) / (4 cos θo) dω = ∫ D(h) G1(ω) G1(ωo) ⟨ωo, h⟩ / cos θo dh`, composite
/// Gauss-Legendre in θh on `[0, 12α]` and the rest (the core and the tail, where microfacets
/// facing a grazing view still reflect) and the midpoint rule in φ. The peak: the lobe is
/// symmetric about the plane of n and ωo, so it lies in it; a scan of half-vector angles in
/// steps of α/64 (in `tan θh`), refined by golden section. λ solves `f_peak A(λ) = integral`
/// (0 for a lobe too flat for any SG of its peak).
pub fn fit_lobe(alpha: f64, cos_o: f64) -> SpecularFit {
    let (integral, schlick) = moments(alpha, cos_o);
    let theta_o = cos_o.acos();
    let (peak_angle, peak_value) = peak(alpha, theta_o);
    // The weight is a ratio of angles near the normal: there it is taken at θo = 1e-3.
    let mirror_weight = if theta_o < 1e-3 {
        let (angle, _) = peak(alpha, 1e-3);
        mirror_weight(angle, 1e-3)
    } else {
        mirror_weight(peak_angle, theta_o)
    };
    let sharpness = sharpness_of_integral(integral / peak_value);
    SpecularFit {
        mirror_weight,
        scaled_sharpness: sharpness * alpha * alpha * (cos_o + alpha),
        integral,
        fresnel_cos: 1.0 - (schlick / integral).powf(0.2),
    }
}

/// The weight w with `w r + (1 − w) n` at polar angle `peak_angle` towards the mirror direction
/// `r` at polar angle `theta_o`: `w = tan θp / (sin θo + tan θp (1 − cos θo))`.
fn mirror_weight(peak_angle: f64, theta_o: f64) -> f64 {
    let t = peak_angle.tan();
    t / (theta_o.sin() + t * (1.0 - theta_o.cos()))
}

/// The lobe's integral with `F = 1` and with Schlick's `(1 − ⟨ωo, h⟩)⁵` (see [`fit_lobe`]).
fn moments(alpha: f64, cos_o: f64) -> (f64, f64) {
    let a2 = alpha * alpha;
    let sin_o = (1.0 - cos_o * cos_o).max(0.0).sqrt();
    let g1_o = g1_f64(a2, cos_o);
    let (mut integral, mut schlick) = (0.0, 0.0);
    let split = (12.0 * alpha).min(FRAC_PI_2);
    for (lo, hi) in [(0.0, split), (split, FRAC_PI_2)] {
        let panel = (hi - lo) / QUADRATURE_PANELS as f64;
        for p in 0..QUADRATURE_PANELS {
            for (node, weight) in GAUSS {
                let theta_h = lo + (p as f64 + 0.5 + 0.5 * node) * panel;
                let (sin_h, cos_h) = theta_h.sin_cos();
                let d = d_f64(a2, cos_h, sin_h * sin_h);
                // Symmetric about the plane of n and ωo: φ in [0, π], doubled.
                let ring_weight =
                    d * sin_h * weight * 0.5 * panel * 2.0 * PI / QUADRATURE_PHI as f64;
                for j in 0..QUADRATURE_PHI {
                    let phi = PI * (j as f64 + 0.5) / QUADRATURE_PHI as f64;
                    let oh = sin_o * sin_h * phi.cos() + cos_o * cos_h;
                    let cos_i = 2.0 * oh * cos_h - cos_o;
                    if oh > 0.0 && cos_i > 0.0 {
                        let f = ring_weight * g1_f64(a2, cos_i) * g1_o * oh / cos_o;
                        integral += f;
                        schlick += f * (1.0 - oh).powi(5);
                    }
                }
            }
        }
    }
    (integral, schlick)
}

/// The lobe's peak in the plane of n and ωo: its polar angle towards the mirror direction (in
/// [0, π/2)) and its value (see [`fit_lobe`]).
fn peak(alpha: f64, theta_o: f64) -> (f64, f64) {
    let a2 = alpha * alpha;
    let cos_o = theta_o.cos();
    let g1_o = g1_f64(a2, cos_o);
    // The half vector at signed angle s from n, ω at 2s − θo.
    let value = |s: f64| {
        let t = 2.0 * s - theta_o;
        if t.abs() >= FRAC_PI_2 || s.cos() <= 0.0 {
            return 0.0;
        }
        let cos_h = s.cos();
        let d = d_f64(a2, cos_h, s.sin().powi(2));
        d * g1_f64(a2, t.cos()) * g1_o / (4.0 * cos_o)
    };
    let step = alpha / PEAK_STEPS_PER_ALPHA;
    let steps = (PEAK_SPAN_ALPHAS * PEAK_STEPS_PER_ALPHA) as i64;
    let (mut best, mut best_s) = (0.0, 0.0);
    for k in -steps..=steps {
        let s = (k as f64 * step).atan();
        let v = value(s);
        if v > best {
            (best, best_s) = (v, s);
        }
    }
    let (mut lo, mut hi) = ((best_s.tan() - step).atan(), (best_s.tan() + step).atan());
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (x1, x2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
        if value(x1) < value(x2) {
            lo = x1;
        } else {
            hi = x2;
        }
    }
    let s = 0.5 * (lo + hi);
    (
        (theta_o - 2.0 * s).clamp(0.0, FRAC_PI_2 - 1e-9),
        value(s).max(best),
    )
}

/// The λ with `A(λ) = ratio` (A falls from 4π at λ = 0): bisection in log λ; 0 where the ratio
/// is at least 4π.
fn sharpness_of_integral(ratio: f64) -> f64 {
    if ratio >= 4.0 * PI {
        return 0.0;
    }
    let (mut lo, mut hi) = (1e-9f64, 1e12f64);
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if integral_f64(mid) > ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo * hi).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sg::quadrature::sphere_integral;

    fn values(f: &SpecularFit) -> [f64; 4] {
        [
            f.mirror_weight,
            f.scaled_sharpness,
            f.integral,
            f.fresnel_cos,
        ]
    }

    /// The committed table is the generator's output (regenerate with the example otherwise),
    /// within 1e-5 relative and 1e-6 absolute: the peak search ends in rounding noise where the
    /// maximum is flat (α = 1), which another libm may round differently.
    #[test]
    fn table_is_the_fit() {
        for (i, j) in [
            (0, 0),
            (0, 31),
            (1, 9),
            (5, 16),
            (10, 3),
            (16, 0),
            (16, 32),
            (13, 32),
        ] {
            let (alpha, cos_o) = table_node(i, j);
            let fit = values(&fit_lobe(alpha, cos_o));
            let table = TABLE[i * VIEW_STEPS + j];
            for k in 0..4 {
                let err = (fit[k] - f64::from(table[k])).abs();
                assert!(
                    err <= 1e-5 * fit[k].abs() + 1e-6,
                    "{i} {j} {k}: {fit:?} {table:?}"
                );
            }
        }
    }

    /// The fit's integral and Fresnel cosine against the true lobe integrated over the sphere
    /// (an independent quadrature in ω), with Schlick's Fresnel for F0 = 0.04 and 0.9.
    #[test]
    fn integral_and_fresnel_match_quadrature() {
        for alpha in [0.05f64, 0.3, 1.0] {
            for view in [0.0f64, 45.0, 75.0, 88.0] {
                let c = view.to_radians().cos();
                let wo = glam::DVec3::new((1.0 - c * c).sqrt(), 0.0, c);
                let mirror = glam::DVec3::new(-wo.x, 0.0, c);
                let fit = fit_lobe(alpha, c);
                for f0 in [0.04, 0.9] {
                    let truth = sphere_integral(mirror, alpha.min(1.0), |wi| {
                        if wi.z <= 0.0 {
                            return 0.0;
                        }
                        let h = (wi + wo).normalize();
                        let a2 = alpha * alpha;
                        let d = d_f64(a2, h.z, 1.0 - h.z * h.z);
                        let f = f0 + (1.0 - f0) * (1.0 - wo.dot(h)).powi(5);
                        f * d * g1_f64(a2, wi.z) * g1_f64(a2, c) / (4.0 * c)
                    });
                    let schlick = f0 + (1.0 - f0) * (1.0 - fit.fresnel_cos).powi(5);
                    let got = schlick * fit.integral;
                    // Measured: within 1.6e-4 relative (α 0.05 at 88°), 1e-6 below 75°.
                    assert!(
                        (got / truth - 1.0).abs() < 1e-3,
                        "α {alpha} {view}° F0 {f0}: {got} {truth}"
                    );
                }
            }
        }
    }

    /// Between the nodes the lookup stays near the fit: the integral within 1.5 %, the mirror
    /// weight within 0.015, the sharpness within 1.5 % and Fresnel's cosine within 0.02 (near
    /// normal views of smooth lobes, where `(1 − x)⁵` is below 1e-8); at views beyond 85° of
    /// lobes smoother than α = 1/8 (α down to 0.001), where the true lobe changes on the scale
    /// of `cos θo ~ α`, the integral within 6 % and the sharpness within 25 %.
    #[test]
    fn lookup_between_nodes_follows_the_fit() {
        let (mut worst, mut worst_grazing) = ([0.0f64; 4], [0.0f64; 4]);
        for alpha in [0.001f64, 0.02, 0.07, 0.28, 0.53, 0.97] {
            for view in [2.5f64, 42.5, 77.5, 87.5, 89.5] {
                let c = view.to_radians().cos();
                let (fit, got) = (fit_lobe(alpha, c), SpecularFit::lookup(alpha, c));
                let errs = [
                    (got.integral / fit.integral - 1.0).abs(),
                    (got.mirror_weight - fit.mirror_weight).abs(),
                    (got.sharpness(alpha, c) / fit.sharpness(alpha, c) - 1.0).abs(),
                    (got.fresnel_cos - fit.fresnel_cos).abs(),
                ];
                let w = if view > 85.0 && alpha < 0.125 {
                    &mut worst_grazing
                } else {
                    &mut worst
                };
                for k in 0..4 {
                    w[k] = w[k].max(errs[k]);
                }
            }
        }
        // Measured: [0.0108, 0.0086, 0.0071, 0.0154] and at grazing [0.048, -, 0.185, -].
        assert!(
            worst[0] < 0.015 && worst[1] < 0.015 && worst[2] < 0.015 && worst[3] < 0.02,
            "{worst:?}"
        );
        assert!(
            worst_grazing[0] < 0.06 && worst_grazing[2] < 0.25,
            "{worst_grazing:?}"
        );
    }

    #[test]
    fn lookup_clamps_and_stays_finite() {
        for alpha in [0.0, 1e-9, 0.5, 1.0, 2.0] {
            for c in [-1.0, 0.0, 1e-7, 0.5, 1.0, 1.5] {
                let f = SpecularFit::lookup(alpha, c);
                assert!(
                    values(&f).iter().all(|v| v.is_finite() && *v >= 0.0),
                    "{alpha} {c}: {f:?}"
                );
            }
        }
        assert_eq!(
            SpecularFit::lookup(1.0, 1.0).mirror_weight,
            f64::from(TABLE[16 * VIEW_STEPS][0])
        );
    }
}
