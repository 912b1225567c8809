//! Fresnel factors and their maxima over half vectors (supplemental, section 1).
use glam::Vec3;

/// A Fresnel model: Schlick's approximation with an RGB reflectance at normal incidence, or
/// the exact unpolarized dielectric Fresnel factor with a relative index of refraction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fresnel {
    /// Schlick with F0 per channel, supplemental eq. (1).
    Schlick(Vec3),
    /// Unpolarized dielectric with relative index eta > 0, supplemental eq. (3)-(5).
    Dielectric(f32),
}

impl Fresnel {
    /// F(cos θh) for the cosine between the incoming direction and the half vector.
    #[inline]
    pub fn eval(&self, cos_h: f32) -> Vec3 {
        match *self {
            Fresnel::Schlick(f0) => schlick(f0, cos_h),
            Fresnel::Dielectric(eta) => Vec3::splat(dielectric(eta, cos_h)),
        }
    }

    /// F_max(ωi): the largest Fresnel factor over all half vectors reachable from an incoming
    /// direction with cosine `cos_i` to the normal; supplemental eq. (2) for Schlick and
    /// eq. (6) for dielectrics.
    #[inline]
    pub fn max_over_half_vectors(&self, cos_i: f32) -> Vec3 {
        let c = cos_theta_h_max(cos_i);
        match *self {
            Fresnel::Schlick(f0) => schlick(f0, c),
            Fresnel::Dielectric(eta) => Vec3::splat(dielectric(eta, 1.0).max(dielectric(eta, c))),
        }
    }
}

/// Schlick's approximation, supplemental eq. (1): `F0 + (1 - F0)(1 - cos θh)^5`.
#[inline]
pub fn schlick(f0: Vec3, cos_h: f32) -> Vec3 {
    let m = (1.0 - cos_h.clamp(0.0, 1.0)).powi(5);
    f0 + (Vec3::ONE - f0) * m
}

/// Unpolarized Fresnel factor of a dielectric with relative index `eta`, supplemental
/// eq. (3)-(5): the mean of the perpendicular and parallel reflectances. Total internal
/// reflection (η² < sin² θh) gives 1.
#[inline]
pub fn dielectric(eta: f32, cos_h: f32) -> f32 {
    let c = cos_h.clamp(0.0, 1.0);
    let s2 = 1.0 - c * c;
    let g2 = eta * eta - s2;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let e2c = eta * eta * c;
    let perp = ((c - g) / (c + g)).powi(2);
    let par = ((g - e2c) / (g + e2c)).powi(2);
    0.5 * (perp + par)
}

/// Cosine of the largest angle θh_max(ωi) = ½ arccos(ωi·n) + π/4 between ωi and a half vector
/// whose reflected direction lies above the surface (supplemental, after eq. (2)):
/// `sqrt((1 - sqrt(1 - (ωi·n)²)) / 2)`.
#[inline]
pub fn cos_theta_h_max(cos_i: f32) -> f32 {
    let c = cos_i.clamp(0.0, 1.0);
    let sin_i = (1.0 - c * c).max(0.0).sqrt();
    ((1.0 - sin_i) * 0.5).max(0.0).sqrt()
}
