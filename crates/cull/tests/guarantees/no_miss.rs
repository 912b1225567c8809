//! No strategy ever culls a contributing VPL (missed pairs = 0 against the brute-force truth).
use crate::common::*;
use slc_core::frame::LobeSelection;
use slc_core::{Camera, CullInput, GBuffer, Vpl};

/// A random room: a floor G-buffer by ray casting from a random camera (1 to 90 x 1 to 70
/// pixels), up to 240 VPLs around it, δ from 1e-6 to 1e-1 and K from 1 to `max_k`.
struct Room {
    camera: Camera,
    gbuffer: GBuffer,
    vpls: Vec<Vpl>,
    delta: f32,
    k: u32,
    label: String,
}

impl Room {
    fn input(&self) -> CullInput<'_> {
        input(&self.gbuffer, &self.camera, &self.vpls, self.delta, self.k)
    }

    fn random(rng: &mut Rng, case: u32, max_k: u32) -> Self {
        let camera = floor_camera(rng);
        let (w, h) = (1 + rng.below(90), 1 + rng.below(70));
        let gbuffer = floor_gbuffer(&camera, w, h, rng);
        let count = rng.below(240);
        let vpls = room_vpls(rng, count);
        let delta = rng.log(-6.0, -1.0);
        let k = 1 + rng.below(max_k);
        let label = format!("room {case} ({w}x{h}, {count} VPLs, delta {delta:.1e}, K {k})");
        Self {
            camera,
            gbuffer,
            vpls,
            delta,
            k,
            label,
        }
    }
}

/// 300 random rooms: a floor G-buffer by ray casting (jittered, often exactly on pixel corners
/// and edges; sky above the horizon), VPLs on the walls and ceiling, hanging just above the
/// floor and anywhere around (also behind the camera), random lobes, α from 1e-3 to 1, δ from
/// 1e-6 to 1e-1, K from 1 to 5, image sizes from 1 to 90 pixels.
#[test]
fn synthetic_rooms_never_miss() {
    let mut rng = Rng::new(1);
    let (mut contributing, mut listed_none, mut listed_ellipsoid) = (0u64, 0u64, 0u64);
    for case in 0..300 {
        let room = Room::random(&mut rng, case, 5);
        let label = &room.label;
        let all = check_all(&room.input(), label);
        contributing += of(&all, "none").true_positive_pairs;
        listed_none += of(&all, "none").true_positive_pairs + of(&all, "none").false_positive_pairs;
        let e = of(&all, "ellipsoid");
        listed_ellipsoid += e.true_positive_pairs + e.false_positive_pairs;
    }
    println!(
        "rooms: {contributing} contributing pairs, {listed_ellipsoid} listed by ellipsoid, \
         {listed_none} by none"
    );
    // The test has teeth: many pairs contribute, and culling removes most of the others.
    assert!(contributing > 100_000, "{contributing}");
    assert!(
        listed_ellipsoid < listed_none / 2,
        "{listed_ellipsoid} vs {listed_none}"
    );
}

/// The built-in default scene (jittered G-buffer, VPLs of both lobes), K = 1, 4 and 8, δ from
/// 1e-5 to 1e-1.
#[test]
fn default_scene_never_misses() {
    let (scene, camera) = default_scene();
    let (gbuffer, vpls) = frame(&scene, &camera, (160, 120), 16, LobeSelection::Both);
    let cases = [
        (1, 1e-3),
        (4, 1e-3),
        (4, 1e-5),
        (4, 1e-1),
        (1, 1e-2),
        (8, 1e-3),
    ];
    never_misses("default scene", (&gbuffer, &camera, &vpls), &cases);
}

/// The default scene with its spot narrowed from 10° to 0.5° (and its intensity raised by the
/// ratio of the cones' powers, so the VPLs carry the same flux): the VPLs of a narrow cone,
/// lit with the falloff that no longer dims it, miss nothing either.
#[test]
fn a_narrow_spot_never_misses() {
    let (mut scene, camera) = default_scene();
    let Some(slc_core::Light::Spot {
        intensity,
        outer_cone_angle,
        inner_cone_angle,
        ..
    }) = scene.lights.first_mut()
    else {
        panic!("the default scene has a spot light")
    };
    let narrow = 0.5f32.to_radians();
    let power = |inner: f32, outer: f32| {
        let h = |a: f32| 1.0 - f64::from(a).cos();
        h(inner) + (h(outer) - h(inner)) / 3.0
    };
    *intensity *= (power(*inner_cone_angle, *outer_cone_angle) / power(0.0, narrow)) as f32;
    (*inner_cone_angle, *outer_cone_angle) = (0.0, narrow);
    let (gbuffer, vpls) = frame(&scene, &camera, (96, 72), 16, LobeSelection::Both);
    never_misses("narrow spot", (&gbuffer, &camera, &vpls), &[(4, 1e-3)]);
}

