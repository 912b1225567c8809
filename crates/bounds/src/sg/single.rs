//! The SG shading of VSGL eq. (2)-(5) in `f32`, for inner loops over many receiver-light pairs
//! (the CPU's VSGL shading): the forms of the GPU's `crates/gpu-wgpu/shaders/sg.wgsl`, which
//! avoid the cancellations plain `f32` would suffer (series for `expm1`, the Langevin function
//! and the away-facing irradiance at small sharpness, `1 − L(λ)` formed directly, the product's
//! exponent `d − λ1 − λ2` without cancelling). The `f64` forms of the sibling modules
//! ([`SphericalGaussian::product`], [`SphericalGaussian::inner_product`],
//! [`SphericalGaussian::irradiance`], [`SgSurface::radiance`]) stay the reference: the tests
//! below hold these to them.
use crate::error::BoundsError;
use crate::sg::irradiance::hill_y;
use crate::sg::lobe::SphericalGaussian;
use crate::sg::shading::SgSurface;
use core::f32::consts::{PI, TAU};
use glam::Vec3;

/// `e^x − 1`: its Taylor series to `x^10/10!` below `|x| = 1/2` (truncation below 3e-10 of the
/// value), `e^x − 1` above, where it does not cancel. (Plain products and sums where the
/// shader fuses them: without FMA in the target, `mul_add` is a library call.)
fn expm1(x: f32) -> f32 {
    if x.abs() < 0.5 {
        let mut t: f32 = 1.0 / 3_628_800.0;
        for c in [
            1.0 / 362_880.0,
            1.0 / 40_320.0,
            1.0 / 5_040.0,
            1.0 / 720.0,
            1.0 / 120.0,
            1.0 / 24.0,
            1.0 / 6.0,
            0.5,
            1.0,
        ] {
            t = t * x + c;
        }
        return t * x;
    }
    x.exp() - 1.0
}

/// `A(λ) = 2π/λ (1 − e^{−2λ})` ([`crate::sg::sg_integral`]): `4π` at 0, `2π/λ` above 20.
fn integral(sharpness: f32) -> f32 {
    let l = sharpness.max(0.0);
    if l == 0.0 {
        4.0 * PI
    } else if l > 20.0 {
        TAU / l
    } else {
        -TAU * expm1(-2.0 * l) / l
    }
}

/// `(L, 1 − L)` of the Langevin function `L = coth λ − 1/λ`: below 1 its series (eight terms,
/// truncation below 1e-8 of the value); up to 20 with `coth = 1 + t`, `t = 2e/(1 − e)`,
/// `e = e^{−2λ}`, and `1 − L = 1/λ − t` formed directly; above 20, `1 − 1/λ` and `1/λ`.
fn langevin(l: f32) -> (f32, f32) {
    if l < 1.0 {
        let l2 = l * l;
        let mut s: f32 = -2.221_460_9e-8;
        for c in [
            2.192_594_8e-7,
            -2.164_404_3e-6,
            2.137_779_8e-5,
            -2.116_402_2e-4,
            2.116_402_1e-3,
            -2.222_222_3e-2,
            1.0 / 3.0,
        ] {
            s = s * l2 + c;
        }
        let mean = s * l;
        return (mean, 1.0 - mean);
    }
    if l > 20.0 {
        return (1.0 - 1.0 / l, 1.0 / l);
    }
    let e = (-2.0 * l).exp();
    let t = 2.0 * e / (1.0 - e);
    ((1.0 + t) - 1.0 / l, 1.0 / l - t)
}

/// `b(λ) = E(λ, −1)`, the irradiance facing away: `1/4 − λ/6` below 1e-3, the closed form from
/// 1 on, and between them its numerator `1 − e^{−λ}(1 + λ)` by its series to `k = 12`
/// (truncation below 1e-8 of the value).
fn away_facing(l: f32) -> f32 {
    if l < 1e-3 {
        return 0.25 - l / 6.0;
    }
    let e = (-l).exp();
    if l >= 1.0 {
        return e * (1.0 - e * (1.0 + l)) / (l * (1.0 - e * e));
    }
    let mut s: f32 = 2.296_443_2e-8;
    for c in [
        -2.505_210_8e-7,
        2.480_158_6e-6,
        -2.204_585_5e-5,
        1.736_111_2e-4,
        -1.190_476_2e-3,
        6.944_444_5e-3,
        -3.333_333_5e-2,
        0.125,
        -1.0 / 3.0,
        0.5,
    ] {
        s = s * l + c;
    }
    e * (l * s) / -expm1(-2.0 * l)
}

/// What `E(λ, μ)` needs of λ alone, for many cosines μ with one sharpness (a VSGL's diffuse
/// lobe against every receiver): the Langevin mean length `L(λ)`, Hill's `x = √(1 − L)` and the
/// away-facing `b(λ)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IrradianceFit {
    mean: f32,
    x: f32,
    away: f32,
}

