//! Light transport checks that would catch a wrong flux, solid angle, falloff or estimator.
use glam::Vec3;
use slc_bounds::BoundsError;
use slc_core::frame::{LobeSelection, Method, RenderError, RenderSettings, Stochastic};
use slc_core::shapes::{cuboid, quad};
use slc_core::Strategy;
use slc_core::{builtin, GBuffer, Image, Light, Material, Scene, Vpl};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::rsm::{trace_rsm, Rsm, TexelSample};
use slc_cpu_ref::vpl_shading::shade_vpls;
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::{render, Tracer, VplEstimator};

/// The stochastic estimate without culling, interleaving or denoising.
fn unculled(delta: f32) -> Stochastic {
    Stochastic {
        delta,
        strategy: Strategy::None,
        interleave: 1,
        denoise: false,
        metrics: false,
    }
}
use std::f32::consts::PI;

fn scene(meshes: Vec<slc_core::Mesh>, double_sided: bool, light: Light) -> Scene {
    let mut m = Material::direct("grey", Vec3::splat(0.5), Vec3::splat(0.04), 0.3);
    m.double_sided = double_sided;
    Scene {
        name: "test".into(),
        meshes,
        materials: vec![m],
        lights: vec![light],
        ..Scene::default()
    }
}

fn total_flux(rsm: &Rsm) -> Vec3 {
    rsm.texels.iter().flatten().map(|t| t.flux).sum()
}

/// A closed box around a point light receives all of its power, 4π I.
#[test]
fn point_light_power_is_conserved_in_a_closed_box() {
    let box_mesh = cuboid(
        "room",
        Vec3::new(0.1, 0.2, -0.3),
        [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.5, 0.0),
            Vec3::new(0.0, 0.0, 0.7),
        ],
        0,
    );
    let intensity = Vec3::new(2.0, 1.0, 0.5);
    let s = scene(
        vec![box_mesh],
        true,
        Light::Point {
            position: Vec3::new(0.3, 0.4, -0.1),
            intensity,
        },
    );
    let tracer = Tracer::new(&s);
    let power = 4.0 * PI * intensity;
    let centre = trace_rsm(&s, &tracer, &s.lights[0], 32, TexelSample::Centre);
    assert_eq!(
        centre.texels.iter().flatten().count(),
        6 * 32 * 32,
        "every texel hits the room"
    );
    assert!((total_flux(&centre) - power).abs().max_element() < 1e-4 * power.max_element());
    // Jittered texels estimate the same power without bias: the mean over passes converges.
    let passes = 16;
    let mean: Vec3 = (0..passes)
        .map(|p| {
            total_flux(&trace_rsm(
                &s,
                &tracer,
                &s.lights[0],
                16,
                TexelSample::Jittered { seed: 3, pass: p },
            ))
        })
        .sum::<Vec3>()
        / passes as f32;
    assert!(
        (mean - power).abs().max_element() < 2e-3 * power.max_element(),
        "{mean} vs {power}"
    );
}

/// One-sided surfaces seen from behind reflect nothing: a light inside an outward-facing box
/// makes no VPL.
#[test]
fn backs_of_one_sided_surfaces_make_no_vpls() {
    let box_mesh = cuboid("box", Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], 0);
    let s = scene(
        vec![box_mesh],
        false,
        Light::Point {
            position: Vec3::ZERO,
            intensity: Vec3::ONE,
        },
    );
    let tracer = Tracer::new(&s);
    let rsm = trace_rsm(&s, &tracer, &s.lights[0], 8, TexelSample::Centre);
    assert!(rsm.texels.iter().all(Option::is_none));
}

