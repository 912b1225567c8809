//! The surface BRDF: Lambertian diffuse plus the GGX microfacet specular lobe.
use crate::fresnel::Fresnel;
use crate::ggx;
use core::f32::consts::FRAC_1_PI;
use glam::Vec3;

/// A one-sided diffuse + GGX BRDF, `f(ωi, ωo) = kd/π + F(ωi·ωh) D(ωh·n) G1(ωi) G1(ωo) / (4 |ωi·n| |ωo·n|)`
/// (paper eq. (6) with the separable Smith G2 of section 4.1). The diffuse term is not weighted
/// by (1 - F). Zero unless both directions are on the side the normal points to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brdf {
    pub kd: Vec3,
    pub fresnel: Fresnel,
    /// GGX roughness α in (0, 1].
    pub alpha: f32,
}

impl Brdf {
    /// The full BRDF value (diffuse + specular). `omega_i` and `omega_o` point away from the surface.
    #[inline]
    pub fn eval(&self, n: Vec3, omega_i: Vec3, omega_o: Vec3) -> Vec3 {
        if n.dot(omega_i) <= 0.0 || n.dot(omega_o) <= 0.0 {
            return Vec3::ZERO;
        }
        self.kd * FRAC_1_PI + self.specular(n, omega_i, omega_o)
    }

    /// The Lambertian part kd/π (one-sided).
    #[inline]
    pub fn diffuse(&self, n: Vec3, omega_i: Vec3, omega_o: Vec3) -> Vec3 {
        if n.dot(omega_i) <= 0.0 || n.dot(omega_o) <= 0.0 {
            return Vec3::ZERO;
        }
        self.kd * FRAC_1_PI
    }

    /// The microfacet part, paper eq. (6) with GGX D (eq. 7) and separable Smith G2 (eq. 8).
    #[inline]
    pub fn specular(&self, n: Vec3, omega_i: Vec3, omega_o: Vec3) -> Vec3 {
        microfacet(n, omega_i, omega_o, self.alpha, self.fresnel)
    }
}

/// The GGX microfacet BRDF, paper eq. (6): `F(ωi·ωh) G2(ωi, ωo) D(ωh·n) / (4 |ωi·n| |ωo·n|)`,
/// with the separable Smith G2; zero unless both directions are above the surface.
#[inline]
pub fn microfacet(n: Vec3, omega_i: Vec3, omega_o: Vec3, alpha: f32, fresnel: Fresnel) -> Vec3 {
    let cos_i = n.dot(omega_i);
    let cos_o = n.dot(omega_o);
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return Vec3::ZERO;
    }
    let h = omega_i + omega_o;
    let len = h.length();
    if len <= 0.0 {
        return Vec3::ZERO;
    }
    let h = h / len;
    let d = ggx::d(alpha, n.dot(h));
    // G1/cos for each direction keeps grazing angles finite (no 0/0).
    let g = ggx::g1_over_cos(alpha, cos_i) * ggx::g1_over_cos(alpha, cos_o);
    fresnel.eval(omega_i.dot(h)) * (0.25 * d * g)
}
