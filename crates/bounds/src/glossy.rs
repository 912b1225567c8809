//! A glossy VPL: the GGX specular lobe of its radiant intensity (eq. 4, 6) and the radius r
//! of its bounding spheroid (eq. 12).
use crate::anisotropy::Anisotropy;
use crate::brdf::microfacet;
use crate::check;
use crate::error::BoundsError;
use crate::fresnel::Fresnel;
use crate::ggx;
use crate::shading_normal::{emitted_cosine, flux_scale, g1_tilt_max};
use crate::stochastic::{scalar_intensity, StochasticParams};
use core::f64::consts::PI;
use glam::Vec3;

/// A VPL reflecting by the GGX microfacet BRDF, validated: finite position q, unit normal n,
/// unit incoming direction ωi (from the VPL towards where the light came from), α in (0, 1],
/// finite non-negative RGB flux Φ and a valid [`Fresnel`] model.
///
/// ωi below or on the surface (ωi·n <= 0) is accepted: such a VPL reflects nothing, and its
/// bounds are empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossyLobe {
    position: Vec3,
    normal: Vec3,
    /// The geometric normal n_g (`normal` unless set by [`Self::with_geometric_normal`]).
    geometric_normal: Vec3,
    omega_i: Vec3,
    /// α of eq. (7); the roughness along the bitangent where anisotropic.
    alpha: f32,
    /// Set by [`Self::with_anisotropy`].
    anisotropy: Option<Anisotropy>,
    flux: Vec3,
    fresnel: Fresnel,
}

impl GlossyLobe {
    /// Validates the VPL of eq. (4) with the BRDF of eq. (6); see [`BoundsError`] for the
    /// rejected inputs. Unit vectors are accepted within 1e-3 and renormalised.
    pub fn new(
        position: Vec3,
        normal: Vec3,
        omega_i: Vec3,
        alpha: f32,
        flux: Vec3,
        fresnel: Fresnel,
    ) -> Result<Self, BoundsError> {
        let normal = check::unit(normal, "normal")?;
        Ok(Self {
            position: check::finite(position, "position")?,
            normal,
            geometric_normal: normal,
            omega_i: check::unit(omega_i, "omega_i")?,
            alpha: check::alpha(alpha)?,
            anisotropy: None,
            flux: check::non_negative(flux, "flux")?,
            fresnel: check::fresnel(fresnel)?,
        })
    }

    /// The VPL position q of eq. (15).
    #[inline]
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// The geometric normal n of eq. (4).
    #[inline]
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// The same VPL on a surface whose geometric normal n_g differs from its shading normal n
    /// (a normal map): its intensity and bounds follow [`crate::shading_normal`]. `n_g` must
    /// be a unit vector (within 1e-3); it is used as given when equal to n.
    pub fn with_geometric_normal(mut self, n_g: Vec3) -> Result<Self, BoundsError> {
        self.geometric_normal = match n_g == self.normal {
            true => n_g,
            false => check::unit(n_g, "geometric normal")?,
        };
        Ok(self)
    }

    /// The same VPL with an anisotropic lobe (`None`: isotropic): α_t along the tangent, this
    /// lobe's α along the bitangent ([`crate::anisotropy`]). The tangent must be a unit
    /// vector (within 1e-3) perpendicular to the shading normal within 1e-4 and α_t/2 (the
    /// bound factor covers what is left), α_t in (0, 1]. It is used as given, as the shader
    /// uses it.
    pub fn with_anisotropy(mut self, anisotropy: Option<Anisotropy>) -> Result<Self, BoundsError> {
        self.anisotropy = match anisotropy {
            None => None,
            Some(a) => {
                check::unit(a.tangent, "tangent")?;
                let alpha_t = check::alpha(a.alpha_t)?;
                let off = a.tangent.dot(self.normal).abs();
                if off > 1e-4 || off >= 0.5 * alpha_t {
                    return Err(BoundsError::NotPerpendicular("tangent"));
                }
                Some(Anisotropy {
                    tangent: a.tangent,
                    alpha_t,
                })
            }
        };
        Ok(self)
    }

