//! The SG shading of VSGL eq. (2)-(5) in `f32`, for inner loops over many receiver-light pairs
//! (the CPU's VSGL shading), written once for one `f32` and for eight lanes ([`crate::lanes`]):
//! the forms of the GPU's `crates/gpu-wgpu/shaders/sg.wgsl`, which avoid the cancellations
//! plain `f32` would suffer (series for `expm1`, the Langevin function and the away-facing
//! irradiance at small sharpness, `1 − L(λ)` formed directly, the product's exponent
//! `d − λ1 − λ2` without cancelling; here `e^{−2λ}` is the square of `e^{−λ}` where the
//! GPU forms its own, within the rounding). Each branch is taken per lane ([`crate::branch!`]), and `e^x` is
//! [`crate::lanes::exp`], so a lane equals the scalar form bit for bit. The `f64` forms of the
//! sibling modules ([`SphericalGaussian::product`], [`SphericalGaussian::inner_product`],
//! [`SphericalGaussian::irradiance`], [`SgSurface::radiance`]) stay the reference: the tests
//! below hold these to them.
use crate::error::BoundsError;
use crate::lanes::{clamp01, dot, exp, max, min, normalize, Real};
use crate::sg::lobe::SphericalGaussian;
use crate::sg::shading::SgSurface;
use core::f32::consts::{PI, TAU};
use glam::Vec3;

/// An SG `c G(ω; ξ, λ)` in lanes of `R` (one lobe per lane): unit axis, sharpness, amplitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SgLanes<R> {
    pub axis: [R; 3],
    pub sharpness: R,
    pub amplitude: R,
}

/// `v` in every lane of `R`.
#[inline(always)]
pub fn splat3<R: Real>(v: Vec3) -> [R; 3] {
    [R::splat(v.x), R::splat(v.y), R::splat(v.z)]
}

/// `v` scaled by `k`, per component.
#[inline(always)]
fn scale<R: Real>(v: [R; 3], k: R) -> [R; 3] {
    [v[0] * k, v[1] * k, v[2] * k]
}

/// `u + v`, per component.
#[inline(always)]
fn add<R: Real>(u: [R; 3], v: [R; 3]) -> [R; 3] {
    [u[0] + v[0], u[1] + v[1], u[2] + v[2]]
}

/// Where `v` is finite (`0 v` is 0 only there, NaN at infinities and NaN).
#[inline(always)]
pub fn finite<R: Real>(v: R) -> R::Mask {
    let zero = R::splat(0.0);
    (v * zero).le(zero)
}

/// `e^x − 1`: its Taylor series to `x^10/10!` below `|x| = 1/2` (truncation below 3e-10 of the
/// value), `e^x − 1` above, where it does not cancel. (Plain products and sums where the
/// shader fuses them: without FMA in the target, `mul_add` is a library call.)
#[inline(always)]
fn expm1<R: Real>(x: R) -> R {
    let small = x.gt(R::splat(-0.5)) & R::splat(0.5).gt(x);
    crate::branch!(R, small, expm1_series(x), exp(x) - R::splat(1.0))
}

/// The Taylor series of [`expm1`], for `|x| < 1/2`.
#[inline(always)]
fn expm1_series<R: Real>(x: R) -> R {
    let mut t = R::splat(1.0 / 3_628_800.0);
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
        t = t * x + R::splat(c);
    }
    t * x
}

/// The exponentials of one sharpness `λ ≥ 0` that its integral, Langevin mean and away-facing
/// irradiance share (one `exp` for the three where each took its own): `e = e^{−λ}`,
/// `e2 = e^{−2λ}` as `e²` (from `e` raised to 2^−62 at least: `1 − e^{−2λ}` rounds to 1 below
/// that, and the square stays clear of subnormals, see `exp`), and `m2 = e^{−2λ} − 1` by
/// [`expm1`]'s series below `λ = 1/4`, `e2 − 1` above.
struct Decay<R> {
    l: R,
    e: R,
    e2: R,
    m2: R,
}

