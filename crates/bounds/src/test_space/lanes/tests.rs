//! The lanes against `TestSpace::new` one spheroid at a time, bit for bit, over rotations and
//! semi-axes at the extremes and outside the domain.
use super::*;
use crate::lanes::{Lanes8, F8};
use crate::test_space::TestSpace;
use crate::test_util::Rng;
use glam::{Mat3, Quat, Vec3};

/// A rotation (of a random unit quaternion, a few in f64 then rounded like the culler's), or
/// one spoilt: a reflection, a scaled or skewed matrix, NaN, infinite or huge entries.
fn rotation(rng: &mut Rng) -> Mat3 {
    let q = Quat::from_xyzw(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    )
    .normalize();
    let m = Mat3::from_quat(q);
    match rng.u64() % 16 {
        0 => -m,
        1 => m * 1.0002,
        2 => Mat3::from_cols(m.x_axis + m.y_axis * 3e-5, m.y_axis, m.z_axis),
        3 => Mat3::from_cols(Vec3::new(f32::NAN, 0.0, 0.0), m.y_axis, m.z_axis),
        4 => Mat3::from_cols(m.x_axis, Vec3::splat(f32::INFINITY), m.z_axis),
        5 => m * 1e30,
        _ => m,
    }
}

/// Semi-axes from 1e-12 to 1e9 with elongations up to 1e4 (a spheroid's two equal ones, or
/// three different), or spoilt: zero, negative, NaN, infinite, tiny enough to overflow 1/r.
fn semi_axes(rng: &mut Rng) -> Vec3 {
    let r = 10f32.powf(rng.range(-12.0, 9.0));
    let along = r * 10f32.powf(rng.range(0.0, 4.0));
    match rng.u64() % 16 {
        0 => Vec3::ZERO,
        1 => Vec3::new(along, -r, r),
        2 => Vec3::new(f32::NAN, r, r),
        3 => Vec3::new(f32::INFINITY, r, r),
        4 => Vec3::new(along, 1e-40, r),
        5 => Vec3::new(r * rng.range(0.5, 2.0), r, along),
        _ => Vec3::new(along, r, r),
    }
}

fn lanes<L: Lanes8>(rotations: &[Mat3; 8], semi: &[Vec3; 8]) -> (u8, [String; 8]) {
    let at = |f: &dyn Fn(usize) -> f32| L::load(&F8(core::array::from_fn(f)));
    let column = |j: usize| [0, 1, 2].map(|i| at(&|k| rotations[k].col(j)[i]));
    let rotation = [column(0), column(1), column(2)];
    let semi_axes = [0, 1, 2].map(|i| at(&|k| semi[k][i]));
    let (matrix, ok) = test_matrices(rotation, semi_axes);
    let stored = matrix.map(|c| c.map(|v| v.store()));
    let lane = |k: usize| {
        let m = Mat3::from_cols_array_2d(&stored.map(|c| c.map(|v| v.0[k])));
        format!("{m:?}")
    };
    (L::bits(ok), core::array::from_fn(lane))
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn lanes_avx2(rotations: &[Mat3; 8], semi: &[Vec3; 8]) -> (u8, [String; 8]) {
    lanes::<crate::lanes_avx::A8>(rotations, semi)
}

#[test]
fn eight_at_a_time_equal_test_space_new_bit_for_bit() {
    let mut rng = Rng::new(0x7E57_5ACE);
    let (mut taken, mut valid) = (0, 0);
    for round in 0..20_000 {
        let rotations: [Mat3; 8] = core::array::from_fn(|_| rotation(&mut rng));
        let semi: [Vec3; 8] = core::array::from_fn(|_| semi_axes(&mut rng));
        let mut results = vec![lanes::<F8>(&rotations, &semi)];
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: AVX2 is available, checked just above.
            results.push(unsafe { lanes_avx2(&rotations, &semi) });
        }
        for (bits, matrices) in results {
            for k in 0..8 {
                let one = TestSpace::new(rotations[k], semi[k], Vec3::ZERO)
                    .ok()
                    .filter(|s| !s.is_empty());
                if bits >> k & 1 == 1 {
                    let one = one.unwrap_or_else(|| panic!("round {round}, lane {k}: refused"));
                    assert_eq!(matrices[k], format!("{:?}", one.matrix()), "round {round}");
                }
            }
        }
        for k in 0..8 {
            let one = TestSpace::new(rotations[k], semi[k], Vec3::ZERO);
            valid += usize::from(one.is_ok_and(|s| !s.is_empty()));
        }
        taken += lanes::<F8>(&rotations, &semi).0.count_ones() as usize;
    }
    // The lanes take all but a few of the spheroids TestSpace::new accepts.
    assert!(
        taken > 60_000 && taken * 1000 >= valid * 999,
        "{taken} of {valid}"
    );
}
