//! The surface BRDF: Lambertian diffuse plus the GGX microfacet specular lobe.
use crate::anisotropy::Anisotropy;
use crate::fresnel::Fresnel;
use crate::ggx;
use core::f32::consts::FRAC_1_PI;
use glam::Vec3;

/// A one-sided diffuse + GGX BRDF, `f(ωi, ωo) = kd/π + F(ωi·ωh) D(ωh·n) G1(ωi) G1(ωo) / (4 |ωi·n| |ωo·n|)`
/// (paper eq. (6) with the separable Smith G2 of section 4.1). The diffuse term is not weighted
/// by (1 - F). Zero unless both directions are on the side the normal points to. With an
/// [`Anisotropy`], D and G1 are the anisotropic GGX's ([`crate::anisotropy`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brdf {
    pub kd: Vec3,
    pub fresnel: Fresnel,
    /// GGX roughness α in (0, 1]; the roughness along the bitangent where anisotropic.
    pub alpha: f32,
    /// The tangent and its roughness α_t of an anisotropic lobe (`KHR_materials_anisotropy`);
    /// the tangent is perpendicular to the shading normal the BRDF is evaluated with.
    pub anisotropy: Option<Anisotropy>,
}

impl Brdf {
    /// The full BRDF value kd/π + eq. (6) (diffuse + specular). `omega_i` and `omega_o` point
    /// away from the surface.
    #[inline]
    pub fn eval(&self, n: Vec3, omega_i: Vec3, omega_o: Vec3) -> Vec3 {
        if n.dot(omega_i) <= 0.0 || n.dot(omega_o) <= 0.0 {
            return Vec3::ZERO;
        }
        self.kd * FRAC_1_PI + self.specular(n, omega_i, omega_o)
    }

    /// The Lambertian part kd/π (one-sided), the BRDF of a diffuse VPL in eq. (4) (section 6).
    #[inline]
    pub fn diffuse(&self, n: Vec3, omega_i: Vec3, omega_o: Vec3) -> Vec3 {
        if n.dot(omega_i) <= 0.0 || n.dot(omega_o) <= 0.0 {
            return Vec3::ZERO;
        }
        self.kd * FRAC_1_PI
    }

    /// The isotropic roughness that stands for this lobe where a method has no anisotropic
    /// form (the spherical Gaussians of VSGL): α, or sqrt(α_t α) for an anisotropic lobe, whose
    /// isotropic GGX has the same peak D(n) = 1/(π α_t α).
    #[inline]
    pub fn isotropic_alpha(&self) -> f32 {
        self.anisotropy
            .map_or(self.alpha, |a| (a.alpha_t * self.alpha).sqrt())
    }

    /// The microfacet part, paper eq. (6) with GGX D (eq. 7) and separable Smith G2 (eq. 8).
    #[inline]
    pub fn specular(&self, n: Vec3, omega_i: Vec3, omega_o: Vec3) -> Vec3 {
        microfacet(
            n,
            omega_i,
            omega_o,
            self.alpha,
            self.anisotropy.as_ref(),
            self.fresnel,
        )
    }
}