impl<R: Real> Decay<R> {
    #[inline(always)]
    fn new(sharpness: R) -> Self {
        let l = max(sharpness, R::splat(0.0));
        let e = exp(-l);
        let e_floor = max(e, R::splat(2.168_404_3e-19));
        let e2 = e_floor * e_floor;
        let m2 = crate::branch!(
            R,
            R::splat(0.25).gt(l),
            expm1_series(R::splat(-2.0) * l),
            e2 - R::splat(1.0)
        );
        Self { l, e, e2, m2 }
    }

    /// [`integral`] from the shared exponentials.
    #[inline(always)]
    fn integral(&self) -> R {
        let l = self.l;
        crate::branch!(R, l.gt(R::splat(20.0)), R::splat(TAU) / l, {
            crate::branch!(
                R,
                l.le(R::splat(0.0)),
                R::splat(4.0 * PI),
                -R::splat(TAU) * self.m2 / l,
            )
        })
    }
}

/// `A(λ) = 2π/λ (1 − e^{−2λ})` ([`crate::sg::sg_integral`]): `4π` at 0, `2π/λ` above 20.
#[inline(always)]
fn integral<R: Real>(sharpness: R) -> R {
    let l = max(sharpness, R::splat(0.0));
    crate::branch!(R, l.gt(R::splat(20.0)), R::splat(TAU) / l, {
        crate::branch!(
            R,
            l.le(R::splat(0.0)),
            R::splat(4.0 * PI),
            -R::splat(TAU) * expm1(R::splat(-2.0) * l) / l,
        )
    })
}

/// `(L, 1 − L)` of the Langevin function `L = coth λ − 1/λ`: below 1 its series (eight terms,
/// truncation below 1e-8 of the value); up to 20 with `coth = 1 + t`, `t = 2e/(1 − e)`,
/// `e = e^{−2λ}`, and `1 − L = 1/λ − t` formed directly; above 20, `1 − 1/λ` and `1/λ`.
#[inline(always)]
fn langevin<R: Real>(d: &Decay<R>) -> (R, R) {
    let (l, one) = (d.l, R::splat(1.0));
    crate::branch!(
        R,
        one.gt(l),
        {
            let l2 = l * l;
            let mut s = R::splat(-2.221_460_9e-8);
            for c in [
                2.192_594_8e-7,
                -2.164_404_3e-6,
                2.137_779_8e-5,
                -2.116_402_2e-4,
                2.116_402_1e-3,
                -2.222_222_3e-2,
                1.0 / 3.0,
            ] {
                s = s * l2 + R::splat(c);
            }
            let mean = s * l;
            (mean, one - mean)
        },
        {
            crate::branch!(R, l.gt(R::splat(20.0)), (one - one / l, one / l), {
                let t = R::splat(2.0) * d.e2 / -d.m2;
                ((one + t) - one / l, one / l - t)
            })
        },
    )
}

/// `b(λ) = E(λ, −1)`, the irradiance facing away: `1/4 − λ/6` below 1e-3, the closed form from
/// 1 on, and between them its numerator `1 − e^{−λ}(1 + λ)` by its series to `k = 12`
/// (truncation below 1e-8 of the value).
#[inline(always)]
fn away_facing<R: Real>(d: &Decay<R>) -> R {
    let (l, e, one) = (d.l, d.e, R::splat(1.0));
    crate::branch!(
        R,
        R::splat(1e-3).gt(l),
        R::splat(0.25) - l / R::splat(6.0),
        {
            crate::branch!(
                R,
                one.le(l),
                e * (one - e * (one + l)) / (l * (one - d.e2)),
                {
                    let mut s = R::splat(2.296_443_2e-8);
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
                        s = s * l + R::splat(c);
                    }
                    e * (l * s) / -d.m2
                },
            )
        },
    )
}

/// `c0` of Hill's fit ([`crate::sg::normalized_sg_irradiance`]).
const HILL_C0: f32 = 0.36;

/// Hill's `y(μ)` for `x = √(1 − L(λ))`, the `f32` form of `crate::sg::irradiance::hill_y`.
#[inline(always)]
fn hill_y<R: Real>(x: R, mu: R) -> R {
    let switch = 4.0 * HILL_C0 * HILL_C0;
    crate::branch!(
        R,
        R::splat(switch).le(x),
        {
            let a =
                R::splat(0.25) + R::splat(0.25) * (x - R::splat(switch)) / R::splat(1.0 - switch);
            a + R::splat(0.5) * mu + (R::splat(0.5) - a) * mu * mu
        },
        {
            let (x0, x1) = (R::splat(HILL_C0) * mu, x / R::splat(4.0 * HILL_C0));
            let zero = R::splat(0.0);
            let inside = x.gt(zero) & x0.le(x1) & (-x0).le(x1);
            let t = x0 + x1;
            R::select(inside, t * t / x, max(mu, zero))
        },
    )
}

