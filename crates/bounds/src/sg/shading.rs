//! Analytic shading of a spherical Gaussian light (VSGL eq. 2 with the incoming radiance of
//! eq. 5) on the project's diffuse + GGX surface.
use crate::brdf::Brdf;
use crate::check;
use crate::error::BoundsError;
use crate::sg::lobe::SphericalGaussian;
use crate::sg::specular::SpecularLobeSg;
use core::f32::consts::FRAC_1_PI;
use glam::Vec3;

/// A shading point with normal `n`, view direction `ωo` and [`Brdf`], ready to integrate
/// `∫ L_in(ω) ρ(ωo, ω) ⟨ω, n⟩ dω` (VSGL eq. 2) against incoming radiance given as an SG
/// `L_in(ω) = c_in G(ω; ξ_in, λ_in)` (VSGL eq. 5) in closed form: the diffuse term as
/// `kd/π` times the SG's irradiance ([`SphericalGaussian::irradiance`], clamped at the
/// horizon) and the specular term as `weight ⟨L_in, warped NDF SG⟩` ([`SpecularLobeSg`]), an
/// SG inner product. The results are linear in the light: an RGB `c_in` is applied by shading
/// a unit-amplitude light and multiplying.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SgSurface {
    pub(crate) kd_over_pi: Vec3,
    pub(crate) normal: Vec3,
    pub(crate) specular: SpecularLobeSg,
}

impl SgSurface {
    /// The shading point; `n` and `omega_o` are unit vectors (within 1e-3), `brdf` has a
    /// finite non-negative `kd`, α in (0, 1] and a valid Fresnel model. A view below the
    /// surface shades to zero (the BRDF is one-sided). An anisotropic lobe is shaded as the
    /// isotropic one of [`Brdf::isotropic_alpha`] (spherical Gaussians are isotropic).
    pub fn new(n: Vec3, omega_o: Vec3, brdf: &Brdf) -> Result<Self, BoundsError> {
        let kd = check::non_negative(brdf.kd, "kd")?;
        let specular = SpecularLobeSg::new(n, omega_o, brdf.isotropic_alpha(), brdf.fresnel)?;
        let normal = check::unit(n, "normal")?;
        let front = normal.dot(omega_o) > 0.0;
        Ok(Self {
            kd_over_pi: if front { kd * FRAC_1_PI } else { Vec3::ZERO },
            normal,
            specular,
        })
    }

    /// The diffuse radiance `kd/π ∫ L_in(ω) ⟨ω, n⟩ dω`, the SG's irradiance.
    #[inline]
    pub fn diffuse(&self, light: &SphericalGaussian) -> Vec3 {
        saturate(self.kd_over_pi * light.irradiance(self.normal))
    }

    /// The specular radiance `∫ L_in(ω) ρ_s(ωo, ω) ⟨ω, n⟩ dω ≈ weight ⟨L_in, warped NDF SG⟩`.
    #[inline]
    pub fn specular(&self, light: &SphericalGaussian) -> Vec3 {
        saturate(self.specular.weight * light.inner_product(&self.specular.lobe))
    }

    /// The reflected radiance of VSGL eq. (2): [`SgSurface::diffuse`] + [`SgSurface::specular`].
    #[inline]
    pub fn radiance(&self, light: &SphericalGaussian) -> Vec3 {
        saturate(self.diffuse(light) + self.specular(light))
    }
}