    /// The factor by which this VPL's bounds exceed eq. (9)-(12)'s, taken with [`Self::alpha`],
    /// for the same flux: the product of the shading-normal factor (1 where n = n_g, else
    /// `(ωi·n)/(ωi·n_g) (cos θt + (2/α_min) sin θt)`, [`crate::shading_normal`]) and the
    /// anisotropy's (1 if isotropic, else [`Anisotropy::bound_factor`]).
    pub fn bound_factor(&self) -> f32 {
        let tilt = flux_scale(self.normal, self.geometric_normal, self.omega_i)
            * g1_tilt_max(self.normal, self.geometric_normal, self.alpha_min());
        match self.anisotropy {
            None => tilt,
            Some(a) => tilt * a.bound_factor(self.alpha, self.normal, self.omega_i),
        }
    }

    /// Whether the shading normal differs from the geometric one.
    #[inline]
    pub fn is_tilted(&self) -> bool {
        self.normal != self.geometric_normal
    }

    /// The incoming direction ωi of eq. (4).
    #[inline]
    pub fn omega_i(&self) -> Vec3 {
        self.omega_i
    }

    /// The GGX roughness α of eq. (7) the bounds use: the lobe's α, or for an anisotropic
    /// lobe the larger of α_t and α_b (the isotropic lobe that bounds it, with
    /// [`Self::bound_factor`]).
    #[inline]
    pub fn alpha(&self) -> f32 {
        self.anisotropy
            .map_or(self.alpha, |a| a.alpha_max(self.alpha))
    }

    /// The smallest roughness of the lobe (α if isotropic): G1 of it bounds the lobe's G1.
    #[inline]
    pub fn alpha_min(&self) -> f32 {
        self.anisotropy
            .map_or(self.alpha, |a| a.alpha_min(self.alpha))
    }

    /// The RGB flux Φ of eq. (4).
    #[inline]
    pub fn flux(&self) -> Vec3 {
        self.flux
    }

    /// The Fresnel model F of eq. (6).
    #[inline]
    pub fn fresnel(&self) -> Fresnel {
        self.fresnel
    }

    /// ωi·n, the cosine in the denominators of eq. (9) and (12).
    #[inline]
    pub fn cos_i(&self) -> f32 {
        self.normal.dot(self.omega_i)
    }

    /// |n × ωi|, the sine of ωi's angle to the normal, exact near normal incidence (where
    /// `sqrt(1 − cos²)` is not: [`crate::fresnel::cos_theta_h_max`]).
    #[inline]
    pub fn sin_i(&self) -> f32 {
        self.normal.cross(self.omega_i).length()
    }

    /// The mirror direction ω_u = 2(ωi·n)n − ωi of section 4.2 (the spheroid's long axis).
    #[inline]
    pub fn reflection(&self) -> Vec3 {
        (2.0 * self.cos_i() * self.normal - self.omega_i).normalize()
    }

    /// The scalar radiant intensity I(ωo) = scalar(Φ f(ωi, ωo)) max(ωo·n, 0) of eq. (4), with
    /// the GGX BRDF of eq. (6) (true Fresnel factor, separable Smith G2), reduced to a scalar
    /// by [`scalar_intensity`]; for a tilted shading normal the cosine is
    /// [`emitted_cosine`]'s. `omega_o` is the unit direction from the VPL to the shading
    /// point; not validated (per-pixel path), and zero below the surface.
    #[inline]
    pub fn intensity(&self, omega_o: Vec3) -> f32 {
        let f = microfacet(
            self.normal,
            self.omega_i,
            omega_o,
            self.alpha,
            self.anisotropy.as_ref(),
            self.fresnel,
        );
        scalar_intensity(self.flux * f)
            * emitted_cosine(self.normal, self.geometric_normal, self.omega_i, omega_o)
    }