/// What `E(λ, μ)` needs of λ alone, for many cosines μ with one sharpness (a VSGL's diffuse
/// lobe against every receiver): the Langevin mean length `L(λ)`, Hill's `x = √(1 − L)` and the
/// away-facing `b(λ)`. One sharpness per lane of `R`; the fields are public so that fits made
/// one at a time can be packed into lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IrradianceFit<R = f32> {
    /// `L(λ)`.
    pub mean: R,
    /// `x = √(1 − L(λ))`.
    pub x: R,
    /// `b(λ)`.
    pub away: R,
}

impl<R: Real> IrradianceFit<R> {
    /// The fit of sharpness `sharpness` (negative or NaN taken as 0).
    #[inline(always)]
    pub fn new(sharpness: R) -> Self {
        Self::of(&Decay::new(sharpness))
    }

    #[inline(always)]
    fn of(d: &Decay<R>) -> Self {
        let (mean, rest) = langevin(d);
        Self {
            mean,
            x: max(rest, R::splat(0.0)).sqrt(),
            away: away_facing(d),
        }
    }

    /// `E(λ, μ)`, the normalized irradiance of [`crate::sg::normalized_sg_irradiance`] (Hill's
    /// fit with exact limits), clamped to `[0, 1]`.
    #[inline(always)]
    pub fn at(&self, mu: R) -> R {
        let y = hill_y(self.x, min(max(mu, R::splat(-1.0)), R::splat(1.0)));
        clamp01(self.mean * y + self.away)
    }
}

/// The combined lobe of two SGs with unit axes: `λa ξa + λb ξb`, its length `d` (scaled by the
/// larger sharpness first, so that squares cannot overflow) and the exponent
/// `d − λa − λb = −λa (λb/(d + λa + λb)) |ξa − ξb|²`, free of cancellation.
struct Merged<R> {
    axis_sum: [R; 3],
    sharpness: R,
    log_scale: R,
}

impl<R: Real> Merged<R> {
    #[inline(always)]
    fn of(a: &SgLanes<R>, b: &SgLanes<R>) -> Self {
        let (la, lb) = (a.sharpness, b.sharpness);
        let zero = R::splat(0.0);
        let axis_sum = add(scale(a.axis, la), scale(b.axis, lb));
        let m = max(la, lb);
        let w = add(scale(a.axis, la / m), scale(b.axis, lb / m));
        let d = R::select(m.gt(zero), m * dot(w, w).sqrt(), zero);
        let total = d + la + lb;
        let gap = [
            a.axis[0] - b.axis[0],
            a.axis[1] - b.axis[1],
            a.axis[2] - b.axis[2],
        ];
        let log_scale = R::select(total.gt(zero), -la * (lb / total) * dot(gap, gap), zero);
        Self {
            axis_sum,
            sharpness: d,
            log_scale,
        }
    }
}

impl<R: Real> SgLanes<R> {
    /// One lobe in every lane.
    #[inline(always)]
    pub fn splat(sg: &SphericalGaussian) -> Self {
        Self {
            axis: splat3(sg.axis),
            sharpness: R::splat(sg.sharpness),
            amplitude: R::splat(sg.amplitude),
        }
    }

    /// [`SphericalGaussian::product`] (unit axes taken as given), and the lanes where the
    /// sharpness or amplitude leaves `f32` (the overflow the `f64` form reports).
    #[inline(always)]
    pub fn product(&self, other: &Self) -> (Self, R::Mask) {
        let m = Merged::of(self, other);
        let zero = R::splat(0.0);
        let amplitude = self.amplitude * other.amplitude * exp(m.log_scale);
        let overflow = !(finite(m.sharpness) & finite(amplitude));
        let sharp = m.sharpness.gt(zero);
        // normalize(axis_sum / d) as glam forms it, kept only where finite.
        let v = scale(m.axis_sum, R::splat(1.0) / m.sharpness);
        let v = normalize(v);
        let keep = sharp & finite(v[0]) & finite(v[1]) & finite(v[2]);
        let axis = [
            R::select(keep, v[0], self.axis[0]),
            R::select(keep, v[1], self.axis[1]),
            R::select(keep, v[2], self.axis[2]),
        ];
        let lobe = Self {
            axis,
            sharpness: R::select(sharp, m.sharpness, zero),
            amplitude,
        };
        (lobe, overflow)
    }

