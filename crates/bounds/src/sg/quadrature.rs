//! Numerical integration over the sphere in `f64`, the reference for every closed form of
//! this module (tests only).
use crate::sg::lobe::SphericalGaussian;
use crate::sg::specular_fit::GAUSS;
use core::f64::consts::PI;
use glam::DVec3;

/// Panels of the composite Gauss-Legendre rule in θ, for each of the two pieces.
const PANELS: usize = 100;
/// Azimuthal resolution (midpoint rule, spectrally accurate for periodic integrands).
const N_PHI: usize = 96;

/// `∫_{S²} f(ω) dω` in polar coordinates around `axis`: composite 4-point Gauss-Legendre in θ
/// on `[0, c]` and `[c, π]` with `c = min(12w, π/2)`, so that a lobe of angular width about `w`
/// around `axis` is resolved as finely as the rest of the sphere, and the midpoint rule in φ.
pub(crate) fn sphere_integral(axis: DVec3, w: f64, mut f: impl FnMut(DVec3) -> f64) -> f64 {
    let axis = axis.normalize();
    let (x, y) = axis.any_orthonormal_pair();
    let c = (12.0 * w).min(0.5 * PI);
    let mut sum = 0.0;
    for (lo, hi) in [(0.0, c), (c, PI)] {
        let h = (hi - lo) / PANELS as f64;
        for p in 0..PANELS {
            let mid = lo + (p as f64 + 0.5) * h;
            for (node, weight) in GAUSS {
                let theta = mid + 0.5 * h * node;
                let (s, co) = theta.sin_cos();
                let mut ring = 0.0;
                for j in 0..N_PHI {
                    let phi = 2.0 * PI * (j as f64 + 0.5) / N_PHI as f64;
                    ring += f(axis * co + (x * phi.cos() + y * phi.sin()) * s);
                }
                sum += ring * s * weight * 0.5 * h;
            }
        }
    }
    sum * 2.0 * PI / N_PHI as f64
}

/// The angular width `1/sqrt(λ)` of a lobe of sharpness λ, at most 1.
pub(crate) fn width(sharpness: f64) -> f64 {
    (1.0 / sharpness.sqrt()).min(1.0)
}

/// The lobe `c exp(λ(ω·ξ − 1))` in `f64`, from the definition of VSGL section 2.2, with the
/// axis renormalised in `f64` (an `f32` unit vector is off by ~6e-8, i.e. 6e-4 at λ = 1e4).
pub(crate) fn eval64(sg: &SphericalGaussian, w: DVec3) -> f64 {
    let axis = sg.axis.as_dvec3().normalize();
    f64::from(sg.amplitude) * (f64::from(sg.sharpness) * (w.dot(axis) - 1.0)).exp()
}

#[test]
fn integrates_polynomials_exactly() {
    let axis = DVec3::new(1.0, 2.0, -0.5);
    for w in [1.0, 0.1, 0.003] {
        let area = sphere_integral(axis, w, |_| 1.0);
        let z2 = sphere_integral(axis, w, |v| v.z * v.z);
        assert!((area / (4.0 * PI) - 1.0).abs() < 1e-5, "{w}: {area}");
        assert!((z2 / (4.0 * PI / 3.0) - 1.0).abs() < 1e-5, "{w}: {z2}");
    }
}