/// The GGX microfacet BRDF, paper eq. (6): `F(ωi·ωh) G2(ωi, ωo) D(ωh·n) / (4 |ωi·n| |ωo·n|)`,
/// with the separable Smith G2; zero unless both directions are above the surface. `n`,
/// `omega_i` and `omega_o` are unit vectors, the directions pointing away from the surface.
/// With an `anisotropy`, D and G1 are the anisotropic GGX's with α along the bitangent.
#[inline]
pub fn microfacet(
    n: Vec3,
    omega_i: Vec3,
    omega_o: Vec3,
    alpha: f32,
    anisotropy: Option<&Anisotropy>,
    fresnel: Fresnel,
) -> Vec3 {
    let cos_i = n.dot(omega_i);
    let cos_o = n.dot(omega_o);
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return Vec3::ZERO;
    }
    // G1/cos for each direction keeps grazing angles finite (no 0/0).
    let (g, alpha_min) = match anisotropy {
        None => (
            ggx::g1_over_cos(alpha, cos_i) * ggx::g1_over_cos(alpha, cos_o),
            alpha,
        ),
        Some(a) => (
            a.g1_over_cos(alpha, n, omega_i) * a.g1_over_cos(alpha, n, omega_o),
            a.alpha_min(alpha),
        ),
    };
    // sin² θh from the cross product keeps D accurate near its peak even for tiny α.
    let s = omega_i + omega_o;
    let s2 = s.length_squared();
    // The f32 sum of (nearly) unit vectors is off by ~1e-7, which tilts ωh by ~1e-7/|s|: far
    // below the lobe width α unless ωi and ωo are almost opposite (grazing incidence near the
    // mirror direction) and α is tiny. Only then is the half vector formed in f64.
    let (d, cos_ih) = if s2 * alpha_min * alpha_min > 1e-6 {
        let h = s / s2.sqrt();
        let d = match anisotropy {
            None => ggx::d_with_sin2(alpha, n.dot(h), n.cross(h).length_squared()),
            Some(a) => a.d(alpha, n, h),
        };
        (d, omega_i.dot(h))
    } else {
        let (wi, wo, nd) = (
            omega_i.as_dvec3(),
            omega_o.as_dvec3(),
            n.as_dvec3().normalize(),
        );
        let wi = wi / wi.length();
        let h = (wi + wo / wo.length()).normalize();
        let d = match anisotropy {
            None => ggx::d_with_sin2(alpha, nd.dot(h) as f32, nd.cross(h).length_squared() as f32),
            Some(a) => {
                let t = a.tangent.as_dvec3();
                let b = nd.cross(t);
                ggx::d_anisotropic(
                    a.alpha_t,
                    alpha,
                    t.dot(h) as f32,
                    b.dot(h) as f32,
                    nd.dot(h) as f32,
                )
            }
        };
        (d, wi.dot(h) as f32)
    };
    fresnel.eval(cos_ih) * (0.25 * d * g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;
    use core::f64::consts::PI;

    /// Eq. (6)-(8) written out in f64 from the textbook formulas.
    fn reference(n: Vec3, wi: Vec3, wo: Vec3, alpha: f64, f0: f64) -> f64 {
        let (n, wi, wo) = (n.as_dvec3(), wi.as_dvec3(), wo.as_dvec3());
        let h = (wi + wo).normalize();
        let (ci, co, ch) = (n.dot(wi), n.dot(wo), n.dot(h));
        let a2 = alpha * alpha;
        let d = a2 / (PI * (a2 * ch * ch + (1.0 - ch * ch)).powi(2));
        let g1 = |c: f64| 2.0 * c / (c + ((1.0 - a2) * c * c + a2).sqrt());
        let f = f0 + (1.0 - f0) * (1.0 - wi.dot(h)).powi(5);
        f * g1(ci) * g1(co) * d / (4.0 * ci * co)
    }

    #[test]
    fn microfacet_matches_eq_6() {
        let mut rng = Rng::new(11);
        for _ in 0..2000 {
            let n = rng.unit();
            let (wi, wo) = (rng.above(n), rng.above(n));
            let alpha = rng.range(0.05, 1.0);
            let f0 = rng.f32();
            let got = microfacet(n, wi, wo, alpha, None, Fresnel::Schlick(Vec3::splat(f0))).x;
            let want = reference(n, wi, wo, f64::from(alpha), f64::from(f0));
            assert!(
                (f64::from(got) - want).abs() <= 1e-4 * want + 1e-7,
                "{got} vs {want}"
            );
        }
    }

    #[test]
    fn reciprocal_and_one_sided() {
        let mut rng = Rng::new(12);
        let brdf = Brdf {
            kd: Vec3::new(0.5, 0.2, 0.1),
            fresnel: Fresnel::Dielectric(1.5),
            alpha: 0.3,
            anisotropy: None,
        };
        for _ in 0..500 {
            let n = rng.unit();
            let (wi, wo) = (rng.above(n), rng.above(n));
            let (a, b) = (brdf.eval(n, wi, wo), brdf.eval(n, wo, wi));
            assert!((a - b).abs().max_element() <= 1e-5 * a.max_element());
            assert_eq!(
                brdf.eval(n, wi, wo),
                brdf.diffuse(n, wi, wo) + brdf.specular(n, wi, wo)
            );
            assert_eq!(brdf.eval(n, -wi, wo), Vec3::ZERO);
            assert_eq!(brdf.eval(n, wi, -wo), Vec3::ZERO);
            assert_eq!(brdf.specular(n, wi, -wo), Vec3::ZERO);
            assert_eq!(brdf.diffuse(n, -wi, wo), Vec3::ZERO);
        }
    }

    #[test]
    fn peak_is_resolved_for_tiny_alpha() {
        // ωo 2e-4 rad from the mirror direction at α = 1e-4: θh = 1e-4 = α, so D is 1/4 of
        // its peak; an f32 n·h rounds to 1 there and would give the peak value.
        let alpha = 1e-4f32;
        let n = Vec3::Z;
        let wo = Vec3::new(2e-4f32.sin(), 0.0, 2e-4f32.cos());
        let f = microfacet(n, n, wo, alpha, None, Fresnel::Schlick(Vec3::ONE)).x;
        let peak = microfacet(n, n, n, alpha, None, Fresnel::Schlick(Vec3::ONE)).x;
        assert!((f / peak - 0.25).abs() < 0.01, "{}", f / peak);
    }
}
