//! Scenes, VPLs and the checks shared by the guarantee tests.
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::shading_normal::flux_scale;
use slc_bounds::{scalar_intensity, Brdf, Fresnel, StochasticParams};
use slc_core::frame::LobeSelection;
use slc_core::Strategy;
use slc_core::{
    builtin, load_scene, Camera, CullInput, GBuffer, GSample, Interleaving, LightLists, Material,
    MaterialModel, Scene, Vpl, VplLobe,
};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::rsm::{trace_rsm, TexelSample};
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::Tracer;
use slc_cull::culler;
use slc_cull::metrics::{measure_all, CullMetrics};
use std::f64::consts::PI;

#[path = "../../../../tests/fixtures/scenes.rs"]
mod scenes;
pub use scenes::sponza;

#[path = "../../../../tests/fixtures/rng.rs"]
mod rng;
pub use rng::Rng;

/// A G-buffer of the floor plane y = 0 seen by `camera`, one ray per pixel through a random
/// point of the pixel (often exactly on its corner or edges); rays that miss the floor see sky.
pub fn floor_gbuffer(camera: &Camera, width: u32, height: u32, rng: &mut Rng) -> GBuffer {
    let brdf = Brdf {
        kd: Vec3::splat(0.5),
        fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
        alpha: 0.5,
        anisotropy: None,
    };
    let jitter = |rng: &mut Rng| match rng.below(4) {
        0 => 0.0,
        1 => 1.0 - f32::EPSILON / 2.0,
        _ => rng.f32(),
    };
    let samples = (0..width * height)
        .map(|p| {
            let (s, t) = (jitter(rng), jitter(rng));
            let dir = camera.ray_direction(p % width, p / width, s, t, width, height);
            let t_hit = -camera.position.y / dir.y;
            (dir.y < 0.0 && t_hit.is_finite()).then(|| {
                let position = camera.position + dir * t_hit;
                GSample {
                    position: Vec3::new(position.x, 0.0, position.z),
                    normal: Vec3::Y,
                    geometric_normal: Vec3::Y,
                    omega_o: -dir,
                    depth: camera.view_depth(position),
                    brdf,
                }
            })
        })
        .collect();
    GBuffer {
        width,
        height,
        samples,
    }
}

/// A random camera above the floor looking at it from 0.3..3 units up (the horizon is often in
/// view, so part of the image is sky).
pub fn floor_camera(rng: &mut Rng) -> Camera {
    let eye = Vec3::new(
        rng.range(-1.0, 1.0),
        rng.range(0.3, 3.0),
        rng.range(2.0, 5.0),
    );
    let target = Vec3::new(
        rng.range(-2.0, 2.0),
        rng.range(-0.5, 1.5),
        rng.range(-6.0, 0.0),
    );
    Camera::look_at(eye, target, Vec3::Y, rng.range(20.0, 100.0).to_radians()).unwrap()
}