/// A spot light delivers `I ∫ falloff dω = 2π I (h(θi) + (h(θo) − h(θi))/3)` with `h = 1 −
/// cos` (the falloff `((cos θ − cos θo)/(cos θi − cos θo))²` integrated over `u = cos θ`), for
/// cones from 34° down to 0.01° (where `cos θ` is 1 in `f32`).
#[test]
fn spot_light_power_matches_its_cone() {
    let floor = quad(
        "floor",
        Vec3::new(-50.0, 0.0, 50.0),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -100.0),
        0,
    );
    for (inner, outer) in [
        (0.3f32, 0.6f32),
        (0.0, 1f32.to_radians()),
        (0.0, 0.01f32.to_radians()),
    ] {
        let light = Light::Spot {
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: Vec3::NEG_Y,
            intensity: Vec3::ONE,
            inner_cone_angle: inner,
            outer_cone_angle: outer,
        };
        let s = scene(vec![floor.clone()], false, light.clone());
        let tracer = Tracer::new(&s);
        let h = |a: f32| 1.0 - f64::from(a).cos();
        let expected = 2.0 * std::f64::consts::PI * (h(inner) + (h(outer) - h(inner)) / 3.0);
        let got = total_flux(&trace_rsm(&s, &tracer, &light, 256, TexelSample::Centre)).x as f64;
        assert!(
            (got - expected).abs() < 2e-3 * expected,
            "{inner}..{outer} rad: {got} vs {expected}"
        );
    }
}

/// A directional light delivers E times the area it meets: a floor quad inside the map.
#[test]
fn directional_light_power_is_irradiance_times_area() {
    let floor = quad(
        "floor",
        Vec3::new(-1.0, 0.0, 0.5),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        0,
    );
    let light = Light::Directional {
        direction: Vec3::NEG_Y,
        irradiance: Vec3::splat(3.0),
    };
    let s = scene(vec![floor], false, light.clone());
    let tracer = Tracer::new(&s);
    let got = total_flux(&trace_rsm(&s, &tracer, &light, 512, TexelSample::Centre)).x;
    // Area 2, irradiance 3; the texel grid only approximates the quad's outline.
    assert!((got - 6.0).abs() < 0.02 * 6.0, "{got}");
}

/// [`shade_vpls`] with the stochastic estimator of δ = `delta`, without visibility.
fn stochastic(
    tracer: &Tracer,
    g: &GBuffer,
    vpls: &[Vpl],
    delta: f32,
) -> Result<Image, BoundsError> {
    shade_vpls(
        tracer,
        g,
        vpls,
        VplEstimator::Stochastic { delta },
        false,
        &|_| {},
    )
}

/// The estimator of eq. (3) is unbiased: over many ξ draws, the mean image converges to the
/// exact all-VPL sum at every pixel (within 5 standard errors of the mean).
#[test]
fn stochastic_estimate_converges_to_the_exact_sum() {
    let s = builtin("default").unwrap();
    let tracer = Tracer::new(&s);
    let maps: Vec<_> = s
        .lights
        .iter()
        .map(|l| trace_rsm(&s, &tracer, l, 8, TexelSample::Centre))
        .collect();
    let g = trace_gbuffer(
        &s,
        &tracer,
        &s.camera_or_default(),
        24,
        24,
        PixelSample::Centre,
    );
    let exact = shade_vpls(
        &tracer,
        &g,
        &generate_vpls(&maps, 0, LobeSelection::Both),
        VplEstimator::Exact,
        false,
        &|_| {},
    )
    .unwrap();
    let draws = 400;
    let delta = 2e-2;
    let mut sum = vec![0.0f64; exact.pixels.len()];
    let mut sum_sq = vec![0.0f64; exact.pixels.len()];
    let mut rejected_some = false;
    for seed in 0..draws {
        let vpls = generate_vpls(&maps, seed, LobeSelection::Both);
        let est = stochastic(&tracer, &g, &vpls, delta).unwrap();
        for (k, p) in est.pixels.iter().enumerate() {
            assert!(p.is_finite());
            let v = p.x as f64;
            sum[k] += v;
            sum_sq[k] += v * v;
            rejected_some |= (v - exact.pixels[k].x as f64).abs() > 1e-6 * v.abs().max(1e-3);
        }
    }
    assert!(
        rejected_some,
        "delta {delta} must actually reject VPLs for this test to mean anything"
    );
    let n = draws as f64;
    // Pixels lit only by far lobe tails (1e-19) may see no acceptance in 400 draws: an
    // absolute floor of 1e-6 of the image mean keeps them from failing a test about bias.
    let floor = 1e-6 * exact.mean().x as f64;
    for (k, e) in exact.pixels.iter().enumerate() {
        let mean = sum[k] / n;
        let var = (sum_sq[k] / n - mean * mean).max(0.0);
        let se = (var / n).sqrt();
        assert!(
            (mean - e.x as f64).abs() <= 5.0 * se + 1e-6 * e.x as f64 + floor,
            "pixel {k}: mean {mean} vs exact {} (se {se})",
            e.x
        );
    }
}

