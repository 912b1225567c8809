//! The lanes against [`BoxBound::glossy`] one lobe at a time, bit for bit, over raw inputs at
//! the extremes and outside the domain: every lobe `GlossyLobe::new` accepts is bounded the
//! same, every one it refuses is left to the caller.
use super::*;
use crate::box_bound::tests::{incident, random_params};
use crate::lanes::Lanes8;
use crate::test_util::Rng;
use crate::GlossyLobe;

/// A raw input to `GlossyLobe::new`: a unit vector (or a vector within and just outside
/// its tolerance, NaN, infinite or zero); α from 1e-4 to 1 (or 0, above 1, subnormal, NaN);
/// ωi from normal to grazing incidence and below the surface; flux from 1e-6 to 1e6 (or
/// negative, zero of either sign, infinite); F0 in [0, 1] (or just outside).
struct Raw {
    normal: Vec3,
    omega_i: Vec3,
    alpha: f32,
    flux: Vec3,
    f0: Vec3,
}

fn spoil(rng: &mut Rng, v: Vec3) -> Vec3 {
    match rng.u64() % 24 {
        0 => Vec3::new(f32::NAN, v.y, v.z),
        1 => Vec3::new(v.x, f32::INFINITY, v.z),
        2 => Vec3::ZERO,
        3 => v * (1.0 + 1.001e-3),
        4 => v * (1.0 - 1.001e-3),
        5..=10 => v * (1.0 + rng.range(-0.999e-3, 0.999e-3)),
        _ => v,
    }
}

fn raw(rng: &mut Rng) -> Raw {
    let n = rng.unit();
    let omega_i = incident(rng, n, true);
    let alpha = match rng.u64() % 12 {
        0 => 0.0,
        1 => 1.0,
        2 => 1.0 + 1e-6,
        3 => 1e-40,
        4 => f32::NAN,
        _ => 10f32.powf(rng.range(-4.0, 0.0)),
    };
    let scale = 10f32.powf(rng.range(-6.0, 6.0));
    let flux = match rng.u64() % 12 {
        0 => Vec3::new(-1e-6, 1.0, 1.0),
        1 => Vec3::ZERO,
        2 => Vec3::new(-0.0, 0.0, 0.5),
        3 => Vec3::new(1.0, f32::INFINITY, 1.0),
        _ => Vec3::new(rng.f32(), rng.f32(), rng.f32()) * scale,
    };
    let f0 = match rng.u64() % 10 {
        0 => Vec3::new(rng.f32(), 1.0 + 1e-6, rng.f32()),
        1 => Vec3::new(-1e-9, rng.f32(), rng.f32()),
        2 => Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 1e-3,
        3 => Vec3::ONE,
        _ => Vec3::new(rng.f32(), rng.f32(), rng.f32()),
    };
    Raw {
        normal: spoil(rng, n),
        omega_i: spoil(rng, omega_i),
        alpha,
        flux,
        f0,
    }
}

/// What a caller gets one lobe at a time (an untilted, isotropic VPL's `glossy_lobe`).
fn one_at_a_time(r: &Raw, params: &StochasticParams) -> Option<BoxBound> {
    let lobe = GlossyLobe::new(
        Vec3::ZERO,
        r.normal,
        r.omega_i,
        r.alpha,
        r.flux,
        Fresnel::Schlick(r.f0),
    )
    .and_then(|l| l.with_geometric_normal(r.normal))
    .and_then(|l| l.with_anisotropy(None))
    .ok()?;
    Some(BoxBound::glossy(&lobe, params))
}

fn lanes<L: Lanes8>(group: &[Raw; 8]) -> SchlickLobes<L> {
    let load3 = |get: fn(&Raw) -> Vec3| {
        [0, 1, 2].map(|c| L::load(&F8(core::array::from_fn(|k| get(&group[k])[c]))))
    };
    SchlickLobes {
        normal: load3(|r| r.normal),
        omega_i: load3(|r| r.omega_i),
        alpha: L::load(&F8(core::array::from_fn(|k| group[k].alpha))),
        flux: load3(|r| r.flux),
        f0: load3(|r| r.f0),
    }
}

/// The bounds handed on, as `{:?}` strings (bit for bit: the shortest digits that round
/// trip, and the sign of a zero).
fn handed<L: Lanes8>(
    group: &[Raw; 8],
    wanted: u8,
    params: &[StochasticParams],
) -> (u8, Vec<Option<String>>) {
    let mut out = vec![None; 8];
    let lanes = lanes::<L>(group).box_bounds(wanted, params, |k, b| {
        assert!(out[k].replace(format!("{b:?}")).is_none(), "lane {k} twice");
    });
    (lanes, out)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn handed_avx2(
    group: &[Raw; 8],
    wanted: u8,
    params: &[StochasticParams],
) -> (u8, Vec<Option<String>>) {
    handed::<crate::lanes_avx::A8>(group, wanted, params)
}

#[test]
fn eight_at_a_time_equal_one_at_a_time_bit_for_bit() {
    let mut rng = Rng::new(0x5c41_1c4e);
    let (mut bounded, mut refused) = (0, 0);
    for round in 0..20_000 {
        let group: [Raw; 8] = core::array::from_fn(|_| raw(&mut rng));
        let params: Vec<StochasticParams> = (0..8).map(|_| random_params(&mut rng)).collect();
        // Fewer roulettes than lanes in some groups, and not every lane wanted.
        let len = if round % 5 == 0 { 1 + round % 8 } else { 8 };
        let wanted = if round % 3 == 0 {
            rng.u64() as u8
        } else {
            0xff
        };
        let params = &params[..len];
        let expected: Vec<Option<String>> = (0..8)
            .map(|k| {
                let on = k < len && wanted >> k & 1 == 1;
                on.then(|| one_at_a_time(&group[k], &params[k]).map(|b| format!("{b:?}")))
                    .flatten()
            })
            .collect();
        let bits = expected
            .iter()
            .enumerate()
            .fold(0u8, |m, (k, e)| m | u8::from(e.is_some()) << k);
        assert_eq!(
            handed::<F8>(&group, wanted, params),
            (bits, expected.clone())
        );
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: AVX2 is available, checked just above.
            let avx = unsafe { handed_avx2(&group, wanted, params) };
            assert_eq!(avx, (bits, expected), "round {round}");
        }
        bounded += bits.count_ones();
        refused += (0..len)
            .filter(|&k| one_at_a_time(&group[k], &params[k]).is_none())
            .count();
    }
    // Both sides are exercised.
    assert!(bounded > 30_000 && refused > 30_000, "{bounded} {refused}");
}
