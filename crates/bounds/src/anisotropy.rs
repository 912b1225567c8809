//! Anisotropic GGX (glTF `KHR_materials_anisotropy`): a roughness α_t along a tangent t and
//! α_b along the bitangent b = n × t, and the bound of its VPLs by an isotropic lobe (the
//! paper's section 8 names anisotropic NDFs as future work; `docs/anisotropy.md`).
//!
//! The BRDF is eq. (6) with the anisotropic D and Smith G1 of [`crate::ggx`]. A glossy VPL's
//! intensity `I(ωo) = Φ F D_a(ωh) G1_a(ωi) G1_a(ωo) / (4 ωi·n)` is bounded by eq. (9)-(12)
//! for the isotropic lobe of the larger roughness α_max = max(α_t, α_b) once its flux is
//! multiplied by [`Anisotropy::bound_factor`]:
//! - D: with m = (x, y, z) in (t, b, n), `x²/α_t² + y²/α_b² >= (x² + y²)/α_max²`, so
//!   `D_a(m) <= (α_max²/(α_t α_b)) D(α_max)(m)` for every m, with equality at m = n and, for
//!   α_t ≠ α_b, along the rougher axis: no smaller multiple of one isotropic lobe bounds it;
//! - G1(ωi)/(ωi·n) is a constant of the VPL: its own anisotropic value replaces the
//!   isotropic one of α_max (the ratio is at least 1, since G1 falls as the roughness grows);
//! - G1(ωo) <= 1 as in eq. (9), and `G1_a(ωo) <= G1(α_min)(ωo)` where a bound keeps it (the
//!   tight box bound, the tilt factor of [`crate::shading_normal`]), since the projected
//!   roughness α(ωo) of eq. (86) lies between α_min and α_max.
use crate::basis::Basis;
use crate::ggx;
use glam::Vec3;

/// The anisotropic part of a GGX lobe: α_t along the unit `tangent`; the lobe's own α (the
/// [`crate::Brdf`]'s `alpha`) is the roughness along the bitangent b = n × t. The tangent must
/// be perpendicular to the shading normal n the BRDF is evaluated with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Anisotropy {
    /// Unit tangent t, perpendicular to the shading normal.
    pub tangent: Vec3,
    /// GGX roughness α_t in (0, 1] along t.
    pub alpha_t: f32,
}

impl Anisotropy {
    /// The anisotropic D at unit micro-normal `m` for shading normal `n` and bitangent
    /// roughness `alpha_b` ([`ggx::d_anisotropic`]).
    #[inline]
    pub fn d(&self, alpha_b: f32, n: Vec3, m: Vec3) -> f32 {
        let b = n.cross(self.tangent);
        ggx::d_anisotropic(
            self.alpha_t,
            alpha_b,
            self.tangent.dot(m),
            b.dot(m),
            n.dot(m),
        )
    }

    /// `G1(ω)/|ω·n|` of the anisotropic Smith function ([`ggx::g1_over_cos_anisotropic`]).
    #[inline]
    pub fn g1_over_cos(&self, alpha_b: f32, n: Vec3, omega: Vec3) -> f32 {
        let b = n.cross(self.tangent);
        ggx::g1_over_cos_anisotropic(
            self.alpha_t,
            alpha_b,
            self.tangent.dot(omega),
            b.dot(omega),
            n.dot(omega),
        )
    }

    /// The tangent as an angle φ in the plane of the unit normal `n`: t = cos φ x + sin φ y
    /// with (x, y) the frame of Duff et al. 2017 around n ([`Basis::new`]); a compact form for
    /// G-buffers ([`Self::from_angle`] inverts it).
    pub fn angle(&self, n: Vec3) -> f32 {
        let f = Basis::from_unit(n);
        f.y.dot(self.tangent).atan2(f.x.dot(self.tangent))
    }

    /// The anisotropy whose tangent has angle `phi` around the unit normal `n`
    /// ([`Self::angle`]).
    pub fn from_angle(n: Vec3, phi: f32, alpha_t: f32) -> Self {
        let f = Basis::from_unit(n);
        let (sin, cos) = phi.sin_cos();
        Self {
            tangent: f.x * cos + f.y * sin,
            alpha_t,
        }
    }

    /// The larger roughness α_max = max(α_t, α_b): the isotropic lobe that bounds this one.
    #[inline]
    pub fn alpha_max(&self, alpha_b: f32) -> f32 {
        self.alpha_t.max(alpha_b)
    }

    /// The smaller roughness α_min = min(α_t, α_b): G1 of α_min bounds the anisotropic G1.
    #[inline]
    pub fn alpha_min(&self, alpha_b: f32) -> f32 {
        self.alpha_t.min(alpha_b)
    }

