//! What a GPU frame reads back: its images, the 16-byte fault record of the culling passes
//! (read after the shading) or the 32-byte one of a VSGL frame, and the VPL count for the
//! frame's report (12 bytes, after the frame). Nothing between VPL generation and the
//! shaded image: the VPL count stays on the GPU (`gpu_count`) and the VSGLs are built there.
use crate::common::{gpu, small_frame};
use glam::Vec3;
use slc_core::frame::{DiffuseEmission, Importance, LightSampling, Method, RenderSettings};
use slc_core::render::render;
use slc_core::{builtin, Interleaving, Light, Renderer, Strategy};
use slc_gpu_wgpu::GpuRenderer;
use std::collections::BTreeMap;

/// The bytes read back by label between two readings of the renderer's counters.
fn read_since(before: &BTreeMap<String, u64>, r: &GpuRenderer) -> BTreeMap<String, u64> {
    r.readback_bytes()
        .unwrap()
        .into_iter()
        .map(|(k, v)| {
            let was = before.get(&k).copied().unwrap_or(0);
            (k, v - was)
        })
        .filter(|(_, v)| *v > 0)
        .collect()
}

fn labels(entries: &[(&str, u64)]) -> BTreeMap<String, u64> {
    entries.iter().map(|&(k, v)| (k.to_owned(), v)).collect()
}

/// Frames of the paper's tiled culling, splatting and the rasterized clusters (no metrics)
/// read back their two images, the culling's fault record and, for the report, the VPL
/// count; step by step, culling reads nothing and shading only the fault record.
#[test]
fn stochastic_frames_read_back_their_images_only() {
    let Some(ctx) = gpu() else { return };
    let r = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    let image = 64 * 48 * 3 * 4;
    for strategy in [
        Strategy::Ellipsoid,
        Strategy::Sphere,
        Strategy::Splatting,
        Strategy::ClusteredRaster,
    ] {
        let mut settings = small_frame(strategy, false);
        if let Method::Stochastic(s) = &mut settings.method {
            s.metrics = false;
        }
        let frame = render(&r, &scene, &settings, &|_| {}).unwrap();
        assert!(frame.vpl_count > 0);
        assert_eq!(
            frame.readback_bytes.unwrap(),
            labels(&[
                ("cull status", 16),
                ("direct image", image),
                ("indirect image", image),
                ("vpl count", 12),
            ]),
            "{strategy}"
        );
        // Step by step: preparing reads the direct image, culling nothing, shading the
        // culling's fault record after its dispatch.
        let loaded = r.load(&scene).unwrap();
        let start = r.readback_bytes().unwrap();
        let p = r.prepare(&scene, &loaded, &settings, None).unwrap();
        assert_eq!(read_since(&start, &r), labels(&[("direct image", image)]));
        let k = Interleaving { k: 4, seed: 2 };
        let before = r.readback_bytes().unwrap();
        let lists = r.cull(&p, strategy, 1e-3, k).unwrap();
        assert_eq!(read_since(&before, &r), labels(&[]), "{strategy} culling");
        let shaded = r
            .shade_lists(&loaded, &p, &lists, 1e-3, k, false, &|_| {})
            .unwrap();
        assert_eq!(
            read_since(&before, &r),
            labels(&[("cull status", 16)]),
            "{strategy} shading"
        );
        drop(shaded);
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
            frame.readback_bytes.unwrap(),
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
