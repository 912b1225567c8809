//! Extreme inputs: sky and empty tiles, VPLs behind the camera, zero flux, the sharpest lobes,
//! extreme δ, no VPLs, a 1x1 image, sizes that are multiples of neither 16 nor K, and invalid
//! inputs (errors, never panics).
use crate::common::*;
use glam::Vec3;
use slc_core::{Camera, CullInput, GBuffer, Interleaving, VplLobe, NO_LIST};
use slc_core::{Culler, Strategy};
use slc_cull::{culler, BoundedCuller, BoundedMemory};

/// A camera 1.5 units above the floor looking at the horizon: the upper half is sky, so
/// whole tiles are empty and others are cut by the horizon.
fn horizon_camera() -> Camera {
    Camera::look_at(
        Vec3::new(0.0, 1.5, 4.0),
        Vec3::new(0.0, 1.5, -10.0),
        Vec3::Y,
        70f32.to_radians(),
    )
    .unwrap()
}

#[test]
fn sky_and_empty_tiles() {
    let mut rng = Rng::new(2);
    let camera = horizon_camera();
    let gbuffer = floor_gbuffer(&camera, 67, 45, &mut rng);
    let sky = gbuffer.samples.iter().filter(|s| s.is_none()).count();
    assert!(sky > 1000 && sky < 67 * 45 - 1000, "{sky} sky pixels");
    let vpls = room_vpls(&mut rng, 200);
    for k in [1, 2, 3] {
        check_all(&input(&gbuffer, &camera, &vpls, 1e-3, k), "horizon");
    }
    // All sky: no lists at all.
    let all_sky = GBuffer {
        samples: vec![None; gbuffer.samples.len()],
        ..gbuffer
    };
    for name in Strategy::on_cpu() {
        let lists = culler(name)
            .cull(&input(&all_sky, &camera, &vpls, 1e-3, 2))
            .unwrap();
        assert!(lists.pixel_list.iter().all(|&l| l == NO_LIST), "{name}");
    }
}

/// A G-buffer whose samples stray up to two pixels outside their own pixel (another
/// renderer's pixel convention, a wide reconstruction filter): tiles grow to contain them.
#[test]
fn samples_outside_their_pixels() {
    let mut rng = Rng::new(8);
    for case in 0..8 {
        let camera = floor_camera(&mut rng);
        let (w, h) = (40 + rng.below(30), 30 + rng.below(20));
        let mut gbuffer = floor_gbuffer(&camera, w, h, &mut rng);
        for (p, s) in gbuffer.samples.iter_mut().enumerate() {
            let (x, y) = (p as u32 % w, p as u32 / w);
            let (u, v) = (rng.range(-2.0, 3.0), rng.range(-2.0, 3.0));
            let dir = camera.ray_direction(x, y, u, v, w, h);
            if let (Some(s), true) = (s.as_mut(), dir.y < 0.0) {
                s.position = camera.position + dir * (-camera.position.y / dir.y);
                s.depth = camera.view_depth(s.position);
            }
        }
        let vpls = room_vpls(&mut rng, 200);
        for k in [1, 2] {
            let label = format!("stray {case}, K {k}");
            let all = check_all(&input(&gbuffer, &camera, &vpls, 1e-1, k), &label);
            println!("{label}: {}", line("ellipsoid", of(&all, "ellipsoid")));
        }
    }
}

#[test]
fn vpls_behind_the_camera_are_never_listed_unless_they_reach() {
    let mut rng = Rng::new(3);
    let camera = horizon_camera();
    let gbuffer = floor_gbuffer(&camera, 40, 30, &mut rng);
    // VPLs 30 units behind the camera, so weak that every bound stays within a unit of
    // them (r <= sqrt(Φ (2/α) / (4π δ ξ)) = 0.025 and r/α <= 0.5 for α >= 0.05, eq. 12).
    let mut vpls = room_vpls(&mut rng, 150);
    for v in &mut vpls {
        v.position = camera.position - 30.0 * camera.forward + rng.unit();
        v.flux = Vec3::splat(1e-6);
        v.xi = 0.5;
        v.brdf.alpha = v.brdf.alpha.max(0.05);
    }
    let far = input(&gbuffer, &camera, &vpls, 1e-2, 1);
    check_all(&far, "far behind");
    for name in Strategy::on_cpu().skip(1) {
        let lists = culler(name).cull(&far).unwrap();
        assert!(
            lists.indices.is_empty(),
            "{name} listed a VPL behind the camera"
        );
    }
    // Strong VPLs just behind the camera do reach the floor in view: listed where they must.
    for v in &mut vpls {
        v.position = camera.position - 0.5 * camera.forward + 0.3 * rng.unit();
        v.flux = Vec3::splat(5.0);
    }
    let all = check_all(&input(&gbuffer, &camera, &vpls, 1e-3, 2), "just behind");
    assert!(of(&all, "none").true_positive_pairs > 1000);
}