    /// The factor by which the flux of a glossy VPL with this anisotropy (incoming direction
    /// ωi, shading normal n) must grow for eq. (9)-(12) with α_max to bound it (module docs):
    /// `(α_max²/(α_t α_b)) · (G1_a(ωi)/(ωi·n)) / (G1(α_max)(ωi)/(ωi·n))`, at least 1. In f64,
    /// with a relative margin of 1e-5 for the rounding of the bounds' f32 inputs.
    ///
    /// A tangent off n's plane by ε = |t·n| (rounding) shifts the shader's D: with
    /// t = t⊥ + ε n, `(m·t)² >= (1 − η)(m·t⊥)² − (1/η − 1) ε² (m·n)²` for η = ε/α_t turns the
    /// denominator of D into at least `(1 − η) |t⊥|²` times the orthonormal one, so the factor
    /// carries `1/((1 − η)² |t⊥|⁴)` (|t⊥| at most 1). Infinite for ε >= α_t/2
    /// ([`crate::GlossyLobe::with_anisotropy`] refuses such tangents).
    pub fn bound_factor(&self, alpha_b: f32, n: Vec3, omega_i: Vec3) -> f32 {
        let (n, t) = (n.as_dvec3(), self.tangent.as_dvec3());
        let w = omega_i.as_dvec3();
        let (at, ab) = (f64::from(self.alpha_t), f64::from(alpha_b));
        let a_max = at.max(ab);
        let eps = t.dot(n).abs();
        if eps >= 0.5 * at {
            return f32::INFINITY;
        }
        let perp2 = (t.length_squared() - eps * eps).min(1.0);
        let off_plane = 1.0 / ((1.0 - eps / at).powi(2) * perp2 * perp2);
        let peak = off_plane * a_max * a_max / (at * ab);
        let c = n.dot(w).abs();
        let (x, y) = (at * t.dot(w), ab * n.cross(t).dot(w));
        let g1_own = 1.0 / (c + (c * c + x * x + y * y).sqrt());
        let g1_max = 1.0 / (c + (c * c + a_max * a_max * n.cross(w).length_squared()).sqrt());
        (peak * (g1_own / g1_max).max(1.0) * (1.0 + 1e-5)) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{random_anisotropy, Rng};
    use core::f64::consts::PI;
    use glam::DVec3;

    /// Sums `f(m, dm)` over the hemisphere of micro-normals on a grid fitted to a lobe of
    /// roughness (α_t, α_b): m = normalize(α_t r cos φ, α_b r sin φ, 1), points of the plane
    /// z = 1 projected onto the sphere (dm = dA/|p|³ with dA = α_t α_b r dr dφ), which spreads
    /// the peak of either width over the grid; r = tan ψ covers the tail.
    fn stretched_grid(
        (alpha_t, alpha_b): (f64, f64),
        (nr, nphi): (usize, usize),
        mut f: impl FnMut(DVec3, f64),
    ) {
        for i in 0..nr {
            let psi = (i as f64 + 0.5) / nr as f64 * PI / 2.0;
            let (r, dr) = (psi.tan(), 1.0 / psi.cos().powi(2) * PI / 2.0 / nr as f64);
            for j in 0..nphi {
                let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI;
                let (x, y) = (alpha_t * r * phi.cos(), alpha_b * r * phi.sin());
                let len = (x * x + y * y + 1.0).sqrt();
                let dm = alpha_t * alpha_b * r * dr * (2.0 * PI / nphi as f64) / len.powi(3);
                f(DVec3::new(x, y, 1.0) / len, dm);
            }
        }
    }

    /// ∫ D_a(m) (m·n) dm over the hemisphere (1: the projected microfacet area), with D from
    /// the implementation.
    fn projected_area(alpha_t: f64, alpha_b: f64) -> f64 {
        let mut sum = 0.0;
        stretched_grid((alpha_t, alpha_b), (4000, 64), |m, dm| {
            let d = ggx::d_anisotropic(
                alpha_t as f32,
                alpha_b as f32,
                m.x as f32,
                m.y as f32,
                m.z as f32,
            );
            sum += f64::from(d) * m.z * dm;
        });
        sum
    }

    #[test]
    fn d_integrates_to_one_and_reduces_to_eq_7() {
        for (at, ab) in [(0.5, 0.5), (0.9, 0.1), (0.05, 0.6), (1.0, 0.01), (0.3, 1.0)] {
            let i = projected_area(at, ab);
            assert!((i - 1.0).abs() < 2e-3, "α ({at}, {ab}): {i}");
        }
        let mut rng = Rng::new(5);
        for _ in 0..1000 {
            let n = rng.unit();
            let alpha = rng.range(0.01, 1.0);
            let a = Anisotropy {
                alpha_t: alpha,
                ..random_anisotropy(&mut rng, n)
            };
            let m = rng.above(n);
            let (iso, aniso) = (
                ggx::d_with_sin2(alpha, n.dot(m), n.cross(m).length_squared()),
                a.d(alpha, n, m),
            );
            assert!((iso - aniso).abs() <= 1e-4 * iso, "{iso} vs {aniso}");
            let w = rng.above(n);
            let (iso, aniso) = (
                ggx::g1_over_cos(alpha, n.dot(w)),
                a.g1_over_cos(alpha, n, w),
            );
            assert!((iso - aniso).abs() <= 1e-4 * iso, "{iso} vs {aniso}");
        }
    }

    /// G1 by its definition (eq. 8 with D_a): |ω·n| / ∫ D_a(m) max(ω·m, 0) dm, with D_a
    /// written out in f64.
    fn g1_numeric(alpha_t: f64, alpha_b: f64, w: DVec3) -> f64 {
        let mut sum = 0.0;
        stretched_grid((alpha_t, alpha_b), (3000, 256), |m, dm| {
            let s = (m.x / alpha_t).powi(2) + (m.y / alpha_b).powi(2) + m.z * m.z;
            let d = 1.0 / (PI * alpha_t * alpha_b * s * s);
            sum += d * w.dot(m).max(0.0) * dm;
        });
        w.z / sum
    }

    #[test]
    fn g1_closed_form_matches_its_definition() {
        for (at, ab) in [(0.8, 0.2), (0.1, 0.5), (1.0, 0.05)] {
            for (theta, phi) in [(0.3f64, 0.0f64), (1.0, 0.7), (1.4, 1.9), (1.5, 3.0)] {
                let w = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let numeric = g1_numeric(at, ab, w);
                let closed = w.z
                    * f64::from(ggx::g1_over_cos_anisotropic(
                        at as f32, ab as f32, w.x as f32, w.y as f32, w.z as f32,
                    ));
                assert!(
                    (numeric - closed).abs() < 2e-3 * closed,
                    "α ({at}, {ab}) θ {theta} φ {phi}: {numeric} vs {closed}"
                );
            }
        }
    }

    #[test]
    fn angle_round_trips() {
        let mut rng = Rng::new(7);
        for _ in 0..10_000 {
            let n = rng.unit();
            let a = random_anisotropy(&mut rng, n);
            let b = Anisotropy::from_angle(n, a.angle(n), a.alpha_t);
            assert!((a.tangent - b.tangent).length() < 1e-5, "{a:?} {b:?}");
            assert!(b.tangent.dot(n).abs() < 1e-5);
        }
    }

    #[test]
    fn the_isotropic_lobe_of_alpha_max_bounds_it() {
        let mut rng = Rng::new(6);
        let mut closest: f32 = 0.0;
        for _ in 0..100_000 {
            let n = rng.unit();
            let alpha_b = 10f32.powf(rng.range(-3.0, 0.0));
            let mut a = random_anisotropy(&mut rng, n);
            // Half of the tangents off n's plane by up to 1e-4 (and α_t/2), as rounding
            // leaves them; the shader uses them as given.
            if rng.f32() < 0.5 {
                let eps = 10f32.powf(rng.range(-7.0, -4.0)).min(0.45 * a.alpha_t);
                a.tangent = (a.tangent + n * eps).normalize();
            }
            let a_max = a.alpha_max(alpha_b);
            let omega_i = rng.above(n);
            let k = a.bound_factor(alpha_b, n, omega_i);
            assert!(k >= 1.0, "{k}");
            // D_a G1_a(ωi)/cos <= k D(α_max) G1(α_max)(ωi)/cos at random and near-peak m.
            let m = match rng.f32() < 0.5 {
                true => rng.above(n),
                false => (n + (rng.unit() * a_max * rng.f32())).normalize(),
            };
            let own = f64::from(a.d(alpha_b, n, m)) * f64::from(a.g1_over_cos(alpha_b, n, omega_i));
            let iso = f64::from(k)
                * f64::from(ggx::d_with_sin2(
                    a_max,
                    n.dot(m),
                    n.cross(m).length_squared(),
                ))
                * f64::from(ggx::g1_over_cos(a_max, n.dot(omega_i)));
            assert!(own <= iso * (1.0 + 2e-5), "{own} > {iso}");
            closest = closest.max((own / iso) as f32);
            // G1_a(ωo) lies between the isotropic G1 of α_max and α_min.
            let w = rng.above(n);
            let g = a.g1_over_cos(alpha_b, n, w);
            let (lo, hi) = (
                ggx::g1_over_cos(a_max, n.dot(w)),
                ggx::g1_over_cos(a.alpha_min(alpha_b), n.dot(w)),
            );
            assert!(
                g >= lo * (1.0 - 1e-4) && g <= hi * (1.0 + 1e-4),
                "{lo} {g} {hi}"
            );
        }
        // The factor is reached: the bound is tight at the peak.
        assert!(closest > 0.99, "{closest}");
    }
}
