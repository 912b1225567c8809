//! The one-pass tiled culling and shading (`shade::tiled`) against the tiled culler's
//! lists shaded by `shade::lists`: the same image, pixel for pixel (bit for bit where the
//! device does not fuse operations differently in the two kernels), for every tiled strategy,
//! several K and the edge cases (VPLs that reach nothing, no VPL); and the renderer's two
//! paths (`GpuRenderer::with_one_pass`).
use crate::common::{cull_input, gpu, small_frame};
use crate::tiled::frame;
use slc_core::render::render;
use slc_core::{builtin, CullInput, GlossyBound, Interleaving, Renderer, Strategy, Vpl};
use slc_gpu_wgpu::cull::frame::CullFrame;
use slc_gpu_wgpu::cull::list_passes::TileLayout;
use slc_gpu_wgpu::cull::tiled::TiledCuller;
use slc_gpu_wgpu::cull::ListCulling;
use slc_gpu_wgpu::device::buffers::upload;
use slc_gpu_wgpu::frame::raster::records::GpuSample;
use slc_gpu_wgpu::shade::lists::{read_image, ShadePass};
use slc_gpu_wgpu::shade::tiled::TiledShadePass;
use slc_gpu_wgpu::{GpuContext, GpuRenderer};

/// Largest relative difference [`same_sums`] allows between two kernels' sums of the same
/// terms in the same order: a GPU compiler may fuse a multiply and an add in one kernel and
/// not in the other (WGSL allows it), about an ulp per operation; a VPL left out of a sum
/// moves its pixel by the whole term.
const FUSED: f32 = 1e-5;

/// Two images that sum the same VPLs in the same order: bit for bit where the device rounds
/// every operation as written (lavapipe, CI), else within [`FUSED`] of the pixel's value
/// (with a floor of 1e-3 of the image's largest mean channel, as `shade.rs`).
fn same_sums(got: &[glam::Vec3], want: &[glam::Vec3], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    if got == want {
        return;
    }
    let mean = want.iter().fold(glam::Vec3::ZERO, |a, b| a + *b) / want.len().max(1) as f32;
    let floor = 1e-3 * mean.max_element();
    let (mut differing, mut worst, mut worst_pixel) = (0, 0.0f32, 0);
    for (p, (a, b)) in got.iter().zip(want).enumerate() {
        if a == b {
            continue;
        }
        differing += 1;
        let rel = (*a - *b).abs().max_element() / b.abs().max_element().max(floor).max(1e-30);
        if rel > worst {
            (worst, worst_pixel) = (rel, p);
        }
    }
    eprintln!(
        "{what}: {differing} of {} pixels differ in their last bits, largest relative \
         difference {worst:.2e} (pixel {worst_pixel}: {} against {})",
        want.len(),
        got[worst_pixel],
        want[worst_pixel]
    );
    assert!(
        worst <= FUSED,
        "{what}: pixel {worst_pixel} differs by {worst:.2e}"
    );
}

/// The one-pass image of `input` with `glossy` bounds, and the image of its lists; where the
/// device has subgroup operations, the kernel with them and the kernel without must give the
/// same image.
fn both(
    ctx: &GpuContext,
    input: &CullInput,
    glossy: GlossyBound,
) -> (slc_core::Image, slc_core::Image) {
    let culler = TiledCuller::new(ctx).unwrap();
    let frame = CullFrame::upload(ctx, input).unwrap();
    let samples: Vec<GpuSample> = input
        .gbuffer
        .samples
        .iter()
        .map(|s| GpuSample::new(s.as_ref()))
        .collect();
    let samples = upload(ctx, "samples", &samples).unwrap();
    let tiles = culler.prepare(ctx, &frame, glossy, false).unwrap().unwrap();
    let kernels = if ctx.subgroups {
        vec![true, false]
    } else {
        vec![false]
    };
    let images: Vec<_> = kernels
        .into_iter()
        .map(|subgroups| {
            let pass = TiledShadePass::with_subgroups(ctx, subgroups);
            let one = pass.shade(ctx, &frame, &samples, &tiles).unwrap();
            read_image(ctx, &one, frame.width, frame.height).unwrap()
        })
        .collect();
    for other in &images[1..] {
        same_sums(
            &other.pixels,
            &images[0].pixels,
            "with and without subgroups",
        );
    }
    let one = images[0].clone();
    let lists = culler.cull_frame(ctx, &frame, glossy).unwrap();
    let shader = ShadePass::new(ctx).unwrap();
    let want = shader.shade_read_back(ctx, input, &lists).unwrap();
    (one, want)
}

#[test]
fn one_pass_shades_exactly_the_lists() {
    let Some(ctx) = gpu() else { return };
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (72, 50), 16);
    for k in [1, 3, 8] {
        for glossy in [
            GlossyBound::Sphere,
            GlossyBound::EnclosingSphere,
            GlossyBound::Ellipsoid,
        ] {
            let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (k, 6));
            let (one, want) = both(&ctx, &input, glossy);
            let lit = want.pixels.iter().filter(|p| p.max_element() > 0.0).count();
            assert!(lit * 2 > want.pixels.len(), "{glossy:?} K {k}: {lit} lit");
            same_sums(&one.pixels, &want.pixels, &format!("{glossy:?} K {k}"));
        }
    }
}