    /// [`SphericalGaussian::inner_product`], saturated at `f32::MAX`.
    #[inline(always)]
    pub fn inner_product(&self, other: &Self) -> R {
        let m = Merged::of(self, other);
        let v = self.amplitude * other.amplitude * exp(m.log_scale) * integral(m.sharpness);
        min(v, R::splat(f32::MAX))
    }

    /// [`SphericalGaussian::irradiance`] for the unit normal `n`, saturated at `f32::MAX`.
    #[inline(always)]
    pub fn irradiance(&self, n: [R; 3]) -> R {
        let d = Decay::new(self.sharpness);
        let e = IrradianceFit::of(&d).at(dot(self.axis, n));
        min(self.amplitude * d.integral() * e, R::splat(f32::MAX))
    }
}

impl SgSurface {
    /// [`SgSurface::radiance`] of the light in each lane, with the `f32` forms, each term
    /// saturated at `f32::MAX`.
    #[inline(always)]
    pub fn radiance_lanes<R: Real>(&self, light: &SgLanes<R>) -> [R; 3] {
        let big = R::splat(f32::MAX);
        let irradiance = light.irradiance(splat3(self.normal));
        let lobe = &self.specular;
        let inner = light.inner_product(&SgLanes::splat(&lobe.lobe));
        let mut out = [big; 3];
        for (c, out) in out.iter_mut().enumerate() {
            let diffuse = min(R::splat(self.kd_over_pi[c]) * irradiance, big);
            let specular = min(R::splat(lobe.weight[c]) * inner, big);
            *out = min(diffuse + specular, big);
        }
        out
    }

    /// [`SgSurface::radiance`] with the `f32` forms ([`SgSurface::radiance_lanes`] for one
    /// light).
    pub fn radiance_f32(&self, light: &SphericalGaussian) -> Vec3 {
        Vec3::from(self.radiance_lanes::<f32>(&SgLanes::splat(light)))
    }
}

impl SphericalGaussian {
    /// [`SphericalGaussian::product`] in `f32` (unit axes taken as given): the same
    /// [`BoundsError::Overflow`] where the sharpness or amplitude leaves `f32`.
    pub fn product_f32(&self, other: &Self) -> Result<Self, BoundsError> {
        let (p, overflow) = SgLanes::<f32>::splat(self).product(&SgLanes::splat(other));
        if overflow {
            return Err(BoundsError::Overflow("SG product"));
        }
        Ok(Self {
            axis: Vec3::from(p.axis),
            sharpness: p.sharpness,
            amplitude: p.amplitude,
        })
    }

    /// [`SphericalGaussian::inner_product`] in `f32`, saturated at `f32::MAX`.
    pub fn inner_product_f32(&self, other: &Self) -> f32 {
        SgLanes::<f32>::splat(self).inner_product(&SgLanes::splat(other))
    }