impl IrradianceFit {
    /// The fit of sharpness `sharpness` (negative or NaN taken as 0).
    pub fn new(sharpness: f32) -> Self {
        let l = sharpness.max(0.0);
        let (mean, rest) = langevin(l);
        Self {
            mean,
            x: rest.max(0.0).sqrt(),
            away: away_facing(l),
        }
    }

    /// `E(λ, μ)`, the normalized irradiance of [`crate::sg::normalized_sg_irradiance`] (Hill's
    /// fit with exact limits, its `y(μ)` shared), clamped to `[0, 1]`.
    pub fn at(&self, mu: f32) -> f32 {
        let y = hill_y(f64::from(self.x), f64::from(mu.clamp(-1.0, 1.0))) as f32;
        (self.mean * y + self.away).clamp(0.0, 1.0)
    }
}

/// The combined lobe of two SGs with unit axes: `λa ξa + λb ξb`, its length `d` (scaled by the
/// larger sharpness first, so that squares cannot overflow) and the exponent
/// `d − λa − λb = −λa (λb/(d + λa + λb)) |ξa − ξb|²`, free of cancellation.
struct Merged {
    axis_sum: Vec3,
    sharpness: f32,
    log_scale: f32,
}

impl Merged {
    fn of(a: &SphericalGaussian, b: &SphericalGaussian) -> Self {
        let (la, lb) = (a.sharpness, b.sharpness);
        let axis_sum = a.axis * la + b.axis * lb;
        let m = la.max(lb);
        let d = if m > 0.0 {
            m * (a.axis * (la / m) + b.axis * (lb / m)).length()
        } else {
            0.0
        };
        let total = d + la + lb;
        let log_scale = if total > 0.0 {
            -la * (lb / total) * (a.axis - b.axis).length_squared()
        } else {
            0.0
        };
        Self {
            axis_sum,
            sharpness: d,
            log_scale,
        }
    }
}

impl SphericalGaussian {
    /// [`SphericalGaussian::product`] in `f32` (unit axes taken as given): the same
    /// [`BoundsError::Overflow`] where the sharpness or amplitude leaves `f32`.
    pub fn product_f32(&self, other: &Self) -> Result<Self, BoundsError> {
        let m = Merged::of(self, other);
        let amplitude = self.amplitude * other.amplitude * m.log_scale.exp();
        if !(m.sharpness.is_finite() && amplitude.is_finite()) {
            return Err(BoundsError::Overflow("SG product"));
        }
        if m.sharpness > 0.0 {
            let v = (m.axis_sum / m.sharpness).normalize();
            Ok(Self {
                axis: if v.is_finite() { v } else { self.axis },
                sharpness: m.sharpness,
                amplitude,
            })
        } else {
            Ok(Self {
                axis: self.axis,
                sharpness: 0.0,
                amplitude,
            })
        }
    }

    /// [`SphericalGaussian::inner_product`] in `f32`, saturated at `f32::MAX`.
    pub fn inner_product_f32(&self, other: &Self) -> f32 {
        let m = Merged::of(self, other);
        (self.amplitude * other.amplitude * m.log_scale.exp() * integral(m.sharpness)).min(f32::MAX)
    }

    /// [`SphericalGaussian::irradiance`] in `f32`, saturated at `f32::MAX`.
    pub fn irradiance_f32(&self, n: Vec3) -> f32 {
        let e = IrradianceFit::new(self.sharpness).at(self.axis.dot(n));
        (self.amplitude * integral(self.sharpness) * e).min(f32::MAX)
    }
}

