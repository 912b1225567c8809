//! What a GPU frame reads back: its images, the 16-byte fault record of the culling passes
//! (read after the shading; two for the tight strategies, whose refinement has its own) or
//! the 32-byte one of a VSGL frame, and the VPL count for the frame's report (12 bytes,
//! after the frame). Nothing between VPL generation and the shaded image: the VPL count
//! stays on the GPU (`device::count`), the list cullers write into a buffer sized from earlier
//! frames (`cull::room`) and the VSGLs are built there. On a GPU whose timestamps measure
//! execution (`GpuContext::timestamps_trusted`: not lavapipe), a frame also reads back its
//! per-pass timestamps, two 8-byte stamps per pass.
use crate::common::{gpu, small_frame};
use glam::Vec3;
use slc_core::frame::{DiffuseEmission, Importance, LightSampling, Method, RenderSettings};
use slc_core::render::render;
use slc_core::{builtin, Interleaving, Light, Renderer, Strategy};
use slc_gpu_wgpu::GpuRenderer;
use std::collections::BTreeMap;

/// The bytes read back by label between two readings of the renderer's counters, less the
/// timestamps a step may read ([`without_timestamps`]).
fn read_since(before: &BTreeMap<String, u64>, r: &GpuRenderer) -> BTreeMap<String, u64> {
    let read = r
        .readback_bytes()
        .unwrap()
        .into_iter()
        .map(|(k, v)| {
            let was = before.get(&k).copied().unwrap_or(0);
            (k, v - was)
        })
        .filter(|(_, v)| *v > 0)
        .collect();
    without_timestamps(r, read, false)
}

fn labels(entries: &[(&str, u64)]) -> BTreeMap<String, u64> {
    entries.iter().map(|&(k, v)| (k.to_owned(), v)).collect()
}

/// `read` without its timestamps (two u64 per pass), read only where the adapter's
/// timestamps are trusted: there a whole `frame` reads some, a step may.
fn without_timestamps(
    r: &GpuRenderer,
    mut read: BTreeMap<String, u64>,
    frame: bool,
) -> BTreeMap<String, u64> {
    let stamps = read.remove("timestamps").unwrap_or(0);
    assert!(stamps.is_multiple_of(16), "{stamps} bytes of timestamps");
    if r.context().timestamps_trusted {
        assert!(stamps > 0 || !frame, "no timestamps");
    } else {
        assert_eq!(stamps, 0);
    }
    read
}

/// The fault records a frame of `strategy` reads after its shading: none without culling,
/// two where the tight refinement follows the base lists or binned's lists its tiles' bins,
/// else one.
fn status_bytes(strategy: Strategy) -> u64 {
    match strategy {
        Strategy::None => 0,
        Strategy::Tight | Strategy::ClusteredTight | Strategy::Binned => 32,
        _ => 16,
    }
}

/// Frames of every strategy (no metrics), the tiled ones also through light lists
/// (`--gpu-tiled lists`), read back their two images, the culling's fault records and, for
/// the report, the VPL count; step by step, culling reads nothing and shading only the
/// fault records.
#[test]
fn stochastic_frames_read_back_their_images_only() {
    let Some(ctx) = gpu() else { return };
    let mut r = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    let image = 64 * 48 * 3 * 4;
    let one_pass = [Strategy::Sphere, Strategy::Ellipsoid];
    let runs = Strategy::every()
        .map(|s| (s, true))
        .chain(one_pass.map(|s| (s, false)));
    for (strategy, one_pass) in runs {
        r.set_one_pass(one_pass);
        let mut settings = small_frame(strategy, false);
        if let Method::Stochastic(s) = &mut settings.method {
            s.metrics = false;
        }
        let frame = render(&r, &scene, &settings, &|_| {}).unwrap();
        assert!(frame.vpl_count > 0);
        let status = status_bytes(strategy);
        let mut expected = labels(&[
            ("cull status", status),
            ("direct image", image),
            ("indirect image", image),
            ("vpl count", 12),
        ]);
        expected.retain(|_, v| *v > 0);
        assert_eq!(
            without_timestamps(&r, frame.readback_bytes.unwrap(), true),
            expected,
            "{strategy}, one pass {one_pass}"
        );
        // Step by step: preparing reads the direct image, culling nothing, shading the
        // culling's fault record after its dispatch.
        let loaded = r.load(&scene).unwrap();
        let start = r.readback_bytes().unwrap();
        let p = r
            .prepare(&scene, &loaded, &settings, None, &|_| {})
            .unwrap();
        assert_eq!(read_since(&start, &r), labels(&[("direct image", image)]));
        let k = Interleaving { k: 4, seed: 2 };
        let before = r.readback_bytes().unwrap();
        let lists = r.cull(&p, strategy, 1e-3, k).unwrap();
        assert_eq!(read_since(&before, &r), labels(&[]), "{strategy} culling");
        let shaded = r
            .shade_lists(&loaded, &p, &lists, 1e-3, k, false, &|_| {})
            .unwrap();
        let mut expected = labels(&[("cull status", status)]);
        expected.retain(|_, v| *v > 0);
        assert_eq!(read_since(&before, &r), expected, "{strategy} shading");
        drop(shaded);
    }
}