/// Dabrovic Sponza (with a point light, a camera in the atrium and glossy layers of α from
/// 1e-3 to 1), K = 1 and 4, δ from 1e-3 to 1e-1.
#[test]
fn sponza_never_misses() {
    let (scene, camera) = sponza();
    let (gbuffer, vpls) = frame(&scene, &camera, (160, 96), 12, LobeSelection::Both);
    let seen = gbuffer.samples.iter().flatten().count();
    assert!(
        seen > gbuffer.samples.len() / 2,
        "the camera sees the atrium: {seen}"
    );
    let cases = [(1, 1e-3), (4, 1e-3), (1, 1e-2), (4, 1e-1)];
    never_misses("sponza", (&gbuffer, &camera, &vpls), &cases);
}

/// `scenes/materials` (normal-mapped glossy floor, cut-outs, a double-sided sheet) with the
/// floor's roughness 0.4 (as authored, α 0.16) and 0.1 (α 0.01), K = 1 and 4, δ 1e-3 and
/// 1e-2: bounds built around normal-mapped shading normals miss nothing.
#[test]
fn materials_scene_never_misses() {
    for roughness in [0.4, 0.1] {
        let (scene, camera) = materials_scene(roughness);
        let (gbuffer, vpls) = frame(&scene, &camera, (128, 128), 24, LobeSelection::Both);
        let label = format!("materials, roughness {roughness}");
        let cases = [(1, 1e-3), (4, 1e-3), (4, 1e-2)];
        never_misses(&label, (&gbuffer, &camera, &vpls), &cases);
    }
}

/// `scenes/anisotropy`, K = 1 and 4, δ 1e-3 and 1e-2: anisotropic VPLs (their bounds: the
/// isotropic lobe of the larger α, the flux times `GlossyLobe::bound_factor`) miss nothing.
#[test]
fn anisotropy_scene_never_misses() {
    let (scene, camera) = anisotropy_scene();
    let (gbuffer, vpls) = frame(&scene, &camera, (128, 128), 24, LobeSelection::Both);
    assert!(vpls.iter().any(|v| v.brdf.anisotropy.is_some()));
    let cases = [(1, 1e-3), (4, 1e-3), (4, 1e-2)];
    never_misses("anisotropy", (&gbuffer, &camera, &vpls), &cases);
}

/// [`check_all`] on one frame for each (K, δ) of `cases`, printing every strategy's metrics;
/// each case must hold more than 5,000 contributing pairs (so that "no miss" says something).
fn never_misses(
    label: &str,
    (gbuffer, camera, vpls): (&GBuffer, &Camera, &[Vpl]),
    cases: &[(u32, f32)],
) {
    for &(k, delta) in cases {
        let label = format!("{label}, K {k}, delta {delta}");
        let all = check_all(&input(gbuffer, camera, vpls, delta, k), &label);
        println!("{label}, {} VPLs", vpls.len());
        for (name, m) in &all {
            println!("{}", line(name, m));
        }
        assert!(of(&all, "none").true_positive_pairs > 5_000);
    }
}

/// `binned`'s cells ([`BinnedCuller::shared_above`]): 200 random rooms with every VPL (0),
/// those above 64 pixels, the default and none (`u64::MAX`) shared per cell. A pixel's
/// union holds every VPL the per-pixel test passes there (the cell test is conservative),
/// its own list only VPLs not shared, and no pair is missed; the cells are used.
#[test]
fn binned_cells_keep_every_pixel_the_pixel_test_passes() {
    use slc_core::Culler;
    use slc_cull::BinnedCuller;
    let mut rng = Rng::new(9);
    let (mut shared_pixels, mut checked) = (0u64, 0u64);
    for case in 0..200 {
        let room = Room::random(&mut rng, case, 3);
        let (label, gbuffer) = (&room.label, &room.gbuffer);
        let input = room.input();
        let exact = BinnedCuller::per_pixel().cull(&input).unwrap();
        assert!(exact.shared_list.is_empty(), "{label}");
        for shared_above in [0, 64, BinnedCuller::default().shared_above] {
            let lists = BinnedCuller { shared_above }.cull(&input).unwrap();
            lists.check(gbuffer.samples.len(), room.vpls.len()).unwrap();
            let m = slc_cull::metrics::measure(&input, &lists).unwrap();
            assert_eq!(m.missed_pairs, 0, "{label}, above {shared_above}");
            for p in 0..gbuffer.samples.len() {
                let union = lists.for_pixel(p);
                let [own, shared] = lists.lists_of(p);
                assert!(
                    exact.for_pixel(p).iter().all(|v| union.contains(v)),
                    "{label}, above {shared_above}: pixel {p}"
                );
                assert!(
                    own.iter().all(|v| !shared.contains(v)),
                    "{label}: pixel {p}"
                );
                shared_pixels += u64::from(!shared.is_empty());
                checked += 1;
            }
        }
    }
    println!("{shared_pixels} of {checked} pixel lists with a shared list");
    assert!(shared_pixels * 10 > checked, "{shared_pixels} of {checked}");
}