/// `n` random VPLs in a room around the floor: on the walls x = ±4, the back wall z = −8, the
/// ceiling y = 3, hanging 1e-3 to 0.3 above the floor facing it (small lit discs), or
/// anywhere (also behind the camera) with random normals; random incoming directions (one in
/// five below the surface), random lobes, α from 1e-3 to 1,
/// flux from 1e-4 to 10 (one in ten zero), Schlick or dielectric Fresnel, ξ in (0, 1).
pub fn room_vpls(rng: &mut Rng, n: u32) -> Vec<Vpl> {
    (0..n)
        .map(|id| {
            let (position, normal) = match rng.below(6) {
                0 => (
                    Vec3::new(-4.0, rng.range(0.0, 3.0), rng.range(-8.0, 6.0)),
                    Vec3::X,
                ),
                1 => (
                    Vec3::new(4.0, rng.range(0.0, 3.0), rng.range(-8.0, 6.0)),
                    Vec3::NEG_X,
                ),
                2 => (
                    Vec3::new(rng.range(-4.0, 4.0), rng.range(0.0, 3.0), -8.0),
                    Vec3::Z,
                ),
                3 => (
                    Vec3::new(rng.range(-4.0, 4.0), 3.0, rng.range(-8.0, 6.0)),
                    Vec3::NEG_Y,
                ),
                // Hanging just above the floor, facing it: small lit discs, tile edges matter.
                4 => (
                    Vec3::new(
                        rng.range(-4.0, 4.0),
                        rng.log(-3.0, -0.5),
                        rng.range(-8.0, 6.0),
                    ),
                    Vec3::NEG_Y,
                ),
                _ => (
                    Vec3::new(
                        rng.range(-6.0, 6.0),
                        rng.range(-1.0, 5.0),
                        rng.range(-10.0, 10.0),
                    ),
                    rng.unit(),
                ),
            };
            let mut omega_i = rng.unit();
            if (omega_i.dot(normal) < 0.0) != rng.chance(0.2) {
                omega_i = -omega_i;
            }
            let flux = if rng.chance(0.1) {
                Vec3::ZERO
            } else {
                Vec3::new(rng.log(-4.0, 1.0), rng.log(-4.0, 1.0), rng.log(-4.0, 1.0))
            };
            let fresnel = if rng.chance(0.7) {
                Fresnel::Schlick(Vec3::new(rng.f32(), rng.f32(), rng.f32()))
            } else {
                Fresnel::Dielectric(rng.range(1.1, 2.5))
            };
            let kd = if rng.chance(0.1) {
                Vec3::ZERO
            } else {
                Vec3::new(rng.f32(), rng.f32(), rng.f32())
            };
            Vpl {
                position,
                normal,
                geometric_normal: normal,
                omega_i,
                flux,
                brdf: Brdf {
                    kd,
                    fresnel,
                    alpha: rng.log(-3.0, 0.0),
                    anisotropy: None,
                },
                lobe: if rng.chance(0.5) {
                    VplLobe::Diffuse
                } else {
                    VplLobe::Glossy
                },
                id,
                xi: rng.range(1e-6, 1.0 - 1e-6),
            }
        })
        .collect()
}

/// Every strategy's lists for `input` and their metrics, after checking what every strategy
/// must guarantee: no contributing pair missed, well-formed ascending lists without repeats,
/// only the pixel's own subregion's VPLs, no list for a pixel without a sample, finite
/// metrics. Returns (name, metrics) in the order of `Strategy::on_cpu`.
pub fn check_all(input: &CullInput, label: &str) -> Vec<(&'static str, CullMetrics)> {
    let strategies: Vec<Strategy> = Strategy::on_cpu().collect();
    let lists: Vec<LightLists> = strategies
        .iter()
        .map(|&name| {
            let culler = culler(name);
            culler
                .cull(input)
                .unwrap_or_else(|e| panic!("{label}: {name} failed: {e}"))
        })
        .collect();
    let refs: Vec<&LightLists> = lists.iter().collect();
    let metrics = measure_all(input, &refs).unwrap();
    let contributing = metrics[0].true_positive_pairs + metrics[0].missed_pairs;
    assert_eq!(
        contributing,
        accepted_pairs(input),
        "{label}: the metrics' early exits dropped accepted pairs"
    );
    let w = input.gbuffer.width.max(1);
    for ((name, l), m) in strategies.iter().zip(&lists).zip(&metrics) {
        assert_eq!(
            m.missed_pairs, 0,
            "{label}: {name} culled {} contributing pairs",
            m.missed_pairs
        );
        assert_eq!(m.true_positive_pairs, contributing, "{label}: {name}");
        assert!(m.lights_per_pixel_mean.is_finite() && m.false_discovery_rate.is_finite());
        assert!(m.fdr_per_pixel.iter().all(|f| f.is_finite()));
        for (p, sample) in input.gbuffer.samples.iter().enumerate() {
            let list = l.for_pixel(p);
            if sample.is_none() {
                assert!(list.is_empty(), "{label}: {name}: sky pixel {p}");
            }
            assert!(
                list.windows(2).all(|w| w[0] < w[1]),
                "{label}: {name}: order"
            );
            let s = input
                .interleaving
                .pixel_subregion(p as u32 % w, p as u32 / w);
            for &i in list.iter() {
                let vpl = &input.vpls[i as usize];
                assert_eq!(
                    input.interleaving.vpl_subregion(vpl.id),
                    s,
                    "{label}: {name}"
                );
            }
        }
    }
    // A tight strategy only cuts its base strategy's lists: pixel by pixel a subset.
    let lists_of = |s: Strategy| &lists[strategies.iter().position(|&t| t == s).unwrap()];
    for (tight, base) in [
        (Strategy::Tight, Strategy::Ellipsoid),
        (Strategy::ClusteredTight, Strategy::Clustered),
    ] {
        let (t, b) = (lists_of(tight), lists_of(base));
        for p in 0..input.gbuffer.samples.len() {
            let base_list = b.for_pixel(p);
            assert!(
                t.for_pixel(p)
                    .iter()
                    .all(|i| base_list.binary_search(i).is_ok()),
                "{label}: {tight} lists a VPL {base} does not at pixel {p}"
            );
        }
    }
    strategies.iter().map(|s| s.name()).zip(metrics).collect()
}

