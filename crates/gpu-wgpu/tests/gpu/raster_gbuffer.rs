//! The rasterized G-buffer (`GbufferPass`) against the ray-traced one
//! (`slc_cpu_ref::gbuffer::trace_gbuffer`) on the built-in default scene, the glTF
//! reference room, textured Sponza and the normal-mapped, alpha-masked `scenes/materials`.
//!
//! Edge pixels (defined in `raster_common`, measured on the CPU G-buffer) are where the
//! rasterizer may pick another triangle than the ray tracer; their fraction is bounded per
//! scene, and so is the fraction of all pixels that are edge pixels *and* differ (the
//! rasterizer's choice of triangle: a visibility view shifted by half a pixel raises it from
//! 0.14% to 2.0% on the default scene, from 0.01% to 4.9% on the reference room and from
//! 0.18% to 19% on Sponza). Outside edge pixels every pixel must agree: the same presence; position within
//! `POSITION_TOLERANCE` of the view depth (a pixel at these sizes spans 2e-3 to 1e-2 of it,
//! so half a pixel of shift fails); shading and geometric normals and ωo within
//! `DIRECTION_TOLERANCE`; view depth within the position tolerance; the same Fresnel model,
//! F0, η and α within 1e-6; kd within 1e-6 (untextured) or `TEXTURED_KD_TOLERANCE`
//! (bilinear texture lookups at texture coordinates that differ in the last bits).
use crate::common::gpu;
use crate::raster_common::{
    anisotropy, cornell_a, default_scene, edge_pixels, extent, fraction, materials, sponza,
};
use glam::Vec3;
use slc_bounds::Fresnel;
use slc_core::frame::LobeSelection;
use slc_core::frame::{Method, RenderSettings};
use slc_core::{Camera, CullInput, GBuffer, GSample, Interleaving, Mesh, Scene};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::prepare;
use slc_cpu_ref::Tracer;
use slc_gpu_wgpu::cull::frame::CullFrame;
use slc_gpu_wgpu::cull::lists::read_lists;
use slc_gpu_wgpu::cull::room::settled;
use slc_gpu_wgpu::cull::GpuCulling;
use slc_gpu_wgpu::cull::ListCulling;
use slc_gpu_wgpu::frame::raster::gbuffer::GbufferPass;
use slc_gpu_wgpu::frame::raster::scene::GpuScene;
use slc_gpu_wgpu::shade::lists::ShadePass;
use slc_gpu_wgpu::GpuError;

const POSITION_TOLERANCE: f32 = 1e-4;
const DIRECTION_TOLERANCE: f32 = 1e-4;
const PARAMETER_TOLERANCE: f32 = 1e-6;
const TEXTURED_KD_TOLERANCE: f32 = 4e-3;

/// How a GPU G-buffer compares with the CPU's.
struct Agreement {
    pixels: usize,
    edge_fraction: f64,
    /// Edge pixels where the two differ in presence or beyond the tolerances (reported).
    edge_mismatches: usize,
    /// Largest position error relative to the view depth, and largest direction error,
    /// over the non-edge pixels with a sample.
    worst_position: f32,
    worst_direction: f32,
    worst_kd: f32,
    failures: Vec<String>,
}

/// Why `gpu` differs from `cpu` (None: it agrees).
fn difference(cpu: &GSample, gpu: &GSample, kd_tolerance: f32) -> Option<String> {
    let position = (gpu.position - cpu.position).length() / cpu.depth;
    let direction = [
        (gpu.normal, cpu.normal),
        (gpu.geometric_normal, cpu.geometric_normal),
        (gpu.omega_o, cpu.omega_o),
    ]
    .iter()
    .map(|(a, b)| (*a - *b).length())
    .fold(0.0, f32::max);
    let kd = (gpu.brdf.kd - cpu.brdf.kd).abs().max_element();
    let fresnel = match (gpu.brdf.fresnel, cpu.brdf.fresnel) {
        (Fresnel::Schlick(a), Fresnel::Schlick(b)) => (a - b).abs().max_element(),
        (Fresnel::Dielectric(a), Fresnel::Dielectric(b)) => (a - b).abs(),
        _ => f32::INFINITY,
    };
    // The anisotropy: the tangent (within the direction tolerance) and α_t.
    let anisotropy = match (gpu.brdf.anisotropy, cpu.brdf.anisotropy) {
        (None, None) => 0.0,
        (Some(a), Some(b)) => ((a.tangent - b.tangent).length() / DIRECTION_TOLERANCE)
            .max((a.alpha_t - b.alpha_t).abs() / PARAMETER_TOLERANCE),
        _ => f32::INFINITY,
    };
    let ok = position <= POSITION_TOLERANCE
        && (gpu.depth - cpu.depth).abs() <= POSITION_TOLERANCE * cpu.depth
        && direction <= DIRECTION_TOLERANCE
        && kd <= kd_tolerance
        && fresnel <= PARAMETER_TOLERANCE
        && (gpu.brdf.alpha - cpu.brdf.alpha).abs() <= PARAMETER_TOLERANCE
        && anisotropy <= 1.0;
    (!ok).then(|| {
        format!(
            "position {position:.2e} of depth, direction {direction:.2e}, kd {kd:.2e}, \
             fresnel {fresnel:.2e}, alpha {} vs {}, anisotropy {anisotropy:.2e} of the tolerance",
            gpu.brdf.alpha, cpu.brdf.alpha
        )
    })
}