/// Clamps an overflowing product to `f32::MAX` (only reachable for amplitudes near it).
#[inline]
fn saturate(v: Vec3) -> Vec3 {
    v.min(Vec3::splat(f32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fresnel::Fresnel;
    use crate::sg::quadrature::{eval64, sphere_integral, width};
    use core::f64::consts::PI;
    use glam::DVec3;

    /// The specular BRDF of eq. (6)-(8) with Schlick F in f64 (as in the BRDF's own tests).
    fn specular64(wi: DVec3, wo: DVec3, alpha: f64, f0: f64) -> f64 {
        let (ci, co) = (wi.z, wo.z);
        if ci <= 0.0 || co <= 0.0 {
            return 0.0;
        }
        let h = (wi + wo).normalize();
        let a2 = alpha * alpha;
        let d = a2 / (PI * (a2 * h.z * h.z + (1.0 - h.z * h.z)).powi(2));
        let g1 = |c: f64| 2.0 * c / (c + ((1.0 - a2) * c * c + a2).sqrt());
        let f = f0 + (1.0 - f0) * (1.0 - wi.dot(h)).powi(5);
        f * g1(ci) * g1(co) * d / (4.0 * ci * co)
    }

    fn direction(theta_deg: f64) -> Vec3 {
        let t = theta_deg.to_radians();
        Vec3::new(t.sin() as f32, 0.0, t.cos() as f32)
    }

    fn brdf(alpha: f32) -> Brdf {
        Brdf {
            kd: Vec3::new(0.8, 0.5, 0.2),
            fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
            alpha,
            anisotropy: None,
        }
    }

    #[test]
    fn diffuse_matches_quadrature() {
        let surface = SgSurface::new(Vec3::Z, direction(30.0), &brdf(0.5)).unwrap();
        let (mut worst_total, mut worst_above) = (0.0f64, 0.0f64);
        for l in [0.1f32, 1.0, 10.0, 100.0, 1000.0] {
            for k in 0..=12 {
                let light = SphericalGaussian::new(direction(15.0 * k as f64), l, 1.0).unwrap();
                let truth = sphere_integral(light.axis.as_dvec3(), width(f64::from(l)), |w| {
                    eval64(&light, w) * w.z.max(0.0)
                });
                let got = f64::from(surface.diffuse(&light).x) * PI / 0.8;
                let err = (got - truth).abs();
                worst_total = worst_total.max(err / f64::from(light.integral()));
                if k <= 4 {
                    worst_above = worst_above.max(err / truth);
                }
            }
        }
        // Measured: 0.016 of the light's integral at worst, 0.008 relative for lights up to 60°
        // from the normal (the cosine-SG inner product this replaced: 0.169 and 0.193).
        assert!(
            worst_total < 0.02 && worst_above < 0.01,
            "{worst_total} {worst_above}"
        );
    }

    #[test]
    fn specular_matches_quadrature() {
        for alpha in [0.05f32, 0.1, 0.3, 0.6, 1.0] {
            for view in [0.0, 30.0, 60.0, 80.0] {
                let surface = SgSurface::new(Vec3::Z, direction(view), &brdf(alpha)).unwrap();
                let mirror = direction(-view);
                let mut ratios = Vec::new();
                for l in [1.0f32, 10.0, 100.0, 1000.0] {
                    let light = SphericalGaussian::new(mirror, l, 1.0).unwrap();
                    let w = width(f64::from(l)).min(f64::from(alpha));
                    let wo = direction(view).as_dvec3();
                    let truth = sphere_integral(mirror.as_dvec3(), w, |wi| {
                        eval64(&light, wi) * specular64(wi, wo, f64::from(alpha), 0.04) * wi.z
                    });
                    let got = f64::from(surface.specular(&light).x);
                    ratios.push(got / truth);
                }
                // Measured ratios SG / quadrature over the lights: 0.99..1.49 for views up to 60°
                // (worst at α = 1), 1.02..2.13 at 80° (worst at α = 0.3): the isotropic warp
                // overestimates, most at grazing views where the true lobe is stretched.
                let hi = if view <= 60.0 { 1.6 } else { 2.3 };
                for r in ratios {
                    assert!(r > 0.95 && r < hi, "α {alpha} view {view}: {r}");
                }
            }
        }
    }

    #[test]
    fn extremes_are_finite() {
        let lights = [
            SphericalGaussian::new(Vec3::Z, 0.0, 1.0).unwrap(),
            SphericalGaussian::new(direction(-89.9), 1e9, 1.0).unwrap(),
            SphericalGaussian::new(direction(-45.0), 1e-6, 1.0).unwrap(),
        ];
        for alpha in [1e-3f32, 0.05, 1.0] {
            for cos_o in [1.0f32, 1e-3, 1e-7, 0.0, -0.5] {
                let wo = Vec3::new((1.0 - cos_o * cos_o).sqrt(), 0.0, cos_o);
                let surface = SgSurface::new(Vec3::Z, wo, &brdf(alpha)).unwrap();
                for light in &lights {
                    let v = surface.radiance(light);
                    assert!(
                        v.is_finite() && v.min_element() >= 0.0,
                        "{alpha} {cos_o}: {v}"
                    );
                    if cos_o <= 0.0 {
                        assert_eq!(v, Vec3::ZERO);
                    }
                }
            }
        }
        // A mirror-like surface seen head-on, lit by a broad light: the specular radiance is
        // about F0 times the light's value at the mirror direction.
        let mirror = SgSurface::new(Vec3::Z, Vec3::Z, &brdf(1e-3)).unwrap();
        let s = mirror.specular(&lights[0]).x;
        assert!((s / 0.04 - 1.0).abs() < 1e-3, "{s}");
        assert!(SgSurface::new(Vec3::Z, Vec3::Z, &brdf(0.0)).is_err());
        assert!(SgSurface::new(Vec3::ZERO, Vec3::Z, &brdf(0.5)).is_err());
    }
}