/// The pixel test of the one-pass kernel (a pixel skips a VPL whose bound its point lies
/// outside) never skips a contributing pair: the same image as the lists at the extremes of
/// the bounds' shapes and sizes and of f32 rounding. Sharp and rough lobes (α 1e-3 and 1,
/// needle-like spheroids and spheres), ranges far below a pixel's footprint and far above the
/// frame (δ 1e-9 to 1e3), ξ near 0 and 1, and the whole frame moved 3e4 from the origin (the
/// view points' rounding then grows with their distance from the origin, not from the eye).
#[test]
fn one_pass_pixel_test_keeps_every_contributing_pair_at_the_extremes() {
    let Some(ctx) = gpu() else { return };
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (64, 40), 16);
    let with = |f: &dyn Fn(&mut Vpl)| -> Vec<Vpl> {
        vpls.iter()
            .map(|v| {
                let mut v = *v;
                f(&mut v);
                v
            })
            .collect()
    };
    let far = glam::Vec3::new(3e4, -2e4, 1.5e4);
    let moved_gbuffer = slc_core::GBuffer {
        samples: gbuffer
            .samples
            .iter()
            .map(|s| {
                s.map(|s| slc_core::GSample {
                    position: s.position + far,
                    ..s
                })
            })
            .collect(),
        ..gbuffer.clone()
    };
    let moved_camera = slc_core::Camera {
        position: camera.position + far,
        ..camera.clone()
    };
    let cases: Vec<(&str, Vec<Vpl>, f32, bool)> = vec![
        ("alpha 1e-3", with(&|v| v.brdf.alpha = 1e-3), 1e-3, false),
        ("alpha 1", with(&|v| v.brdf.alpha = 1.0), 1e-3, false),
        ("delta 1e-9", vpls.clone(), 1e-9, false),
        ("delta 1e3", vpls.clone(), 1e3, false),
        ("xi near 0", with(&|v| v.xi = 1e-7), 1e-2, false),
        ("xi near 1", with(&|v| v.xi = 1.0 - 1e-7), 1e-4, false),
        ("moved 3e4", vpls.clone(), 1e-3, true),
        (
            "moved 3e4, alpha 1e-3",
            with(&|v| v.brdf.alpha = 1e-3),
            1e-4,
            true,
        ),
    ];
    let mut lit_cases = 0;
    for (name, case_vpls, delta, moved) in &cases {
        let moved_vpls: Vec<Vpl> = case_vpls
            .iter()
            .map(|v| Vpl {
                position: v.position + far,
                ..*v
            })
            .collect();
        let input = CullInput {
            gbuffer: if *moved { &moved_gbuffer } else { &gbuffer },
            camera: if *moved { &moved_camera } else { &camera },
            vpls: if *moved { &moved_vpls } else { case_vpls },
            delta: *delta,
            interleaving: Interleaving { k: 2, seed: 9 },
        };
        for glossy in [
            GlossyBound::Sphere,
            GlossyBound::EnclosingSphere,
            GlossyBound::Ellipsoid,
        ] {
            let (one, want) = both(&ctx, &input, glossy);
            same_sums(&one.pixels, &want.pixels, &format!("{name}, {glossy:?}"));
            if want.pixels.iter().any(|p| p.max_element() > 0.0) {
                lit_cases += 1;
            }
        }
    }
    // Every case but the tiny ranges of δ 1e3 lights something.
    assert!(lit_cases >= 3 * (cases.len() - 1), "{lit_cases} lit");
}

/// VPLs whose bounds reach no tile (flux zero, or far behind the camera) shade nothing; no
/// VPL at all, the same.
#[test]
fn one_pass_without_reachable_vpls_is_black() {
    let Some(ctx) = gpu() else { return };
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (40, 30), 4);
    let dark: Vec<Vpl> = vpls
        .iter()
        .map(|v| Vpl {
            flux: glam::Vec3::ZERO,
            ..*v
        })
        .collect();
    for vpls in [&dark[..], &[]] {
        let input = CullInput {
            gbuffer: &gbuffer,
            camera: &camera,
            vpls,
            delta: 1e-3,
            interleaving: Interleaving { k: 2, seed: 1 },
        };
        let (one, want) = both(&ctx, &input, GlossyBound::Ellipsoid);
        assert!(one.pixels.iter().all(|p| *p == glam::Vec3::ZERO));
        same_sums(&one.pixels, &want.pixels, "no reachable VPL");
    }
}

/// The renderer's two paths for the tiled strategies, one pass and lists, render the same
/// frame; with metrics both measure the same lists.
#[test]
fn renderer_one_pass_and_lists_render_the_same_frame() {
    let Some(ctx) = gpu() else { return };
    let one_pass = GpuRenderer::from_context(ctx).unwrap();
    let Some(ctx) = gpu() else { return };
    let lists = GpuRenderer::from_context(ctx).unwrap().with_one_pass(false);
    let scene = builtin("default").unwrap();
    for strategy in [Strategy::Sphere, Strategy::Ellipsoid] {
        let settings = small_frame(strategy, true);
        let a = render(&one_pass, &scene, &settings, &|_| {}).unwrap();
        let b = render(&lists, &scene, &settings, &|_| {}).unwrap();
        same_sums(
            &a.indirect.pixels,
            &b.indirect.pixels,
            &format!("{strategy:?}"),
        );
        assert_eq!(a.metrics, b.metrics, "{strategy:?}");
        assert_eq!(a.metrics.unwrap().missed_pairs, 0);
        let one_pass_note = |r: &GpuRenderer| {
            r.info(&settings)
                .notes
                .iter()
                .any(|n| n.contains("tiled_shade"))
        };
        assert!(
            one_pass_note(&one_pass) && !one_pass_note(&lists),
            "{strategy:?}"
        );
    }
}