fn compare(cpu: &GBuffer, gpu: &GBuffer, extent: f32, kd_tolerance: f32) -> Agreement {
    assert_eq!((cpu.width, cpu.height), (gpu.width, gpu.height));
    let edges = edge_pixels(cpu, extent);
    let mut a = Agreement {
        pixels: edges.len(),
        edge_fraction: fraction(&edges),
        edge_mismatches: 0,
        worst_position: 0.0,
        worst_direction: 0.0,
        worst_kd: 0.0,
        failures: Vec::new(),
    };
    for (p, (c, g)) in cpu.samples.iter().zip(&gpu.samples).enumerate() {
        let why = match (c, g) {
            (None, None) => None,
            (Some(c), Some(g)) => {
                if !edges[p] {
                    a.worst_position = a
                        .worst_position
                        .max((g.position - c.position).length() / c.depth);
                    a.worst_direction = a
                        .worst_direction
                        .max((g.normal - c.normal).length())
                        .max((g.geometric_normal - c.geometric_normal).length())
                        .max((g.omega_o - c.omega_o).length());
                    a.worst_kd = a.worst_kd.max((g.brdf.kd - c.brdf.kd).abs().max_element());
                }
                difference(c, g, kd_tolerance)
            }
            (c, g) => Some(format!(
                "sample on the CPU: {}, on the GPU: {}",
                c.is_some(),
                g.is_some()
            )),
        };
        if let Some(why) = why {
            if edges[p] {
                a.edge_mismatches += 1;
            } else {
                a.failures.push(format!(
                    "pixel ({}, {}): {why}",
                    p as u32 % cpu.width,
                    p as u32 / cpu.width
                ));
            }
        }
    }
    a
}

/// Renders `scene` on both sides at pixel centres and checks the agreement, with `bounds`:
/// the largest fraction of edge pixels, and of pixels that are edge pixels and differ.
fn check_scene(
    name: &str,
    (scene, camera): (Scene, Camera),
    (w, h): (u32, u32),
    kd_tolerance: f32,
    (edges, edge_mismatches): (f64, f64),
) {
    let Some(ctx) = gpu() else { return };
    let ctx = &ctx;
    let tracer = Tracer::new(&scene);
    let cpu = trace_gbuffer(&scene, &tracer, &camera, w, h, PixelSample::Centre);
    let gpu_scene = GpuScene::upload(ctx, &scene).unwrap();
    let gpu = GbufferPass::new(ctx)
        .unwrap()
        .render(ctx, &gpu_scene, &camera, w, h, (0.5, 0.5))
        .unwrap()
        .read_back(ctx)
        .unwrap();
    report(
        name,
        &compare(&cpu, &gpu, extent(&scene), kd_tolerance),
        Bounds {
            edges,
            edge_mismatches,
        },
    );
}

/// Per scene: the largest fraction of edge pixels, and of pixels that are edge pixels and
/// differ.
#[derive(Clone, Copy)]
struct Bounds {
    edges: f64,
    edge_mismatches: f64,
}

