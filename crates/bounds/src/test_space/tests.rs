//! Tests of the stretched and rotated test space (eq. 16-17) and of the tile test built on it.
use super::*;
use crate::fresnel::Fresnel;
use crate::glossy::GlossyLobe;
use crate::stochastic::StochasticParams;
use crate::test_util::{fibonacci, Rng};
use glam::Quat;

fn random_rotation(rng: &mut Rng) -> Mat3 {
    Mat3::from_quat(Quat::from_axis_angle(
        rng.unit(),
        rng.range(0.0, core::f32::consts::TAU),
    ))
}

/// A view-space ellipsoid in front of a +z camera: rotation, semi-axes, centre. Half are
/// GGX-like spheroids ((1+α²)/(2α) r, r, r), half triaxial.
fn random_ellipsoid(rng: &mut Rng) -> (Mat3, Vec3, Vec3) {
    let r = rng.range(0.1, 2.0);
    let semi = if rng.f32() < 0.5 {
        let a = rng.range(0.05, 1.0);
        Vec3::new((1.0 + a * a) / (2.0 * a) * r, r, r)
    } else {
        Vec3::new(r, rng.range(0.1, 2.0), rng.range(0.1, 2.0))
    };
    let c = Vec3::new(
        rng.range(-3.0, 3.0),
        rng.range(-3.0, 3.0),
        rng.range(2.0, 15.0),
    );
    (random_rotation(rng), semi, c)
}

#[test]
fn stretch_maps_the_ellipsoid_surface_to_the_unit_sphere() {
    let mut rng = Rng::new(51);
    for _ in 0..200 {
        let (rot, semi, c) = random_ellipsoid(&mut rng);
        let space = TestSpace::new(rot, semi, c).unwrap();
        let s = stretch(rot, semi);
        for k in 0..100 {
            let p = c + rot * (semi * fibonacci(k, 100));
            let mapped = (space.map(p) - space.center()).length();
            assert!((mapped - 1.0).abs() < 1e-4, "|BS(p - c)| = {mapped}");
            assert!(
                ((s * (p - c)).length() - 1.0).abs() < 1e-4,
                "eq. (16) alone"
            );
            assert!(space.contains(c + rot * (semi * fibonacci(k, 100) * 0.999)));
            assert!(!space.contains(c + rot * (semi * fibonacci(k, 100) * 1.001)));
        }
    }
}

#[test]
fn world_spheroid_through_a_view_maps_to_the_unit_sphere() {
    let mut rng = Rng::new(52);
    for _ in 0..100 {
        let n = rng.unit();
        let lobe = GlossyLobe::new(
            Vec3::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
            ),
            n,
            rng.above(n),
            rng.range(0.02, 1.0),
            Vec3::splat(rng.range(0.1, 10.0)),
            Fresnel::Dielectric(1.5),
        )
        .unwrap();
        let params = StochasticParams::new(0.1, rng.range(0.1, 0.9)).unwrap();
        let s = Spheroid::new(&lobe, &params).unwrap();
        let rotation = Quat::from_axis_angle(rng.unit(), rng.range(0.0, 6.0));
        let view = Affine3A::from_rotation_translation(rotation, Vec3::new(1.0, -2.0, 3.0));
        let space = TestSpace::from_spheroid(&s, view).unwrap();
        for k in 0..50 {
            let surface = s.center() + s.rotation() * (s.semi_axes() * fibonacci(k, 50));
            let d = (space.map(view.transform_point3(surface)) - space.center()).length();
            assert!((d - 1.0).abs() < 1e-3, "{d}");
            let inner = s.center() + s.rotation() * (s.semi_axes() * fibonacci(k, 50) * 0.99);
            assert!(s.contains(inner) && space.contains(view.transform_point3(inner)));
        }
    }
}

#[test]
fn b_is_a_rotation_that_keeps_depth_planes_flat() {
    let mut rng = Rng::new(53);
    let mut branches = [0; 2];
    for _ in 0..500 {
        let (rot, semi, c) = random_ellipsoid(&mut rng);
        let s = stretch(rot, semi);
        let b = test_rotation(s);
        let err = b.transpose() * b - Mat3::IDENTITY;
        assert!(
            err.x_axis
                .abs()
                .max(err.y_axis.abs())
                .max(err.z_axis.abs())
                .max_element()
                < 1e-5
        );
        assert!((b.determinant() - 1.0).abs() < 1e-5);
        branches[usize::from(s.x_axis.length() > s.y_axis.length())] += 1;
        let bs = TestSpace::new(rot, semi, c).unwrap().matrix();
        assert_eq!(bs, b * s);
        // Row 3 of BS is (0, 0, BS₃₃) with BS₃₃ > 0: z = k maps to z' = BS₃₃ k.
        let scale = bs
            .x_axis
            .abs()
            .max(bs.y_axis.abs())
            .max(bs.z_axis.abs())
            .max_element();
        assert!(bs.x_axis.z.abs() < 1e-6 * scale && bs.y_axis.z.abs() < 1e-6 * scale);
        assert!(bs.z_axis.z > 0.0);
        let z = rng.range(0.1, 20.0);
        for _ in 0..10 {
            let p = Vec3::new(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0), z);
            assert!((bs * p).z - bs.z_axis.z * z <= 1e-5 * scale * 9.0);
        }
    }
    assert!(
        branches[0] > 50 && branches[1] > 50,
        "both cases of eq. (17): {branches:?}"
    );
}

