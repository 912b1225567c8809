//! Conservativeness of the spheroid and the baseline spheres against the true BRDF (eq. 4-6)
//! over dense grids, random lobes and extreme inputs.
use super::probe::{assert_conservative, directions, random_lobe, random_params};
use super::*;
use crate::fresnel::Fresnel;
use crate::frustum::TileFrustum;
use crate::test_space::TestSpace;
use crate::test_util::Rng;
use glam::{Affine3A, Quat, Vec2};
use proptest::prelude::*;

#[test]
fn dense_grid_is_conservative_and_tight_at_the_peak() {
    let mut rng = Rng::new(41);
    let fresnels = [
        Fresnel::Schlick(Vec3::ONE),
        Fresnel::Schlick(Vec3::new(0.04, 0.5, 0.9)),
        Fresnel::Dielectric(1.5),
        Fresnel::Dielectric(0.3),
        Fresnel::Dielectric(4.5),
    ];
    for alpha in [1e-3, 0.01, 0.1, 0.3, 0.7, 1.0] {
        for deg in [0.0f32, 20.0, 45.0, 70.0, 85.0, 89.9] {
            for fresnel in fresnels {
                let lobe = random_lobe(&mut rng, alpha, deg.to_radians(), fresnel);
                let params = random_params(&mut rng);
                let dirs = directions(&lobe, &mut rng, 600);
                let w = assert_conservative(&lobe, &params, &dirs);
                if deg == 0.0 && fresnel == Fresnel::Schlick(Vec3::ONE) {
                    assert!(
                        w.spheroid >= 1.0 - 1e-3,
                        "loose: {} at α {alpha}",
                        w.spheroid
                    );
                }
            }
        }
    }
}

/// Identity-oriented view that puts `target` on the +z axis at depth `depth`.
fn view_looking_at(target: Vec3, depth: f32, rotation: Quat) -> Affine3A {
    let eye = target - depth * (rotation.inverse() * Vec3::Z);
    Affine3A::from_rotation_translation(rotation, -(rotation * eye))
}