/// Lists that outgrow the room their culler leaves are culled and shaded again: the same
/// image, bit for bit (list order is fixed; the rasterized clusters' atomics order nodes
/// differently between runs), the same metrics; the culler learns the room, so the next
/// frame is culled once. With the room 1, the tight strategies outgrow twice (the base
/// lists, then the refined ones), and binned (its tiles' bins, then its lists).
#[test]
fn lists_that_outgrow_their_buffer_are_culled_again() {
    let Some(ctx) = gpu() else { return };
    let r = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    for strategy in [
        Strategy::Clustered,
        Strategy::Tight,
        Strategy::ClusteredTight,
        Strategy::Binned,
        Strategy::None,
        Strategy::ClusteredRaster,
    ] {
        let settings = small_frame(strategy, false);
        r.set_list_room(1 << 20);
        let roomy = render(&r, &scene, &settings, &|_| {}).unwrap();
        r.set_list_room(1);
        let cramped = render(&r, &scene, &settings, &|_| {}).unwrap();
        let again = render(&r, &scene, &settings, &|_| {}).unwrap();
        for frame in [&cramped, &again] {
            let metrics = frame.metrics.as_ref().unwrap();
            assert_eq!(metrics, roomy.metrics.as_ref().unwrap(), "{strategy}");
            assert_eq!(metrics.missed_pairs, 0, "{strategy}");
            let worst = frame
                .indirect
                .pixels
                .iter()
                .zip(&roomy.indirect.pixels)
                .map(|(a, b)| (*a - *b).abs().max_element() / b.abs().max_element().max(1e-6))
                .fold(0.0f32, f32::max);
            let tolerance = if strategy == Strategy::ClusteredRaster {
                1e-5
            } else {
                0.0
            };
            assert!(worst <= tolerance, "{strategy}: {worst}");
        }
        let status = |f: &slc_core::frame::RenderedFrame| {
            f.readback_bytes
                .as_ref()
                .unwrap()
                .get("cull status")
                .copied()
                .unwrap_or(0)
        };
        // A frame that outgrew reads more records (each culling's again); once the room is
        // learnt, as many as a frame with ample room.
        assert_eq!(status(&again), status(&roomy), "{strategy}");
        if strategy == Strategy::None {
            assert_eq!(status(&cramped), 0);
        } else {
            assert!(status(&cramped) > status(&roomy), "{strategy}");
        }
    }
}

/// Lights without flux make no VPL: the count on the GPU is 0 and every strategy shades
/// black from buffers sized for the VPLs there could have been.
#[test]
fn frames_without_vpls_shade_black() {
    let Some(ctx) = gpu() else { return };
    let r = GpuRenderer::from_context(ctx).unwrap();
    let mut scene = builtin("default").unwrap();
    for light in &mut scene.lights {
        match light {
            Light::Point { intensity, .. } | Light::Spot { intensity, .. } => {
                *intensity = Vec3::ZERO
            }
            Light::Directional { irradiance, .. } => *irradiance = Vec3::ZERO,
        }
    }
    for strategy in Strategy::ALL.iter().chain(&Strategy::RASTER) {
        let frame = render(&r, &scene, &small_frame(*strategy, false), &|_| {}).unwrap();
        assert_eq!(frame.vpl_count, 0, "{strategy}");
        assert!(
            frame.indirect.pixels.iter().all(|p| *p == Vec3::ZERO),
            "{strategy}"
        );
        let metrics = frame.metrics.unwrap();
        assert_eq!(metrics.missed_pairs, 0, "{strategy}");
    }
}

/// A VSGL frame reads back its images, the VSGL fault record and the VPL count.
#[test]
fn vsgl_frames_read_back_their_images_only() {
    let Some(ctx) = gpu() else { return };
    let r = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    for importance in [
        Importance::Flux,
        Importance::Bidirectional { camera_vsgls: 32 },
    ] {
        let settings = RenderSettings {
            method: Method::Vsgl(LightSampling {
                count: 256,
                importance,
                diffuse: DiffuseEmission::ClampedCosine,
            }),
            ..small_frame(Strategy::Ellipsoid, false)
        };
        let frame = render(&r, &scene, &settings, &|_| {}).unwrap();
        let image = 64 * 48 * 3 * 4;
        assert_eq!(
            without_timestamps(&r, frame.readback_bytes.unwrap(), true),
            labels(&[
                ("direct image", image),
                ("indirect image", image),
                ("vpl count", 12),
                ("vsgl status", 32),
            ]),
            "{}",
            importance.name()
        );
        assert!(frame.sampled_lights.unwrap() > 100);
    }
}