/// Tiny δ accepts every VPL with p = 1: the estimate equals the exact sum. Huge δ rejects almost
/// everything and stays finite.
#[test]
fn extreme_deltas() {
    let s = builtin("default").unwrap();
    let tracer = Tracer::new(&s);
    let maps = vec![trace_rsm(&s, &tracer, &s.lights[0], 8, TexelSample::Centre)];
    let vpls = generate_vpls(&maps, 5, LobeSelection::Both);
    let g = trace_gbuffer(
        &s,
        &tracer,
        &s.camera_or_default(),
        16,
        16,
        PixelSample::Centre,
    );
    let exact = shade_vpls(&tracer, &g, &vpls, VplEstimator::Exact, false, &|_| {}).unwrap();
    let tiny = stochastic(&tracer, &g, &vpls, 1e-9).unwrap();
    assert!(tiny.rmse(&exact) <= 1e-6 * exact.mean().max_element());
    for delta in [1e3f32, 1e30] {
        let huge = stochastic(&tracer, &g, &vpls, delta).unwrap();
        assert!(huge.is_finite_non_negative());
    }
    assert!(stochastic(&tracer, &g, &vpls, 0.0).is_err());
}

/// A light of zero intensity renders black everywhere, with no NaN.
#[test]
fn zero_flux_renders_black() {
    let mut s = builtin("default").unwrap();
    s.lights = vec![Light::Point {
        position: Vec3::new(0.0, 1.5, 0.0),
        intensity: Vec3::ZERO,
    }];
    for method in [
        Method::Stochastic(unculled(1e-3)),
        Method::Stochastic(Stochastic {
            strategy: Strategy::Ellipsoid,
            interleave: 4,
            denoise: true,
            ..unculled(1e-3)
        }),
        Method::VplReference,
        Method::Path,
    ] {
        let settings = RenderSettings {
            width: 16,
            height: 16,
            rsm_resolution: 4,
            seed: 0,
            method,
            visibility: true,
            spp: 2,
            lobes: LobeSelection::Both,
        };
        let f = render(&s, &settings, &|_| {}).unwrap();
        assert!(
            f.direct
                .pixels
                .iter()
                .chain(&f.indirect.pixels)
                .all(|p| *p == Vec3::ZERO),
            "{method:?}"
        );
    }
}

/// Out-of-domain settings and scenes are errors, not panics.
#[test]
fn bad_settings_and_scenes_are_errors() {
    let s = builtin("default").unwrap();
    let ok = RenderSettings {
        width: 8,
        height: 8,
        rsm_resolution: 4,
        seed: 0,
        method: Method::Path,
        visibility: false,
        spp: 1,
        lobes: LobeSelection::Both,
    };
    for bad in [
        RenderSettings {
            width: 0,
            ..ok.clone()
        },
        RenderSettings {
            spp: 0,
            ..ok.clone()
        },
        RenderSettings {
            rsm_resolution: 0,
            ..ok.clone()
        },
        RenderSettings {
            method: Method::Stochastic(unculled(f32::NAN)),
            ..ok.clone()
        },
        RenderSettings {
            method: Method::Stochastic(unculled(-1.0)),
            ..ok.clone()
        },
        RenderSettings {
            method: Method::Stochastic(Stochastic {
                interleave: 0,
                ..unculled(1e-3)
            }),
            ..ok.clone()
        },
    ] {
        assert!(
            matches!(render(&s, &bad, &|_| {}), Err(RenderError::Settings(_))),
            "{bad:?}"
        );
    }
    let mut dark = s.clone();
    dark.lights.clear();
    assert!(matches!(
        render(&dark, &ok, &|_| {}),
        Err(RenderError::Scene(slc_core::SceneError::NoLight { .. }))
    ));
    let mut nan = s.clone();
    nan.lights[0] = Light::Point {
        position: Vec3::NAN,
        intensity: Vec3::ONE,
    };
    assert!(render(&nan, &ok, &|_| {}).is_err());
}

