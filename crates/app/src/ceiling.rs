//! The ceiling `slc bench` measures the CPU shading against (docs/cpu-ceiling.md): listed
//! pixel-VPL pairs per second when every pair costs only the eight-lane bound-and-sign test
//! of `slc_cull::ReachChunks` — the cheapest per-pair decision slc has, a yardstick rather
//! than a proven bound — on VPLs that stay in L1, with every rayon thread busy. The shading's own
//! pairs per second over this figure is its share of the ceiling; the gap is the roulette,
//! the contributions, the G-buffer reads and the bookkeeping per pixel.
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::{Brdf, Fresnel, StochasticParams};
use slc_core::{Vpl, VplLobe};
use slc_cull::{ReachChunks, VplReach};
use std::hint::black_box;
use std::time::Instant;

/// VPLs per test (eight chunks of eight) and receivers per thread and round.
const VPLS: u32 = 64;
const RECEIVERS: u32 = 100_000;

/// The measured ceiling, in millions of listed pairs per second over all threads: the best
/// of three rounds after a warm-up.
pub fn exit_test_mpairs_per_s() -> f64 {
    let chunks = vpls_in_l1();
    let threads = rayon::current_num_threads();
    let round = || {
        let start = Instant::now();
        let passed: u64 = (0..threads)
            .into_par_iter()
            .map(|t| test_receivers(&chunks, t as f32, RECEIVERS))
            .sum();
        black_box(passed);
        let pairs = threads as u64 * u64::from(RECEIVERS) * u64::from(VPLS);
        pairs as f64 / start.elapsed().as_secs_f64() / 1e6
    };
    round();
    (0..3).map(|_| round()).fold(0.0, f64::max)
}

/// 64 glossy VPLs a centimetre apart, packed as one group of eight chunks.
fn vpls_in_l1() -> ReachChunks {
    let vpls: Vec<Vpl> = (0..VPLS)
        .map(|i| Vpl {
            position: Vec3::new(i as f32 * 1e-2, 0.0, 0.0),
            normal: Vec3::Y,
            geometric_normal: Vec3::Y,
            omega_i: Vec3::new(0.6, 0.8, 0.0),
            flux: Vec3::splat(1e-3),
            brdf: Brdf {
                kd: Vec3::splat(0.5),
                fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
                alpha: 0.1,
                anisotropy: None,
            },
            lobe: VplLobe::Glossy,
            id: i,
            xi: 0.5,
        })
        .collect();
    let reach: Vec<VplReach> = vpls
        .iter()
        .map(|v| {
            let params = StochasticParams::new(1e-3, v.xi).expect("valid roulette");
            VplReach::new(v, &params).expect("valid VPL")
        })
        .collect();
    let all: Vec<u32> = (0..VPLS).collect();
    ReachChunks::new(&vpls, &reach, [all.as_slice()])
}

/// Tests `receivers` receivers far outside every bound (facing the VPLs, so the sign test at
/// the receiver passes and the bound test decides) against every VPL; returns how many pairs
/// passed.
fn test_receivers(chunks: &ReachChunks, z: f32, receivers: u32) -> u64 {
    let mut passed = 0u64;
    for r in 0..receivers {
        let x = black_box(Vec3::new(1e4 + r as f32 * 1e-2, 1e3, z));
        chunks.for_each_passing(0, x, Some(Vec3::NEG_X), |_| passed += 1);
    }
    passed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_receivers_fail_every_bound_and_pass_the_signs() {
        let chunks = vpls_in_l1();
        assert_eq!(test_receivers(&chunks, 0.0, 1000), 0);
        // The same VPLs pass at a receiver inside their bounds: the test is not vacuous.
        let mut near = 0;
        chunks.for_each_passing(0, Vec3::new(0.3, 0.4, 0.0), Some(Vec3::NEG_Y), |_| {
            near += 1
        });
        assert!(near > 0);
    }
}