    /// [`SphericalGaussian::irradiance`] in `f32`, saturated at `f32::MAX`.
    pub fn irradiance_f32(&self, n: Vec3) -> f32 {
        SgLanes::<f32>::splat(self).irradiance(splat3(n))
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

    /// Eight lobes, one per lane, from eight scalar ones.
    fn gather<R: crate::lanes::Lanes8>(lobes: &[SphericalGaussian; 8]) -> SgLanes<R> {
        use crate::lanes::F8;
        let lane = |f: &dyn Fn(&SphericalGaussian) -> f32| R::load(&F8(lobes.each_ref().map(f)));
        SgLanes {
            axis: [
                lane(&|l| l.axis.x),
                lane(&|l| l.axis.y),
                lane(&|l| l.axis.z),
            ],
            sharpness: lane(&|l| l.sharpness),
            amplitude: lane(&|l| l.amplitude),
        }
    }

    /// The product, irradiance and a surface's radiance of eight lobes at once, lane by lane as
    /// bit patterns (`R` of the lanes); `products` and `mask bits` of the products' overflow.
    fn lanes_of<R: crate::lanes::Lanes8>(
        lights: &[SphericalGaussian; 8],
        others: &[SphericalGaussian; 8],
        surface: &SgSurface,
        n: Vec3,
    ) -> Vec<u32> {
        let (a, b) = (gather::<R>(lights), gather::<R>(others));
        let (p, overflow) = a.product(&b);
        let mut out = vec![u32::from(R::bits(overflow))];
        let radiance = surface.radiance_lanes(&a);
        for v in [
            p.axis[0],
            p.axis[1],
            p.axis[2],
            p.sharpness,
            p.amplitude,
            a.inner_product(&b),
            a.irradiance(splat3(n)),
            radiance[0],
            radiance[1],
            radiance[2],
        ] {
            out.extend(v.store().0.map(f32::to_bits));
        }
        out
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn avx_lanes_of(
        lights: &[SphericalGaussian; 8],
        others: &[SphericalGaussian; 8],
        surface: &SgSurface,
        n: Vec3,
    ) -> Vec<u32> {
        lanes_of::<crate::lanes_avx::A8>(lights, others, surface, n)
    }

    /// The lanes (plain arrays and, where the CPU has AVX2, AVX registers) equal the scalar
    /// forms bit for bit, over lobes from 1e-4 to 1e4 in sharpness with extremes mixed in (0,
    /// 1e30, coincident and opposite axes, amplitudes that overflow the product), so that
    /// lanes of one vector take different branches.
    #[test]
    fn lanes_equal_the_scalar_forms_bit_for_bit() {
        let mut rng = Rng::new(73);
        let extreme = |rng: &mut Rng| {
            let mut l = lobe(rng);
            match (rng.f32() * 8.0) as u32 {
                0 => l.sharpness = 0.0,
                1 => l.sharpness = 1e30,
                2 => l.amplitude = 3e38,
                3 => l.sharpness = 10f32.powf(rng.range(-4.0, -2.0)),
                4 => l.sharpness = rng.range(0.9, 1.1),
                5 => l.sharpness = rng.range(19.0, 21.0),
                _ => {}
            }
            l
        };
        for _ in 0..5_000 {
            let lights: [SphericalGaussian; 8] = core::array::from_fn(|_| extreme(&mut rng));
            let mut others: [SphericalGaussian; 8] = core::array::from_fn(|_| extreme(&mut rng));
            others[0].axis = lights[0].axis;
            others[1].axis = -lights[1].axis;
            let n = rng.unit();
            let brdf = crate::brdf::Brdf {
                kd: Vec3::new(rng.f32(), 0.5, 0.0),
                fresnel: Fresnel::Schlick(Vec3::splat(rng.f32())),
                alpha: 10f32.powf(rng.range(-3.0, 0.0)),
                anisotropy: None,
            };
            let surface = SgSurface::new(n, (n + rng.unit()).normalize(), &brdf).unwrap();
            // The scalar forms, lane by lane, in the layout of `lanes_of`.
            let mut want = vec![0u32; 1 + 10 * 8];
            for k in 0..8 {
                let (a, b) = (&lights[k], &others[k]);
                let (p, overflow) = SgLanes::<f32>::splat(a).product(&SgLanes::splat(b));
                want[0] |= u32::from(overflow) << k;
                let r = surface.radiance_f32(a);
                let values = [
                    p.axis[0],
                    p.axis[1],
                    p.axis[2],
                    p.sharpness,
                    p.amplitude,
                    a.inner_product_f32(b),
                    a.irradiance_f32(n),
                    r.x,
                    r.y,
                    r.z,
                ];
                for (i, v) in values.iter().enumerate() {
                    want[1 + 8 * i + k] = v.to_bits();
                }
            }
            let plain = lanes_of::<crate::lanes::F8>(&lights, &others, &surface, n);
            assert_eq!(plain, want, "{lights:?} {others:?}");
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: AVX2 was detected just above.
                let wide = unsafe { avx_lanes_of(&lights, &others, &surface, n) };
                assert_eq!(wide, want, "{lights:?} {others:?}");
            }
        }
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