/// The pairs the roulette of eq. (3) accepts, p(ωo, l) > ξ with p of eq. (2) evaluated for
/// every VPL of every pixel's subregion, with no bound of slc-bounds or early exit: what the
/// metrics' truth (which skips the pairs outside each VPL's own bound) must count too. Only
/// pairs beyond twice the range of the VPL's peak intensity are skipped: p > ξ needs
/// l² < I/(δ ξ) (eq. 5), and I(ωo) <= max(Φ kd)/π for a diffuse VPL, max(Φ)/(4π α² ωi·n) for
/// a glossy one (eq. 4, 6: F <= 1, G2 <= 1, D <= 1/(π α²)), times the tilt factor of a
/// normal-mapped one.
fn accepted_pairs(input: &CullInput) -> u64 {
    let w = input.gbuffer.width.max(1);
    let params: Vec<_> = input
        .vpls
        .iter()
        .map(|v| {
            let r = StochasticParams::new(input.delta, v.xi).unwrap();
            let cos_i = f64::from(v.normal.dot(v.omega_i));
            // A normal-mapped or anisotropic VPL's intensity may exceed these by its bound
            // factor (`slc_bounds::shading_normal`, `slc_bounds::anisotropy`), with the
            // lobe's largest α.
            let peak = match v.lobe {
                VplLobe::Diffuse => {
                    let scale = flux_scale(v.normal, v.geometric_normal, v.omega_i);
                    (v.flux * v.brdf.kd).as_dvec3().max_element() / PI * f64::from(scale)
                }
                VplLobe::Glossy => {
                    let (alpha, factor) = v
                        .glossy_lobe()
                        .map_or((v.brdf.alpha, 1.0), |l| (l.alpha(), l.bound_factor()));
                    let alpha = f64::from(alpha);
                    f64::from(v.flux.max_element()) * f64::from(factor)
                        / (4.0 * PI * alpha * alpha * cos_i)
                }
            };
            (r, 2.0 * peak / (f64::from(input.delta) * f64::from(v.xi)))
        })
        .collect();
    input
        .gbuffer
        .samples
        .par_iter()
        .enumerate()
        .map(|(p, sample)| {
            let Some(g) = sample else { return 0 };
            let s = input
                .interleaving
                .pixel_subregion(p as u32 % w, p as u32 / w);
            input
                .vpls
                .iter()
                .zip(&params)
                .filter(|(v, (r, reach_sq))| {
                    let d = g.position - v.position;
                    let l2 = d.length_squared();
                    input.interleaving.vpl_subregion(v.id) == s
                        && l2 > 0.0
                        && f64::from(l2) <= *reach_sq
                        && r.probability(scalar_intensity(v.intensity(d / l2.sqrt())), l2) > r.xi()
                })
                .count() as u64
        })
        .sum()
}