fn report(name: &str, a: &Agreement, bounds: Bounds) {
    eprintln!(
        "{name}: edge pixels {:.2}% ({} of {} pixels differ), worst position {:.2e} of depth, direction \
         {:.2e}, kd {:.2e}; {} failures",
        100.0 * a.edge_fraction,
        a.edge_mismatches,
        a.pixels,
        a.worst_position,
        a.worst_direction,
        a.worst_kd,
        a.failures.len()
    );
    assert!(
        a.failures.is_empty(),
        "{name}: {} non-edge pixels differ, first: {:?}",
        a.failures.len(),
        &a.failures[..a.failures.len().min(8)]
    );
    assert!(
        a.edge_fraction <= bounds.edges,
        "{name}: {:.2}% edge pixels exceed {:.2}%",
        100.0 * a.edge_fraction,
        100.0 * bounds.edges
    );
    let mismatches = a.edge_mismatches as f64 / a.pixels as f64;
    assert!(
        mismatches <= bounds.edge_mismatches,
        "{name}: {:.3}% of the pixels are edge pixels that differ, more than {:.3}%",
        100.0 * mismatches,
        100.0 * bounds.edge_mismatches
    );
}

#[test]
fn raster_gbuffer_matches_the_traced_one_on_the_default_scene() {
    check_scene(
        "default",
        default_scene(),
        (160, 120),
        PARAMETER_TOLERANCE,
        (0.15, 5e-3),
    );
}

#[test]
fn raster_gbuffer_matches_the_traced_one_on_the_gltf_reference_room() {
    check_scene(
        "cornell-a",
        cornell_a(),
        (128, 128),
        PARAMETER_TOLERANCE,
        (0.2, 5e-3),
    );
}

#[test]
fn raster_gbuffer_matches_the_traced_one_on_textured_sponza() {
    check_scene(
        "sponza",
        sponza(),
        (160, 100),
        TEXTURED_KD_TOLERANCE,
        (0.6, 1e-2),
    );
}

/// Normal maps (the shading normals agree within `DIRECTION_TOLERANCE`), cut-outs (the
/// pixels seen through the sheet's holes agree) and the back of the double-sided sheet.
#[test]
fn raster_gbuffer_matches_the_traced_one_on_the_materials_scene() {
    check_scene(
        "materials",
        materials(),
        (128, 128),
        TEXTURED_KD_TOLERANCE,
        (0.25, 1e-2),
    );
}

/// Anisotropic lobes (`KHR_materials_anisotropy`): the tangent frames (generated on the floor,
/// stored on the panel), the rotation and α_t agree; the sample's tangent travels as an angle
/// (`GpuSample`).
#[test]
fn raster_gbuffer_matches_the_traced_one_on_the_anisotropy_scene() {
    check_scene(
        "anisotropy",
        anisotropy(),
        (128, 128),
        TEXTURED_KD_TOLERANCE,
        (0.25, 1e-2),
    );
}

/// `trace_gbuffer` with every ray at sub-pixel offset (s, t) (the CPU's jitter draws one per
/// pixel; the rasterizer takes one per frame).
fn trace_at_offset(
    scene: &Scene,
    camera: &Camera,
    (w, h): (u32, u32),
    (s, t): (f32, f32),
) -> GBuffer {
    let tracer = Tracer::new(scene);
    let samples = (0..w * h)
        .map(|pixel| {
            let dir = camera.ray_direction(pixel % w, pixel / w, s, t, w, h);
            let hit = tracer.intersect(scene, camera.position, dir, f32::INFINITY)?;
            hit.front.then(|| GSample {
                position: hit.position,
                normal: hit.shading_normal,
                geometric_normal: hit.geometric_normal,
                omega_o: -dir,
                depth: camera.view_depth(hit.position),
                brdf: hit.brdf,
            })
        })
        .collect();
    GBuffer {
        width: w,
        height: h,
        samples,
    }
}

#[test]
fn raster_gbuffer_follows_a_sub_pixel_offset() {
    let Some(ctx) = gpu() else { return };
    let (scene, camera) = default_scene();
    let size = (120, 90);
    let offset = (0.15, 0.8);
    let cpu = trace_at_offset(&scene, &camera, size, offset);
    let gpu_scene = GpuScene::upload(&ctx, &scene).unwrap();
    let gpu = GbufferPass::new(&ctx)
        .unwrap()
        .render(&ctx, &gpu_scene, &camera, size.0, size.1, offset)
        .unwrap()
        .read_back(&ctx)
        .unwrap();
    let agreement = compare(&cpu, &gpu, extent(&scene), PARAMETER_TOLERANCE);
    let bounds = Bounds {
        edges: 0.15,
        edge_mismatches: 5e-3,
    };
    report("default, offset (0.15, 0.8)", &agreement, bounds);
}