/// A uniform point of the unit ball.
fn in_ball(rng: &mut Rng) -> Vec3 {
    rng.unit() * rng.f32().cbrt()
}

#[test]
fn tile_test_agrees_with_brute_force() {
    let mut rng = Rng::new(54);
    let (mut hits, mut misses) = (0, 0);
    let ball: Vec<Vec3> = [0.0f32, 0.25, 0.5, 0.75, 1.0]
        .iter()
        .flat_map(|&radius| (0..600).map(move |k| fibonacci(k, 600) * radius))
        .collect();
    for _ in 0..150 {
        let (rot, semi, c) = random_ellipsoid(&mut rng);
        let space = TestSpace::new(rot, semi, c).unwrap();
        let samples: Vec<Vec3> = (0..400)
            .map(|_| c + rot * (semi * in_ball(&mut rng)))
            .collect();
        for _ in 0..20 {
            let mid = Vec2::new(c.x / c.z, c.y / c.z)
                + Vec2::new(rng.range(-0.4, 0.4), rng.range(-0.4, 0.4));
            let half = Vec2::new(rng.range(0.01, 0.15), rng.range(0.01, 0.15));
            let z_min = rng.range(0.5, 16.0);
            let tile = TileFrustum::new(mid - half, mid + half, z_min, z_min + rng.range(0.1, 6.0))
                .unwrap();
            let hit = space.intersects(&tile);
            let bx = space.frustum_aabb(&tile);
            for &p in &samples {
                assert!(space.contains(p));
                // A point of the ellipsoid in the frustum: its image is in the box, and the
                // test must report the overlap.
                if tile.contains(p) {
                    assert!(bx.distance_sq(space.map(p)) < 1e-8 && hit, "missed overlap");
                }
            }
            // A reported overlap means the unit ball around BS·c reaches the box.
            let near = ball
                .iter()
                .any(|&b| bx.distance_sq(space.center() + b) <= 0.04);
            assert!(
                !hit || near,
                "hit, but no point of the unit ball is near the box"
            );
            if hit {
                hits += 1;
            } else {
                misses += 1;
            }
        }
    }
    assert!(hits > 300 && misses > 300, "{hits} hits, {misses} misses");
}

#[test]
fn empty_space_never_intersects() {
    let space = TestSpace::new(Mat3::IDENTITY, Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0)).unwrap();
    assert!(space.is_empty());
    assert!(space.matrix().is_finite() && space.center().is_finite());
    assert!(!space.contains(Vec3::new(1.0, 2.0, 3.0)) && !space.contains(Vec3::ZERO));
    let huge = TileFrustum::new(Vec2::splat(-1e3), Vec2::splat(1e3), -1e6, 1e6).unwrap();
    assert!(!space.intersects(&huge));
    let bx = space.frustum_aabb(&huge);
    assert!(bx.min.is_finite() && bx.max.is_finite());
}

#[test]
fn invalid_inputs_are_errors() {
    let (r, a, c) = (Mat3::IDENTITY, Vec3::ONE, Vec3::Z);
    assert_eq!(TestSpace::new(r * 2.0, a, c), Err(BoundsError::NotRotation));
    let mirror = Mat3::from_diagonal(Vec3::new(1.0, 1.0, -1.0));
    assert_eq!(TestSpace::new(mirror, a, c), Err(BoundsError::NotRotation));
    assert_eq!(
        TestSpace::new(r, a, Vec3::NAN),
        Err(BoundsError::NotFinite("ellipsoid centre"))
    );
    assert_eq!(
        TestSpace::new(r * f32::NAN, a, c),
        Err(BoundsError::NotFinite("rotation"))
    );
    for semi in [
        Vec3::new(0.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
        Vec3::splat(f32::INFINITY),
    ] {
        assert!(matches!(
            TestSpace::new(r, semi, c),
            Err(BoundsError::InvalidSemiAxes(_))
        ));
    }
    assert!(matches!(
        TestSpace::new(r, Vec3::splat(1e-30), Vec3::splat(1e10)),
        Err(BoundsError::Overflow(_))
    ));
    let scaled_view = Affine3A::from_scale(Vec3::splat(2.0));
    let lobe = GlossyLobe::new(
        Vec3::ZERO,
        Vec3::Z,
        Vec3::Z,
        0.5,
        Vec3::ONE,
        Fresnel::Dielectric(1.5),
    )
    .unwrap();
    let s = Spheroid::new(&lobe, &StochasticParams::new(1e-3, 0.5).unwrap()).unwrap();
    assert_eq!(
        TestSpace::from_spheroid(&s, scaled_view),
        Err(BoundsError::NotRotation)
    );
}