/// The metrics of the named strategy in the output of [`check_all`].
pub fn of<'a>(all: &'a [(&'static str, CullMetrics)], name: &str) -> &'a CullMetrics {
    &all.iter().find(|(n, _)| *n == name).unwrap().1
}

/// A scene's G-buffer (jittered primary rays) and VPLs from reflective shadow maps of `rsm`²
/// texels per face.
pub fn frame(
    scene: &Scene,
    camera: &Camera,
    (width, height): (u32, u32),
    rsm: u32,
    lobes: LobeSelection,
) -> (GBuffer, Vec<Vpl>) {
    let tracer = Tracer::new(scene);
    let gbuffer = trace_gbuffer(
        scene,
        &tracer,
        camera,
        width,
        height,
        PixelSample::Jittered { seed: 5, index: 0 },
    );
    let maps: Vec<_> = scene
        .lights
        .iter()
        .map(|l| trace_rsm(scene, &tracer, l, rsm, TexelSample::Centre))
        .collect();
    (gbuffer, generate_vpls(&maps, 11, lobes))
}

/// The built-in default scene (the glossy Cornell room with a copper panel).
pub fn default_scene() -> (Scene, Camera) {
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    (scene, camera)
}

/// The default scene with a glossy floor (kd 0.1, F0 0.9, α 0.1): floor VPLs throw glossy
/// reflections onto the walls.
pub fn glossy_floor_scene() -> (Scene, Camera) {
    let (mut scene, camera) = default_scene();
    let floor = scene.meshes.iter().position(|m| m.name == "floor").unwrap();
    scene.materials.push(Material::direct(
        "glossy floor",
        Vec3::splat(0.1),
        Vec3::splat(0.9),
        0.1,
    ));
    scene.meshes[floor].material = scene.materials.len() - 1;
    (scene, camera)
}

/// `scenes/materials`: a glossy floor whose normal map tilts its shading normals up to 25°
/// off the geometric one (so its VPLs' lobes and bounds are built around tilted normals),
/// and a double-sided alpha-masked sheet; with the floor's roughness set to `roughness`.
pub fn materials_scene(roughness: f32) -> (Scene, Camera) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/materials/materials.gltf"
    );
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let floor = scene
        .materials
        .iter_mut()
        .find(|m| m.normal_map.is_some())
        .expect("the normal-mapped floor");
    if let MaterialModel::MetallicRoughness { roughness: r, .. } = &mut floor.model {
        *r = roughness;
    }
    let camera = scene.camera_or_default();
    (scene, camera)
}

/// `scenes/anisotropy`: a brushed floor and a brushed panel (glTF `KHR_materials_anisotropy`,
/// α_t up to 0.84 against α 0.09 and 0.16), so that VPLs and receivers are anisotropic and the
/// bounds are the isotropic ones of the larger α with the flux times the bound factor.
pub fn anisotropy_scene() -> (Scene, Camera) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/anisotropy/anisotropy.gltf"
    );
    let scene = load_scene(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    assert!(scene.materials.iter().any(|m| m.anisotropy.is_some()));
    let camera = scene.camera_or_default();
    (scene, camera)
}

/// A cull input with interleaving factor `k` (seed 3).
pub fn input<'a>(
    gbuffer: &'a GBuffer,
    camera: &'a Camera,
    vpls: &'a [Vpl],
    delta: f32,
    k: u32,
) -> CullInput<'a> {
    CullInput {
        gbuffer,
        camera,
        vpls,
        delta,
        interleaving: Interleaving { k, seed: 3 },
    }
}

/// One line of metrics for the test log.
pub fn line(name: &str, m: &CullMetrics) -> String {
    format!(
        "{name:>27}: FP {:>10}  TP {:>8}  missed {}  lights/pixel {:>8.2}  FDR {:.4}",
        m.false_positive_pairs,
        m.true_positive_pairs,
        m.missed_pairs,
        m.lights_per_pixel_mean,
        m.false_discovery_rate
    )
}
