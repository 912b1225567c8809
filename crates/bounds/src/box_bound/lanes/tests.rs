//! The f32 box bound against the shader's own roulette (every box of f32 receivers holding an
//! accepted one passes, at the extremes of `super::super::tests::random_lobe`), against the
//! f64 bound it rounds (it rejects nearly all the boxes that one does), and in eight lanes
//! against one lane at a time, bit for bit.
use super::super::tests::{
    accepted, box_around, direction, lobe_name, near_the_range, random_lobe, random_params,
    TestLobe,
};
use super::super::ReceiverBox;
use super::*;
use crate::test_util::Rng;
use crate::{DiffuseLobe, Fresnel, GlossyLobe, StochasticParams};

/// A box of f32 receivers around the receiver `x` seen from the VPL at `q`: cubes and slabs
/// 1e-7 to 10 times |x − q| wide with x anywhere in them (`box_around`), in the shader's
/// coordinates.
fn receivers_around(rng: &mut Rng, q: Vec3, x: Vec3) -> (Vec3, Vec3) {
    let (lo, hi) = box_around(rng, (x - q).as_dvec3());
    let q = q.as_dvec3();
    ((lo + q).as_vec3().min(x), (hi + q).as_vec3().max(x))
}

/// The f32 test of `bound` against the box `[lo, hi]`.
fn passes(bound: &BoxBoundLanes<f32>, lo: Vec3, hi: Vec3) -> bool {
    bound.may_exceed_xi(lo.to_array(), hi.to_array())
}

/// Receivers with p > ξ as the shader decides it (its f32 offset from q, mostly at the edge of
/// the random range), each in random boxes: every box passes the f32 bound, while the bound of
/// a δ 1% larger misses some of them (the test sees the edge).
#[test]
fn every_f32_box_with_an_accepted_receiver_passes() {
    let mut rng = Rng::new(17);
    let (mut found, mut missed_when_shrunk) = (0, 0);
    for _ in 0..20_000 {
        let lobe = random_lobe(&mut rng);
        let params = random_params(&mut rng);
        // The VPL anywhere in a scene of size 100.
        let q = rng.unit() * rng.range(0.0, 100.0);
        let bound = lobe.bound(&params).to_f32(q);
        let shrunk = StochasticParams::new(params.delta() * 1.01, params.xi()).unwrap();
        let shrunk = lobe.bound(&shrunk).to_f32(q);
        for _ in 0..20 {
            let Some(offset) = near_the_range(&mut rng, &lobe, &params) else {
                continue;
            };
            let x = q + offset;
            // The offset as the shader forms it.
            if !accepted(&lobe, &params, x - q) {
                continue;
            }
            found += 1;
            for _ in 0..4 {
                let (lo, hi) = receivers_around(&mut rng, q, x);
                assert!(
                    passes(&bound, lo, hi),
                    "rejected a box with an accepted receiver: {} {params:?} q {q} x {x} box {lo} {hi}",
                    lobe_name(&lobe)
                );
                missed_when_shrunk += usize::from(!passes(&shrunk, lo, hi));
            }
        }
    }
    assert!(found > 100_000, "{found}");
    assert!(missed_when_shrunk > 100, "{missed_when_shrunk}");
}

/// Wide boxes (the ball around them seen under a half-angle β with sin β from 0.9 to 0.999)
/// whose centre lies within 1e-3 rad of ±n, ±ω_u or ±ω_i from the VPL, where the cone's
/// cosines are formed near ±1: every one holding a receiver the shader accepts passes.
#[test]
fn wide_boxes_centred_near_the_lobe_axes_pass_when_they_hold_an_accepted_receiver() {
    let mut rng = Rng::new(20);
    let mut found = 0;
    for _ in 0..100_000 {
        let lobe = random_lobe(&mut rng);
        let params = random_params(&mut rng);
        let q = rng.unit() * rng.range(0.0, 100.0);
        let bound = lobe.bound(&params).to_f32(q);
        let axis = match (&lobe, rng.u64() % 3) {
            (TestLobe::Glossy(l), 0) => l.reflection(),
            (TestLobe::Glossy(l), 1) => l.omega_i(),
            _ => lobe.normal(),
        };
        let sign = if rng.u64().is_multiple_of(2) {
            1.0
        } else {
            -1.0
        };
        let center_dir = (axis * sign + rng.unit() * rng.range(0.0, 1e-3)).normalize();
        // The box as large as the lobe's reach towards the receiver sampled below.
        let dir = direction(&mut rng, &lobe);
        let l_max = params.range(lobe.intensity(dir));
        if !(l_max > 1e-3 && l_max < 1e6) {
            continue;
        }
        let distance = l_max * rng.range(0.2, 2.0);
        let sin_beta = rng.range(0.9, 0.999);
        let half = distance * sin_beta / 3f32.sqrt();
        let center = q + center_dir * distance;
        let (lo, hi) = (center - half, center + half);
        for _ in 0..8 {
            let x = lo + (hi - lo) * Vec3::new(rng.f32(), rng.f32(), rng.f32());
            if accepted(&lobe, &params, x - q) {
                found += 1;
                assert!(
                    passes(&bound, lo, hi),
                    "rejected a wide box with an accepted receiver: {} {params:?} q {q} x {x}",
                    lobe_name(&lobe)
                );
            }
        }
    }
    assert!(found > 1000, "{found}");
}