#[test]
fn zero_flux_and_unlit_vpls_are_never_listed() {
    let mut rng = Rng::new(4);
    let camera = floor_camera(&mut rng);
    let gbuffer = floor_gbuffer(&camera, 48, 32, &mut rng);
    let mut vpls = room_vpls(&mut rng, 200);
    for (i, v) in vpls.iter_mut().enumerate() {
        if i % 2 == 0 {
            v.flux = Vec3::ZERO;
        } else {
            // Lit from below the surface: the one-sided BRDF reflects nothing.
            v.omega_i = -v.normal;
        }
    }
    let dark = input(&gbuffer, &camera, &vpls, 1e-6, 1);
    check_all(&dark, "dark");
    for name in Strategy::on_cpu().skip(1) {
        let lists = culler(name).cull(&dark).unwrap();
        assert!(lists.indices.is_empty(), "{name} listed a dark VPL");
    }
}

/// The sharpest lobe the project allows (α = 1e-3) with δ at both ends of its range,
/// aimed at the floor in view so the needle-like spheroids cross it.
#[test]
fn sharpest_lobes_and_extreme_delta() {
    let mut rng = Rng::new(5);
    for case in 0..12 {
        let camera = floor_camera(&mut rng);
        let gbuffer = floor_gbuffer(&camera, 64, 48, &mut rng);
        let mut vpls = room_vpls(&mut rng, 200);
        for v in &mut vpls {
            v.lobe = VplLobe::Glossy;
            v.brdf.alpha = 1e-3;
            // Mirror the incoming direction of a point on the floor in view.
            let target = Vec3::new(rng.range(-3.0, 3.0), 0.0, rng.range(-6.0, 3.0));
            let out = (target - v.position).normalize();
            let reflected = 2.0 * out.dot(v.normal) * v.normal - out;
            if reflected.dot(v.normal) > 0.0 {
                v.omega_i = reflected;
            }
        }
        for delta in [1e-6, 1e-1] {
            for k in [1, 3] {
                let label = format!("alpha 1e-3, case {case}, delta {delta}, K {k}");
                let all = check_all(&input(&gbuffer, &camera, &vpls, delta, k), &label);
                if delta == 1e-6 {
                    assert!(of(&all, "none").true_positive_pairs > 0, "{label}");
                }
            }
        }
    }
}

#[test]
fn tiny_and_odd_images_and_no_vpls() {
    let mut rng = Rng::new(6);
    let camera = Camera::look_at(
        Vec3::new(0.0, 2.0, 3.0),
        Vec3::new(0.0, 0.0, -2.0),
        Vec3::Y,
        60f32.to_radians(),
    )
    .unwrap();
    let vpls = room_vpls(&mut rng, 120);
    for (w, h) in [(1, 1), (1, 7), (5, 3), (17, 33), (31, 16), (33, 47)] {
        let gbuffer = floor_gbuffer(&camera, w, h, &mut rng);
        for k in [1, 2, 3, 5, 8] {
            let label = format!("{w}x{h}, K {k}");
            check_all(&input(&gbuffer, &camera, &vpls, 1e-3, k), &label);
            let all = check_all(&input(&gbuffer, &camera, &[], 1e-3, k), &label);
            assert!(all.iter().all(|(_, m)| m.lights_per_pixel_mean == 0.0));
        }
    }
    let empty = GBuffer {
        width: 0,
        height: 0,
        samples: Vec::new(),
    };
    for name in Strategy::on_cpu() {
        let lists = culler(name)
            .cull(&input(&empty, &camera, &vpls, 1e-3, 4))
            .unwrap();
        assert!(lists.pixel_list.is_empty() && lists.is_empty(), "{name}");
    }
}