impl SgSurface {
    /// [`SgSurface::radiance`] with the `f32` forms, each term saturated at `f32::MAX`.
    pub fn radiance_f32(&self, light: &SphericalGaussian) -> Vec3 {
        let max = Vec3::splat(f32::MAX);
        let diffuse = (self.kd_over_pi * light.irradiance_f32(self.normal)).min(max);
        let lobe = &self.specular;
        let specular = (lobe.weight * light.inner_product_f32(&lobe.lobe)).min(max);
        (diffuse + specular).min(max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brdf::Brdf;
    use crate::fresnel::Fresnel;
    use crate::test_util::Rng;

    /// A lobe of random axis, sharpness from 1e-4 to 1e4 and amplitude from 1e-3 to 1e3.
    fn lobe(rng: &mut Rng) -> SphericalGaussian {
        SphericalGaussian::new(
            rng.unit(),
            10f32.powf(rng.range(-4.0, 4.0)),
            10f32.powf(rng.range(-3.0, 3.0)),
        )
        .unwrap()
    }

    /// `|a − b|` within `tol` of `|b|` plus `floor`.
    fn close(a: f32, b: f32, tol: f32, floor: f32) -> bool {
        (a - b).abs() <= tol * b.abs() + floor
    }

    /// The normalized irradiance against the f64 form over sharpness 1e-5…1e5 and every
    /// cosine, including each branch's edges.
    #[test]
    fn normalized_irradiance_matches_the_f64_form() {
        let mut worst = 0.0f32;
        let mut ls: Vec<f32> = (0..=100)
            .map(|i| 10f32.powf(-5.0 + 0.1 * i as f32))
            .collect();
        ls.extend(
            [1e-3, 1.0, 20.0]
                .iter()
                .flat_map(|&e: &f32| [e * 0.999, e, e * 1.001]),
        );
        for l in ls {
            for k in 0..=40 {
                let mu = -1.0 + 0.05 * k as f32;
                let want = crate::sg::normalized_sg_irradiance(l, mu);
                let got = IrradianceFit::new(l).at(mu);
                assert!(
                    close(got, want, 2e-5, 1e-7),
                    "λ {l} μ {mu}: {got} vs {want}"
                );
                worst = worst.max((got - want).abs() / want.max(1e-7));
            }
        }
        println!("normalized irradiance: worst relative error {worst:.2e}");
    }

    /// Products, inner products and irradiance against the f64 forms over random lobes: the
    /// same lobe within 1e-5 (axis 1e-5, sharpness and amplitude relative), the same values
    /// within 2e-5 relative (the irradiance plus 1e-6 of the lobe's whole).
    #[test]
    fn products_and_irradiance_match_the_f64_forms() {
        let mut rng = Rng::new(71);
        for _ in 0..20_000 {
            let (a, b) = (lobe(&mut rng), lobe(&mut rng));
            let want = a.product(&b).unwrap();
            let got = a.product_f32(&b).unwrap();
            assert!((got.axis - want.axis).length() <= 1e-5, "{a:?} {b:?}");
            assert!(
                close(got.sharpness, want.sharpness, 1e-5, 0.0),
                "{a:?} {b:?}"
            );
            assert!(
                close(got.amplitude, want.amplitude, 2e-5, 1e-30),
                "{a:?} {b:?}"
            );
            let (ip, want_ip) = (a.inner_product_f32(&b), a.inner_product(&b));
            assert!(
                close(ip, want_ip, 2e-5, 1e-30),
                "{a:?} {b:?}: {ip} vs {want_ip}"
            );
            // Near the horizon of a sharp lobe Hill's fit loses digits in f32: there the
            // error is held to 1e-6 of the lobe's whole irradiance c A(λ).
            let n = rng.unit();
            let (e, want_e) = (a.irradiance_f32(n), a.irradiance(n));
            let whole = a.amplitude * crate::sg::sg_integral(a.sharpness);
            assert!(
                close(e, want_e, 2e-5, 1e-6 * whole),
                "{a:?} {n}: {e} vs {want_e}"
            );
        }
        // Sharp lobes far apart: the product vanishes, without NaN.
        let a = SphericalGaussian::new(Vec3::Z, 1e4, 1.0).unwrap();
        let b = SphericalGaussian::new(-Vec3::Z, 1e4, 1.0).unwrap();
        assert_eq!(a.inner_product_f32(&b), 0.0);
        assert_eq!(a.product_f32(&b).unwrap().amplitude, 0.0);
        // Beyond f32: an overflow error, as the f64 form.
        let big = SphericalGaussian::new(Vec3::Z, 1.0, 3e38).unwrap();
        assert!(big.product_f32(&big).is_err() && big.product(&big).is_err());
    }

    /// A surface's reflected radiance against the f64 form, over rough and sharp GGX lobes,
    /// views from normal to grazing and random lights (within 3e-5, plus 1e-6 of the light's
    /// whole irradiance near horizons).
    #[test]
    fn surface_radiance_matches_the_f64_form() {
        let mut rng = Rng::new(72);
        for _ in 0..5_000 {
            let n = rng.unit();
            let cos = rng.range(1e-4, 1.0);
            let t = n.any_orthonormal_vector();
            let omega_o = (n * cos + t * (1.0 - cos * cos).sqrt()).normalize();
            let brdf = Brdf {
                kd: Vec3::new(rng.f32(), 0.5, 0.0),
                fresnel: Fresnel::Schlick(Vec3::splat(rng.f32())),
                alpha: 10f32.powf(rng.range(-3.0, 0.0)),
                anisotropy: None,
            };
            let surface = SgSurface::new(n, omega_o, &brdf).unwrap();
            let light = lobe(&mut rng);
            let (got, want) = (surface.radiance_f32(&light), surface.radiance(&light));
            let whole = light.amplitude * crate::sg::sg_integral(light.sharpness);
            for c in 0..3 {
                assert!(
                    close(got[c], want[c], 3e-5, 1e-6 * whole),
                    "{brdf:?} cos {cos} {light:?}: {got} vs {want}"
                );
            }
        }
    }
}