/// Over boxes near and beyond the random range, the f32 test rejects nearly every box the
/// f64 bound rejects: all but 0.5% for α >= 1e-3, all but 15% below, where the f32 cosine of
/// the mirror direction (and its slack of 1e-6) no longer resolves 1 − cos θ of order α².
#[test]
fn rejects_nearly_every_box_the_f64_bound_rejects() {
    let mut rng = Rng::new(18);
    // Per class (α >= 1e-3 or diffuse, α < 1e-3): rejected by f64, by both, by f32 only.
    let mut counts = [[0u32; 3]; 2];
    for _ in 0..20_000 {
        let lobe = random_lobe(&mut rng);
        let params = random_params(&mut rng);
        let q = rng.unit() * rng.range(0.0, 100.0);
        let bound = lobe.bound(&params);
        let fast = bound.to_f32(q);
        let class = usize::from(matches!(lobe, TestLobe::Glossy(l) if l.alpha() < 1e-3));
        for _ in 0..10 {
            let dir = direction(&mut rng, &lobe);
            let l_max = params.range(lobe.intensity(dir));
            if !(l_max > 1e-3 && l_max < 1e6) {
                continue;
            }
            let x = q + dir * l_max * rng.range(0.3, 3.0);
            let (lo, hi) = receivers_around(&mut rng, q, x);
            let exact = bound.may_exceed_xi(
                &ReceiverBox::new(lo.as_dvec3(), hi.as_dvec3()),
                q.as_dvec3(),
            );
            let f32_rejects = !passes(&fast, lo, hi);
            let c = &mut counts[class];
            c[0] += u32::from(!exact);
            c[1] += u32::from(!exact && f32_rejects);
            c[2] += u32::from(exact && f32_rejects);
        }
    }
    for ([by_f64, by_both, by_f32_only], share) in counts.into_iter().zip([0.995, 0.85]) {
        assert!(by_f64 > 5_000, "{counts:?}");
        assert!(
            f64::from(by_both) >= share * f64::from(by_f64),
            "{counts:?}"
        );
        // The f32 test never rejects a box the f64 bound keeps.
        assert_eq!(by_f32_only, 0, "{counts:?}");
    }
}

/// Eight bounds at once (glossy, diffuse and bound-less ones mixed) decide each lane exactly
/// as the one-lane test does, in array lanes and in AVX registers.
#[test]
fn eight_lanes_decide_as_one() {
    let mut rng = Rng::new(19);
    let mut kept = [0u32; 2];
    for _ in 0..20_000 {
        let params = random_params(&mut rng);
        let q = rng.unit() * rng.range(0.0, 100.0);
        let bounds: [BoxBoundLanes<f32>; 8] = core::array::from_fn(|_| {
            if rng.u64().is_multiple_of(8) {
                BoxBoundLanes::ALWAYS
            } else {
                let at = q + rng.unit() * rng.range(0.0, 1.0);
                random_lobe(&mut rng).bound(&params).to_f32(at)
            }
        });
        let x = q + rng.unit() * 10f32.powf(rng.range(-3.0, 2.0));
        let (lo, hi) = receivers_around(&mut rng, q, x);
        let one: u8 = (0..8).fold(0, |bits, k| {
            bits | u8::from(passes(&bounds[k], lo, hi)) << k
        });
        let lanes = BoxBoundLanes::gather(bounds.each_ref());
        let splat = |v: Vec3| v.to_array().map(F8::splat);
        assert_eq!(lanes.may_exceed_xi(splat(lo), splat(hi)).bits(), one);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: AVX2 is available, checked just above.
            assert_eq!(unsafe { avx(&lanes, lo, hi) }, one);
        }
        kept[0] += 8 - one.count_ones();
        kept[1] += one.count_ones();
    }
    // Lanes are both rejected and kept.
    assert!(kept[0] > 10_000 && kept[1] > 10_000, "{kept:?}");
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn avx(lanes: &BoxBoundLanes<F8>, lo: Vec3, hi: Vec3) -> u8 {
    use crate::lanes_avx::A8;
    let splat = |v: Vec3| v.to_array().map(A8::splat);
    A8::bits(lanes.load::<A8>().may_exceed_xi(splat(lo), splat(hi)))
}

/// Boxes around the VPL always pass; boxes behind it or far away, and every box of a VPL
/// without flux or of a diffuse one that reflects nothing, never do.
#[test]
fn degenerate_boxes_and_dark_vpls() {
    let glossy = |flux| {
        let lobe = GlossyLobe::new(
            Vec3::ZERO,
            Vec3::Z,
            Vec3::Z,
            0.3,
            flux,
            Fresnel::Schlick(Vec3::splat(0.5)),
        )
        .unwrap();
        let params = StochasticParams::new(1e-3, 0.5).unwrap();
        TestLobe::Glossy(lobe).bound(&params)
    };
    let q = Vec3::new(3.0, -2.0, 1.0);
    let b = glossy(Vec3::ONE).to_f32(q);
    assert!(passes(&b, q - 1.0, q + 1.0));
    assert!(passes(&b, q, q + 1e-9));
    assert!(!passes(
        &b,
        q + Vec3::new(-1.0, -1.0, -2.0),
        q + Vec3::new(1.0, 1.0, -1.0)
    ));
    assert!(!passes(&b, q + 1e6, q + (1e6 + 1.0)));
    assert!(!passes(&glossy(Vec3::ZERO).to_f32(q), q + 0.1, q + 0.2));
    let diffuse = DiffuseLobe::new(Vec3::ZERO, Vec3::Z, Vec3::ONE, Vec3::ZERO).unwrap();
    let params = StochasticParams::new(1e-3, 0.5).unwrap();
    let dark = TestLobe::Diffuse(diffuse).bound(&params).to_f32(q);
    assert!(!passes(&dark, q + 0.1, q + 0.2));
    assert!(passes(&BoxBoundLanes::ALWAYS, q + 1e6, q + (1e6 + 1.0)));
}