#[test]
fn invalid_inputs_are_errors_not_panics() {
    let mut rng = Rng::new(7);
    let camera = horizon_camera();
    let gbuffer = floor_gbuffer(&camera, 20, 20, &mut rng);
    let vpls = room_vpls(&mut rng, 50);
    let cull = |input: &CullInput| -> Vec<bool> {
        Strategy::on_cpu()
            .map(|n| culler(n).cull(input).is_err())
            .collect()
    };
    let bounded = |errs: Vec<bool>| errs[1..].iter().all(|&e| e);
    // δ and ξ out of their domains: only the bound-based strategies look at them.
    for delta in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(bounded(cull(&input(&gbuffer, &camera, &vpls, delta, 2))));
    }
    let mut bad_xi = vpls.clone();
    bad_xi[3].xi = 1.0;
    assert!(bounded(cull(&input(&gbuffer, &camera, &bad_xi, 1e-3, 2))));
    let mut nan = vpls.clone();
    nan[7].position = Vec3::NAN;
    assert!(bounded(cull(&input(&gbuffer, &camera, &nan, 1e-3, 2))));
    // Every strategy refuses a G-buffer of the wrong size and K = 0.
    let short = GBuffer {
        samples: gbuffer.samples[1..].to_vec(),
        ..gbuffer.clone()
    };
    assert!(cull(&input(&short, &camera, &vpls, 1e-3, 2))
        .iter()
        .all(|&e| e));
    let no_k = CullInput {
        interleaving: Interleaving { k: 0, seed: 0 },
        ..input(&gbuffer, &camera, &vpls, 1e-3, 2)
    };
    assert!(cull(&no_k).iter().all(|&e| e));
    // A sample behind the camera, or a broken camera.
    let mut behind = gbuffer.clone();
    if let Some(s) = behind.samples.iter_mut().flatten().next() {
        s.position = camera.position - camera.forward;
    }
    assert!(bounded(cull(&input(&behind, &camera, &vpls, 1e-3, 2))));
    let broken = Camera {
        forward: Vec3::ZERO,
        ..camera.clone()
    };
    assert!(bounded(cull(&input(&gbuffer, &broken, &vpls, 1e-3, 2))));
    // The metrics refuse lists that do not fit the input.
    let ok = input(&gbuffer, &camera, &vpls, 1e-3, 2);
    let mut lists = culler(Strategy::Ellipsoid).cull(&ok).unwrap();
    assert!(slc_cull::metrics::measure(&ok, &lists).is_ok());
    lists.pixel_list.pop();
    assert!(slc_cull::metrics::measure(&ok, &lists).is_err());
}

/// Every strategy at the extremes of the roulette (issue 42's conformance range): δ from
/// 1e-9 to 1e3, α from 1e-4 to 1, ξ within 1e-6 of 0 and of 1, so that the random ranges lie
/// far below a pixel (δ 1e3, ξ near 1: the binned strategy places most VPLs on no pixel) and
/// far beyond the frame (δ 1e-9, ξ near 0: every VPL covers every tile), with VPLs in the
/// room, just above the floor and near the camera.
#[test]
fn extremes_of_delta_alpha_xi_and_range() {
    let mut rng = Rng::new(42);
    let camera = horizon_camera();
    let gbuffer = floor_gbuffer(&camera, 72, 40, &mut rng);
    let mut vpls = room_vpls(&mut rng, 160);
    for (i, v) in vpls.iter_mut().enumerate() {
        v.brdf.alpha = [1e-4, 1e-3, 0.02, 0.3, 1.0][i % 5];
        v.xi = match i % 3 {
            0 => 1e-6,
            1 => 1.0 - 1e-6,
            _ => v.xi,
        };
        if i % 7 == 0 {
            v.position = camera.position + 0.2 * rng.unit() - 0.3 * camera.forward;
        }
    }
    let mut contributing = [0; 2];
    for (j, delta) in [1e-9, 1e-3, 1e3].into_iter().enumerate() {
        for k in [1, 3] {
            let label = format!("extremes, delta {delta:e}, K {k}");
            let all = check_all(&input(&gbuffer, &camera, &vpls, delta, k), &label);
            println!("{label}: {}", line("binned", of(&all, "binned")));
            if j != 1 {
                contributing[j / 2] += of(&all, "none").true_positive_pairs;
            }
        }
    }
    // The test has teeth at both ends: pairs contribute at δ 1e-9, some still at δ 1e3.
    assert!(
        contributing[0] > 10_000 && contributing[1] > 0,
        "{contributing:?}"
    );
}

/// Culling in kept memory (`BoundedCuller::cull_in`) gives the lists of fresh memory, whatever
/// frame the memory held before: one `BoundedMemory` through every bound-testing strategy and
/// 60 random frames of 0 to 240 VPLs, 1 to 70 x 1 to 50 pixels and K from 1 to 6 (so it is
/// grown, reused and dropped as more than four times too large).
#[test]
fn kept_memory_gives_the_lists_of_fresh_memory() {
    let mut rng = Rng::new(11);
    let mut memory = BoundedMemory::default();
    let bounded: Vec<BoundedCuller> = Strategy::on_cpu().filter_map(BoundedCuller::new).collect();
    assert!(
        bounded.len() >= 8,
        "{} bound-testing strategies",
        bounded.len()
    );
    for case in 0..60 {
        let camera = floor_camera(&mut rng);
        let (w, h) = (1 + rng.below(70), 1 + rng.below(50));
        let gbuffer = floor_gbuffer(&camera, w, h, &mut rng);
        let count = rng.below(240);
        let vpls = room_vpls(&mut rng, count);
        let (delta, k) = (rng.log(-5.0, -1.0), 1 + rng.below(6));
        let input = input(&gbuffer, &camera, &vpls, delta, k);
        let culler = bounded[case as usize % bounded.len()];
        let fresh = culler.cull(&input).unwrap();
        let kept = culler.cull_in(&input, &mut memory).unwrap();
        assert_eq!(kept, fresh, "case {case}: {culler:?}, {w}x{h}, K {k}");
    }
}