/// Culling and shading read the G-buffer where the rasterizer left it: the same lists and
/// image, bit for bit, as from the read-back G-buffer uploaded again.
#[test]
fn culling_and_shading_read_the_gpu_gbuffer_in_place() {
    let Some(ctx) = gpu() else { return };
    let (scene, camera) = default_scene();
    let (w, h) = (96, 72);
    let settings = RenderSettings {
        width: w,
        height: h,
        rsm_resolution: 16,
        seed: 5,
        method: Method::VplReference,
        visibility: false,
        spp: 1,
        lobes: LobeSelection::Both,
    };
    let vpls = std::mem::take(&mut prepare(&scene, &settings, Tracer::new(&scene), None).vpls);
    let gpu_scene = GpuScene::upload(&ctx, &scene).unwrap();
    let gbuffer = GbufferPass::new(&ctx)
        .unwrap()
        .render(&ctx, &gpu_scene, &camera, w, h, (0.5, 0.5))
        .unwrap();
    let read = gbuffer.read_back(&ctx).unwrap();
    let interleaving = Interleaving { k: 2, seed: 9 };
    let delta = 1e-3;
    let culler = GpuCulling::new(&ctx).unwrap();
    let shader = ShadePass::new(&ctx).unwrap();
    let input = CullInput {
        gbuffer: &read,
        camera: &camera,
        vpls: &vpls,
        delta,
        interleaving,
    };
    // Every strategy: the tiled, clustered, binned and unculled passes all read positions.
    // Settled (culled again where they outgrew their room: binned's per-pixel lists do here).
    for strategy in slc_core::Strategy::ALL {
        let name = strategy.name();
        let frame = CullFrame::upload(&ctx, &input).unwrap();
        let uploaded = settled(&ctx, || culler.cull_frame(&ctx, &frame, strategy)).unwrap();
        let want = shader.shade_read_back(&ctx, &input, &uploaded).unwrap();
        let on_gpu = CullFrame::on_gpu(&gbuffer, &vpls, delta, interleaving);
        let lists = settled(&ctx, || culler.cull_frame(&ctx, &on_gpu, strategy)).unwrap();
        assert_eq!(lists.entries, uploaded.entries, "{name}");
        assert_eq!(
            read_lists(&ctx, &lists).unwrap(),
            read_lists(&ctx, &uploaded).unwrap(),
            "{name}"
        );
        let got = crate::common::shade_gpu_gbuffer(
            &ctx,
            &shader,
            &gbuffer,
            &vpls,
            delta,
            interleaving,
            &lists,
        )
        .unwrap();
        assert!(want.mean().max_element() > 0.0, "{name}");
        assert_eq!(got, want, "{name}");
    }
}

#[test]
fn bad_scenes_and_frames_are_errors() {
    let Some(ctx) = gpu() else { return };
    let (scene, camera) = default_scene();
    let mut broken = scene.clone();
    broken.meshes[0].triangles.push([0, 1, 999]);
    assert!(matches!(
        GpuScene::upload(&ctx, &broken),
        Err(GpuError::Input(_))
    ));
    let mut nan = scene.clone();
    nan.meshes[0].positions[0] = Vec3::NAN;
    assert!(matches!(
        GpuScene::upload(&ctx, &nan),
        Err(GpuError::Input(_))
    ));
    let mut no_material = scene.clone();
    no_material.meshes[0].material = 99;
    assert!(matches!(
        GpuScene::upload(&ctx, &no_material),
        Err(GpuError::Input(_))
    ));
    let mut empty = scene.clone();
    empty.meshes = vec![Mesh::default()];
    assert!(matches!(
        GpuScene::upload(&ctx, &empty),
        Err(GpuError::Input(_))
    ));
    let gpu_scene = GpuScene::upload(&ctx, &scene).unwrap();
    let pass = GbufferPass::new(&ctx).unwrap();
    for (w, h, offset) in [
        (0, 8, (0.5, 0.5)),
        (8, 8, (1.0, 0.5)),
        (8, 8, (0.5, f32::NAN)),
    ] {
        let r = pass.render(&ctx, &gpu_scene, &camera, w, h, offset);
        assert!(matches!(r, Err(GpuError::Input(_))), "{w}x{h} {offset:?}");
    }
    let mut bad_camera = camera.clone();
    bad_camera.yfov = 0.0;
    let r = pass.render(&ctx, &gpu_scene, &bad_camera, 8, 8, (0.5, 0.5));
    assert!(matches!(r, Err(GpuError::Input(_))));
    let max = ctx.limits.max_texture_dimension_2d;
    let r = pass.render(&ctx, &gpu_scene, &camera, max + 1, 8, (0.5, 0.5));
    assert!(matches!(r, Err(GpuError::Input(_))));
}
