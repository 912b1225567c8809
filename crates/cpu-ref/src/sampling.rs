//! Importance sampling of the diffuse + GGX BRDF for the path-traced reference.
use glam::Vec3;
use slc_bounds::fresnel::sin_from_cos;
use slc_bounds::{ggx, Brdf};
use std::f32::consts::{FRAC_1_PI, PI};

/// Probability of sampling the specular lobe: the lobes' largest albedo-like weights,
/// max(kd) against max F_max(ωo).
fn specular_probability(brdf: &Brdf, cos_o: f32) -> f32 {
    let wd = brdf.kd.max_element();
    let ws = brdf
        .fresnel
        .max_over_half_vectors(cos_o, sin_from_cos(cos_o))
        .max_element();
    if wd + ws <= 0.0 {
        0.0
    } else {
        ws / (wd + ws)
    }
}

/// Density (solid angle) of [`sample`] producing `omega_i`: the mixture of the cosine density
/// cos θi / π and the GGX density D(h) cos θh / (4 |ωo·h|) (Walter et al. 2007, eq. 14 and 38),
/// D anisotropic where the BRDF is.
pub fn pdf(brdf: &Brdf, n: Vec3, omega_o: Vec3, omega_i: Vec3) -> f32 {
    let cos_i = n.dot(omega_i);
    let cos_o = n.dot(omega_o);
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return 0.0;
    }
    let ps = specular_probability(brdf, cos_o);
    let h = (omega_i + omega_o).normalize();
    let d = match brdf.anisotropy {
        None => ggx::d(brdf.alpha, n.dot(h)),
        Some(a) => a.d(brdf.alpha, n, h),
    };
    let spec = d * n.dot(h) / (4.0 * omega_o.dot(h).abs());
    (1.0 - ps) * cos_i * FRAC_1_PI + ps * spec
}

/// Samples an incoming direction at a surface seen from `omega_o` with three uniform numbers;
/// `None` when the sampled direction lies below the surface (its contribution is zero).
pub fn sample(brdf: &Brdf, n: Vec3, omega_o: Vec3, u: [f32; 3]) -> Option<(Vec3, f32)> {
    let cos_o = n.dot(omega_o);
    if cos_o <= 0.0 {
        return None;
    }
    let (t, b) = n.any_orthonormal_pair();
    let phi = 2.0 * PI * u[2];
    let omega_i = if u[0] < specular_probability(brdf, cos_o) {
        let h = match brdf.anisotropy {
            None => {
                // GGX: tan² θh = α² u / (1 - u), distributed as D(h) cos θh.
                let tan2 = brdf.alpha * brdf.alpha * u[1] / (1.0 - u[1]);
                let cos_h = 1.0 / (1.0 + tan2).sqrt();
                let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
                (t * phi.cos() + b * phi.sin()) * sin_h + n * cos_h
            }
            Some(a) => {
                // The slopes of the α = 1 lobe stretched by (α_t, α_b): distributed as the
                // anisotropic D(h) cos θh (Heitz 2014, section 5.4).
                let slope = (u[1] / (1.0 - u[1])).sqrt();
                let (x, y) = (
                    a.alpha_t * slope * phi.cos(),
                    brdf.alpha * slope * phi.sin(),
                );
                (a.tangent * x + n.cross(a.tangent) * y + n).normalize()
            }
        };
        2.0 * omega_o.dot(h) * h - omega_o
    } else {
        // Cosine-weighted hemisphere.
        let r = u[1].sqrt();
        (t * phi.cos() + b * phi.sin()) * r + n * (1.0 - u[1]).max(0.0).sqrt()
    };
    let p = pdf(brdf, n, omega_o, omega_i);
    (p > 0.0 && p.is_finite()).then_some((omega_i, p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_bounds::{Anisotropy, Fresnel};
    use slc_core::rng::uniform;

    /// The estimator f cos / pdf integrates the BRDF: its mean must equal the directional
    /// albedo computed by brute-force quadrature, which proves pdf and sample agree.
    #[test]
    fn sampling_is_unbiased_for_the_albedo() {
        let n = Vec3::Z;
        for &(alpha, alpha_t, kd, cos_o) in &[
            (0.2, None, 0.5, 0.8),
            (0.05, None, 0.0, 0.6),
            (1.0, None, 0.3, 0.3),
            (0.5, None, 0.7, 0.95),
            (0.05, Some(0.4), 0.0, 0.6),
            (0.3, Some(0.02), 0.2, 0.8),
        ] {
            let brdf = Brdf {
                kd: Vec3::splat(kd),
                fresnel: Fresnel::Schlick(Vec3::splat(0.9)),
                alpha,
                anisotropy: alpha_t.map(|alpha_t| Anisotropy {
                    tangent: Vec3::new(0.6, 0.8, 0.0),
                    alpha_t,
                }),
            };
            let omega_o = Vec3::new((1.0f32 - cos_o * cos_o).sqrt(), 0.0, cos_o);
            let m = 400_000u32;
            let mut est = 0.0f64;
            for k in 0..m {
                let u = [
                    uniform(1, k, 0, 0),
                    uniform(1, k, 0, 1),
                    uniform(1, k, 0, 2),
                ];
                if let Some((wi, p)) = sample(&brdf, n, omega_o, u) {
                    est += (brdf.eval(n, wi, omega_o).x * n.dot(wi) / p) as f64;
                }
            }
            est /= m as f64;
            // Quadrature over the hemisphere in (cos θ, φ), midpoint rule, dense near the peak.
            let (nt, np) = (2000, 1000);
            let mut quad = 0.0f64;
            for i in 0..nt {
                let c = (i as f64 + 0.5) / nt as f64;
                let s = (1.0 - c * c).sqrt();
                for j in 0..np {
                    let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / np as f64;
                    let wi = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32);
                    quad += brdf.eval(n, wi, omega_o).x as f64 * c;
                }
            }
            quad *= 2.0 * std::f64::consts::PI / (nt * np) as f64;
            assert!(
                (est - quad).abs() < 0.01 * quad.max(0.05),
                "alpha {alpha} {alpha_t:?}: sampled {est} vs quadrature {quad}"
            );
        }
    }
}