    /// The radius of eq. (12): `r = sqrt(Φ F_max(ωi) G1(ωi) / (4π δ ξ |ωi·n|))`, where
    /// `Φ F_max` is the largest channel of Φ_c F_max,c(ωi) (supplemental eq. (2), (6)) and
    /// `G1/|ωi·n|` is evaluated in closed form, finite at grazing incidence.
    ///
    /// Zero when ωi·n <= 0 or the flux is zero (the VPL reflects nothing). A tilted or
    /// anisotropic VPL's flux is multiplied by [`Self::bound_factor`], with α =
    /// [`Self::alpha`]. Computed in f64; an [`BoundsError::Overflow`] if r does not fit in
    /// an `f32`.
    pub fn radius(&self, params: &StochasticParams) -> Result<f32, BoundsError> {
        let cos_i = self.cos_i();
        let peak =
            scalar_intensity(self.flux * self.fresnel.max_over_half_vectors(cos_i, self.sin_i()))
                * self.bound_factor();
        if cos_i <= 0.0 || peak <= 0.0 {
            return Ok(0.0);
        }
        let numerator = f64::from(peak) * f64::from(ggx::g1_over_cos(self.alpha(), cos_i));
        let denominator = 4.0 * PI * f64::from(params.delta()) * f64::from(params.xi());
        check::fits((numerator / denominator).sqrt(), "spheroid radius r")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lobe(normal: Vec3, omega_i: Vec3, alpha: f32, flux: Vec3, f: Fresnel) -> GlossyLobe {
        GlossyLobe::new(Vec3::ZERO, normal, omega_i, alpha, flux, f).unwrap()
    }

    #[test]
    fn radius_is_eq_12() {
        let params = StochasticParams::new(1e-3, 0.25).unwrap();
        let wi = Vec3::new(0.6, 0.0, 0.8);
        let l = lobe(
            Vec3::Z,
            wi,
            0.5,
            Vec3::new(1.0, 2.0, 0.5),
            Fresnel::Schlick(Vec3::ONE),
        );
        // F ≡ 1: r² = Φ G1 / (4π δ ξ cos) with max Φ = 2, G1(0.8) = 1.6 / (0.8 + sqrt(0.73)).
        let g1 = 1.6 / (0.8 + 0.73f64.sqrt());
        let want = (2.0 * g1 / (4.0 * PI * 1e-3 * 0.25 * 0.8)).sqrt();
        let got = f64::from(l.radius(&params).unwrap());
        assert!((got - want).abs() < 1e-5 * want, "{got} vs {want}");
        assert!((l.reflection() - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
        assert!((l.cos_i() - 0.8).abs() < 1e-6);
    }

    /// At normal incidence the radius is that of `n = ωi = z` whatever f32 unit vector `n` is,
    /// though `n·n` rounds an ulp below 1 for many of them: F_max's θh_max takes the sine
    /// `|n × ωi|`. With `sqrt(1 − cos²)` one ulp gave a sine of 3.5e-4 and radii 2e-4 apart
    /// (how the GPU, whose `normalize` rounds differently, disagreed with the CPU).
    #[test]
    fn normal_incidence_radius_does_not_hang_on_an_ulp() {
        let params = StochasticParams::new(1e-3, 3e-8).unwrap();
        let mut rng = crate::test_util::Rng::new(12);
        for f in [
            Fresnel::Dielectric(1.5),
            Fresnel::Schlick(Vec3::splat(0.04)),
        ] {
            let flux = Vec3::new(3.0, 0.5, 0.0);
            let exact = lobe(Vec3::Z, Vec3::Z, 1e-3, flux, f)
                .radius(&params)
                .unwrap();
            let mut below_one = 0;
            for _ in 0..200 {
                let n = rng.unit();
                let l = lobe(n, n, 1e-3, flux, f);
                below_one += usize::from(l.cos_i() < 1.0);
                let r = l.radius(&params).unwrap();
                assert!((r / exact - 1.0).abs() < 1e-6, "{n}: {r} vs {exact}");
            }
            assert!(below_one > 20, "{below_one}");
        }
    }

    #[test]
    fn empty_when_nothing_is_reflected() {
        let params = StochasticParams::new(1e-3, 0.5).unwrap();
        let f = Fresnel::Dielectric(1.5);
        let below = lobe(Vec3::Z, Vec3::new(0.6, 0.0, -0.8), 0.3, Vec3::ONE, f);
        assert_eq!(below.radius(&params), Ok(0.0));
        let tangent = lobe(Vec3::Z, Vec3::X, 0.3, Vec3::ONE, f);
        assert_eq!(tangent.radius(&params), Ok(0.0));
        let dark = lobe(Vec3::Z, Vec3::Z, 0.3, Vec3::ZERO, f);
        assert_eq!(dark.radius(&params), Ok(0.0));
        assert_eq!(below.intensity(Vec3::Z), 0.0);
    }

    #[test]
    fn grazing_incidence_is_finite() {
        let params = StochasticParams::new(1e-9, 3e-8).unwrap();
        let wi = Vec3::new(1.0, 0.0, 1e-6).normalize();
        for alpha in [1e-4, 1e-3, 1.0] {
            let l = lobe(
                Vec3::Z,
                wi,
                alpha,
                Vec3::splat(5.0),
                Fresnel::Dielectric(1.5),
            );
            let r = l.radius(&params).unwrap();
            assert!(r.is_finite() && r > 0.0, "alpha {alpha}: {r}");
        }
    }

    #[test]
    fn invalid_inputs_are_errors() {
        let ok = |n, wi, a, flux, f| GlossyLobe::new(Vec3::ZERO, n, wi, a, flux, f);
        let (n, s) = (Vec3::Z, Fresnel::Schlick(Vec3::splat(0.04)));
        for a in [0.0, -0.1, 1.5, f32::NAN] {
            assert!(matches!(
                ok(n, n, a, Vec3::ONE, s),
                Err(BoundsError::InvalidAlpha(_))
            ));
        }
        assert!(ok(n, n, 1.0, Vec3::ONE, s).is_ok());
        assert_eq!(
            ok(n * 2.0, n, 0.5, Vec3::ONE, s),
            Err(BoundsError::NotUnit("normal"))
        );
        assert_eq!(
            ok(n, Vec3::NAN, 0.5, Vec3::ONE, s),
            Err(BoundsError::NotFinite("omega_i"))
        );
        assert_eq!(
            ok(n, n, 0.5, -Vec3::ONE, s),
            Err(BoundsError::Negative("flux"))
        );
        assert_eq!(
            ok(n, n, 0.5, Vec3::splat(f32::INFINITY), s),
            Err(BoundsError::NotFinite("flux"))
        );
        assert!(ok(n, n, 0.5, Vec3::ONE, Fresnel::Dielectric(0.0)).is_err());
        assert!(ok(n, n, 0.5, Vec3::ONE, Fresnel::Schlick(Vec3::splat(2.0))).is_err());
        assert_eq!(
            GlossyLobe::new(Vec3::NAN, n, n, 0.5, Vec3::ONE, s),
            Err(BoundsError::NotFinite("position"))
        );
    }

    #[test]
    fn overflow_is_an_error() {
        let params = StochasticParams::new(f32::MIN_POSITIVE, f32::MIN_POSITIVE).unwrap();
        let l = lobe(
            Vec3::Z,
            Vec3::Z,
            1e-4,
            Vec3::splat(f32::MAX),
            Fresnel::Schlick(Vec3::ONE),
        );
        assert!(matches!(l.radius(&params), Err(BoundsError::Overflow(_))));
    }
}