/// An alpha-masked quad (its left half cut away) in front of a wall: camera, RSM and shadow
/// rays all pass through the cut half and stop at the kept one, from either side.
#[test]
fn alpha_masks_cut_every_ray() {
    use glam::Vec2;
    use slc_core::texture::Texture;
    use slc_core::AlphaMask;
    let mut sheet = quad("sheet", Vec3::ZERO, Vec3::X, Vec3::Y, 1);
    sheet.uvs = Some(vec![
        Vec2::new(0.0, 1.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(0.0, 0.0),
    ]);
    let wall = quad(
        "wall",
        Vec3::new(-5.0, -5.0, -1.0),
        Vec3::new(10.0, 0.0, 0.0),
        Vec3::new(0.0, 10.0, 0.0),
        0,
    );
    let light = Light::Point {
        position: Vec3::new(0.5, 0.5, 1.0),
        intensity: Vec3::ONE,
    };
    let mut s = scene(vec![wall, sheet], false, light);
    let mut masked = s.materials[0].clone();
    masked.alpha_mask = Some(AlphaMask {
        cutoff: 0.5,
        factor: 1.0,
        texture: Some(0),
    });
    s.materials.push(masked);
    s.textures.push(Texture {
        name: "coverage".into(),
        width: 2,
        height: 1,
        texels: vec![Vec3::ZERO, Vec3::ONE],
    });
    let tracer = Tracer::new(&s);
    for (x, expected) in [(0.25, 2.0), (0.75, 1.0)] {
        let from = Vec3::new(x, 0.5, 1.0);
        let hit = tracer
            .intersect(&s, from, Vec3::NEG_Z, f32::INFINITY)
            .unwrap();
        assert!(
            (hit.distance - expected).abs() < 1e-5,
            "x {x}: {}",
            hit.distance
        );
        let behind = Vec3::new(x, 0.5, -0.5);
        assert_eq!(tracer.unoccluded(from, behind), expected == 2.0, "x {x}");
        // From behind the (one-sided) sheet as well.
        assert_eq!(tracer.unoccluded(behind, from), expected == 2.0, "x {x}");
    }
    // The RSM: light through the cut half reaches the wall, the kept half shades it.
    let rsm = trace_rsm(&s, &tracer, &s.lights[0], 32, TexelSample::Centre);
    let on_wall = |t: &&slc_cpu_ref::rsm::RsmTexel| t.position.z < -0.5;
    let lit_wall: Vec<_> = rsm.texels.iter().flatten().filter(on_wall).collect();
    assert!(lit_wall
        .iter()
        .any(|t| t.position.x > 0.0 && t.position.x < 0.5 && (t.position.y - 0.5).abs() < 0.2));
    assert!(!lit_wall
        .iter()
        .any(|t| t.position.x > 0.55 && t.position.x < 0.95 && (t.position.y - 0.5).abs() < 0.2));
    assert!(rsm
        .texels
        .iter()
        .flatten()
        .any(|t| t.position.z == 0.0 && t.position.x > 0.5));
    assert!(!rsm
        .texels
        .iter()
        .flatten()
        .any(|t| t.position.z == 0.0 && t.position.x < 0.5));
}