#[test]
fn extremes_stay_finite_and_conservative() {
    let mut rng = Rng::new(45);
    let n = Vec3::Z;
    let incidences = [n, Vec3::new(1.0, 0.0, 1e-6), Vec3::new(0.6, 0.0, 0.8)];
    let fluxes = [Vec3::ZERO, Vec3::ONE, Vec3::new(3.0, 0.5, 0.0)];
    let mut checked = 0;
    for alpha in [1e-4f32, 1e-3, 1.0] {
        for (i, omega_i) in incidences.into_iter().enumerate() {
            for flux in fluxes {
                for xi in [3e-8f32, 0.5, 1.0 - 6e-8] {
                    for delta in [1e-9f32, 1e-3, 1e3] {
                        let fresnel = if i % 2 == 0 {
                            Fresnel::Schlick(Vec3::new(0.04, 0.9, 1.0))
                        } else {
                            Fresnel::Dielectric(0.25)
                        };
                        let q = Vec3::new(0.5, -2.0, 1.0);
                        let lobe = GlossyLobe::new(q, n, omega_i, alpha, flux, fresnel).unwrap();
                        let params = StochasticParams::new(delta, xi).unwrap();
                        let s = Spheroid::new(&lobe, &params).unwrap();
                        let finite = s.center().is_finite()
                            && s.rotation().is_finite()
                            && s.semi_axes().is_finite();
                        assert!(finite, "{s:?}");
                        let rotation = Quat::from_axis_angle(rng.unit(), rng.range(0.0, 6.0));
                        let depth = 2.0 * s.semi_axes().x.max(1.0);
                        let view = view_looking_at(s.center(), depth, rotation);
                        let space = TestSpace::from_spheroid(&s, view).unwrap();
                        assert!(space.matrix().is_finite() && space.center().is_finite());
                        let tile = TileFrustum::new(
                            Vec2::splat(-0.01),
                            Vec2::splat(0.01),
                            0.5 * depth,
                            1.5 * depth,
                        )
                        .unwrap();
                        assert_eq!(space.intersects(&tile), !s.is_empty(), "{s:?}");
                        if flux == Vec3::ZERO {
                            assert!(s.is_empty() && !s.contains(q));
                            continue;
                        }
                        let dirs = directions(&lobe, &mut rng, 150);
                        assert_conservative(&lobe, &params, &dirs);
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * 3 * 2 * 3 * 3);
}

fn lobe_and_params() -> impl Strategy<Value = (GlossyLobe, StochasticParams)> {
    (
        (
            -3.0f32..=0.0,
            -1.0f32..=1.0,
            0.0f32..1.0,
            1e-4f32..=1.0,
            0.0f32..1.0,
        ),
        (
            prop::array::uniform3(1e-2f32..100.0),
            prop::array::uniform3(-1.0f32..1.0),
        ),
        (
            any::<bool>(),
            prop::array::uniform3(0.0f32..=1.0),
            0.2f32..5.0,
        ),
        (1e-7f32..0.9999999, -5.0f32..0.0),
    )
        .prop_map(
            |((log_a, nz, nphi, cos_i, iphi), (flux, q), (schlick, f0, eta), (xi, log_d))| {
                let (ns, np) = (
                    (1.0 - nz * nz).max(0.0).sqrt(),
                    nphi * core::f32::consts::TAU,
                );
                let n = Vec3::new(ns * np.cos(), ns * np.sin(), nz).normalize();
                let (s, p) = ((1.0 - cos_i * cos_i).sqrt(), iphi * core::f32::consts::TAU);
                let omega_i =
                    Basis::from_unit(n).to_world(Vec3::new(s * p.cos(), s * p.sin(), cos_i));
                let fresnel = if schlick {
                    Fresnel::Schlick(Vec3::from_array(f0))
                } else {
                    Fresnel::Dielectric(eta)
                };
                let lobe = GlossyLobe::new(
                    Vec3::from_array(q),
                    n,
                    omega_i,
                    10f32.powf(log_a),
                    Vec3::from_array(flux),
                    fresnel,
                )
                .unwrap();
                (lobe, StochasticParams::new(10f32.powf(log_d), xi).unwrap())
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]
    #[test]
    fn random_lobes_are_bounded((lobe, params) in lobe_and_params(), seed in any::<u64>()) {
        let dirs = directions(&lobe, &mut Rng::new(seed), 1000);
        assert_conservative(&lobe, &params, &dirs);
    }

    /// The same lobes on a tilted shading normal (`crate::shading_normal`): the geometric
    /// normal up to 0.8 rad from n, ωi above it.
    #[test]
    fn random_tilted_lobes_are_bounded(
        (lobe, params) in lobe_and_params(),
        tilt in 1e-6f32..0.8,
        axis in prop::array::uniform3(-1.0f32..1.0),
        seed in any::<u64>(),
    ) {
        let n = lobe.normal();
        let axis = n.cross(Vec3::from_array(axis)).normalize_or_zero();
        prop_assume!(axis != Vec3::ZERO);
        let n_g = (glam::Quat::from_axis_angle(axis, tilt) * n).normalize();
        prop_assume!(n_g.dot(lobe.omega_i()) > 1e-3);
        let lobe = lobe.with_geometric_normal(n_g).unwrap();
        let dirs = directions(&lobe, &mut Rng::new(seed), 1000);
        assert_conservative(&lobe, &params, &dirs);
    }

    /// The same lobes made anisotropic (`crate::anisotropy`): α_t from 1e-4 to 1 along a
    /// random tangent, α along the bitangent; the spheroid of the larger α with the flux
    /// times the bound factor. Probed also along the tangent and the bitangent planes.
    #[test]
    fn random_anisotropic_lobes_are_bounded(
        (lobe, params) in lobe_and_params(),
        log_alpha_t in -4.0f32..=0.0,
        seed in any::<u64>(),
    ) {
        let mut rng = Rng::new(seed);
        let mut a = crate::test_util::random_anisotropy(&mut rng, lobe.normal());
        a.alpha_t = 10f32.powf(log_alpha_t);
        let lobe = lobe.with_anisotropy(Some(a)).unwrap();
        let mut dirs = directions(&lobe, &mut rng, 1000);
        let u = lobe.reflection();
        let angles = crate::test_util::log_angles(1e-3 * f64::from(lobe.alpha_min()), 3.0, 60);
        for axis in [a.tangent, lobe.normal().cross(a.tangent)] {
            let side = (axis - u * u.dot(axis)).normalize_or_zero();
            for &t in &angles {
                for sign in [-1.0, 1.0] {
                    let (c, s) = (t.cos() as f32, (sign * t.sin()) as f32);
                    dirs.push((u * c + side * s).normalize());
                }
            }
        }
        assert_conservative(&lobe, &params, &dirs);
    }
}
