//! Rasterized RSMs (`RsmPass`) and GPU VPL generation (`VplGenPass`) against
//! `slc_cpu_ref::rsm::trace_rsm(…, TexelSample::Centre)` and `generate_vpls`, for a spot
//! light (one face), a point light (six faces), a directional light (orthographic) and a
//! spot wider than 80° (six faces); and for the point light of `scenes/materials` (normal
//! maps, cut-outs, a double-sided sheet).
//!
//! Edge texels are the edge pixels of `raster_common` on each face's texel grid (presence,
//! normal, plane or material changing in the 3 x 3 neighbourhood; a spot's cone boundary is
//! a presence change). Their fraction is bounded (`MAX_EDGE_FRACTION`). Outside them every
//! texel must agree: presence; position within `POSITION_TOLERANCE` of its distance along
//! the ray; normal and ωi within `DIRECTION_TOLERANCE`; flux within `FLUX_TOLERANCE`
//! relative plus `FLUX_FLOOR` of the map's largest texel flux (the GPU integrates the
//! texel's solid angle by quadrature in f32, the CPU in closed form in f64; near a spot's
//! outer cone the falloff's slope, 1 / (cos inner − cos outer) ≈ 100 here, turns rounding of
//! the ray's cosine into 2e-4 relative of a dim texel's flux); BRDF within 1e-6. VPLs: every id on one side only is an edge
//! texel's; ids on both sides have bit-identical ξ and the same lobe, and outside edge
//! texels agree as their texels do; total flux per channel within `TOTAL_FLUX_TOLERANCE`.
use crate::common::gpu;
use crate::raster_common::{
    anisotropy, default_scene, edge_pixels, extent, fraction, lit_scene, materials,
};
use glam::Vec3;
use slc_bounds::Fresnel;
use slc_core::frame::LobeSelection;
use slc_core::{GBuffer, GSample, Light, Scene, Vpl};
use slc_cpu_ref::rsm::{trace_rsm, Rsm, TexelSample};
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::Tracer;
use slc_gpu_wgpu::frame::light::records::GpuRsmTexel;
use slc_gpu_wgpu::frame::light::rsm::RsmPass;
use slc_gpu_wgpu::frame::raster::scene::GpuScene;
use slc_gpu_wgpu::vpl::generate::{VplGenPass, VplLobes};
use slc_gpu_wgpu::vpl::records::{anisotropy_from_gpu, GpuVpl};
use slc_gpu_wgpu::{GpuContext, GpuError};
use std::collections::HashMap;

const POSITION_TOLERANCE: f32 = 1e-4;
const DIRECTION_TOLERANCE: f32 = 1e-4;
const FLUX_TOLERANCE: f32 = 1e-4;
const FLUX_FLOOR: f32 = 1e-5;
const TOTAL_FLUX_TOLERANCE: f32 = 2e-3;
const MAX_EDGE_FRACTION: f64 = 0.3;
const RESOLUTION: u32 = 32;
const SEED: u32 = 11;

/// A texel as a G-buffer sample, so that `edge_pixels` classifies texels (ωi as ωo, the
/// distance from the ray origin unused).
fn as_sample(t: &slc_cpu_ref::rsm::RsmTexel) -> GSample {
    GSample {
        position: t.position,
        normal: t.normal,
        geometric_normal: t.geometric_normal,
        omega_o: t.omega_i,
        depth: 1.0,
        brdf: t.brdf,
    }
}

/// Edge flags of every texel of `rsm` (per face).
fn edge_texels(rsm: &Rsm, extent: f32) -> Vec<bool> {
    let n = rsm.resolution;
    rsm.texels
        .chunks((n * n) as usize)
        .flat_map(|face| {
            let g = GBuffer {
                width: n,
                height: n,
                samples: face.iter().map(|t| t.as_ref().map(as_sample)).collect(),
            };
            edge_pixels(&g, extent)
        })
        .collect()
}

/// `|gpu − cpu| / (FLUX_TOLERANCE |cpu| + FLUX_FLOOR max flux)`, largest channel: at most
/// 1 where they agree.
fn flux_error(gpu: Vec3, cpu: Vec3, flux_floor: f32) -> f32 {
    ((gpu - cpu).abs() / (FLUX_TOLERANCE * cpu.abs() + Vec3::splat(flux_floor))).max_element()
}

/// The flux floor of a map: `FLUX_FLOOR` times its largest texel flux.
fn flux_floor(rsm: &Rsm) -> f32 {
    FLUX_FLOOR
        * rsm
            .texels
            .iter()
            .flatten()
            .map(|t| t.flux.max_element())
            .fold(0.0, f32::max)
}

/// Why GPU texel `g` differs from CPU texel `c` (None: it agrees). `origin` is the ray
/// origin's distance scale (the light or the orthographic plane).
fn texel_difference(
    c: &slc_cpu_ref::rsm::RsmTexel,
    g: &GpuRsmTexel,
    scale: f32,
    flux_floor: f32,
) -> Option<String> {
    let v = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
    let position = (v(g.position) - c.position).length() / scale;
    let direction = (v(g.normal_alpha) - c.normal)
        .length()
        .max((v(g.omega_i_eta) - c.omega_i).length());
    let flux = flux_error(Vec3::from(g.flux), c.flux, flux_floor);
    let (f0, eta) = match c.brdf.fresnel {
        Fresnel::Schlick(f0) => (f0, 0.0),
        Fresnel::Dielectric(eta) => (Vec3::ZERO, eta),
    };
    let brdf = (v(g.kd) - c.brdf.kd)
        .abs()
        .max((v(g.f0) - f0).abs())
        .max_element()
        .max((g.normal_alpha[3] - c.brdf.alpha).abs())
        .max((g.omega_i_eta[3] - eta).abs())
        .max(
            match (anisotropy_from_gpu(g.anisotropy), c.brdf.anisotropy) {
                (None, None) => 0.0,
                (Some(a), Some(b)) => (a.alpha_t - b.alpha_t).abs(),
                _ => f32::INFINITY,
            },
        );
    let tangent = match (anisotropy_from_gpu(g.anisotropy), c.brdf.anisotropy) {
        (Some(a), Some(b)) => (a.tangent - b.tangent).length(),
        _ => 0.0,
    };
    let direction = direction.max(tangent);
    let ok = position <= POSITION_TOLERANCE
        && direction <= DIRECTION_TOLERANCE
        && flux <= 1.0
        && brdf <= 1e-6;
    (!ok).then(|| {
        format!(
            "position {position:.2e}, direction {direction:.2e}, flux {flux:.2e} of the \
             tolerance, brdf {brdf:.2e}"
        )
    })
}

#[test]
fn raster_rsm_and_gpu_vpls_match_the_cpu() {
    let Some(ctx) = gpu() else { return };
    rsm_and_vpls_match(&ctx, &lit_scene());
}

/// The sheet's holes let the light through, its back (lit) reflects, and the floor's VPLs
/// carry normal-mapped normals.
#[test]
fn raster_rsm_and_gpu_vpls_match_the_cpu_on_the_materials_scene() {
    let Some(ctx) = gpu() else { return };
    rsm_and_vpls_match(&ctx, &materials().0);
}

/// The floor's and the panel's VPLs carry anisotropic lobes (tangent and α_t).
#[test]
fn raster_rsm_and_gpu_vpls_match_the_cpu_on_the_anisotropy_scene() {
    let Some(ctx) = gpu() else { return };
    rsm_and_vpls_match(&ctx, &anisotropy().0);
}

/// Each light's RSM and the VPLs of all of them, GPU against CPU (module documentation).
fn rsm_and_vpls_match(ctx: &GpuContext, scene: &Scene) {
    let extent = extent(scene);
    let tracer = Tracer::new(scene);
    let gpu_scene = GpuScene::upload(ctx, scene).unwrap();
    let pass = RsmPass::new(ctx).unwrap();
    let mut cpu_maps = Vec::new();
    let mut gpu_maps = Vec::new();
    // Per global texel: whether it is an edge texel.
    let mut edges = Vec::new();
    // Per global texel: the flux floor of its map.
    let mut floors = Vec::new();
    for (l, light) in scene.lights.iter().enumerate() {
        let cpu = trace_rsm(scene, &tracer, light, RESOLUTION, TexelSample::Centre);
        let gpu = pass.render(ctx, &gpu_scene, light, RESOLUTION).unwrap();
        let texels = gpu.read_texels(ctx).unwrap();
        assert_eq!(texels.len(), cpu.texels.len(), "light {l}");
        let light_edges = edge_texels(&cpu, extent);
        let floor = flux_floor(&cpu);
        let (mut failures, mut edge_mismatches, mut worst_flux) = (Vec::new(), 0, 0.0f32);
        let scale = match light {
            Light::Directional { .. } => extent,
            _ => 1.0,
        };
        for (k, (c, g)) in cpu.texels.iter().zip(&texels).enumerate() {
            let why = match (c, g.position[3] != 0.0) {
                (None, false) => None,
                (Some(c), true) => {
                    let distance = match light {
                        Light::Point { position, .. } | Light::Spot { position, .. } => {
                            (c.position - *position).length()
                        }
                        Light::Directional { .. } => scale,
                    };
                    if !light_edges[k] {
                        let f = Vec3::from_slice(&g.flux[..3]);
                        worst_flux = worst_flux.max(
                            ((f - c.flux).abs() / c.flux.max(Vec3::splat(1e-30))).max_element(),
                        );
                    }
                    texel_difference(c, g, distance, floor)
                }
                (c, g) => Some(format!(
                    "texel on the CPU: {}, on the GPU: {g}",
                    c.is_some()
                )),
            };
            if let Some(why) = why {
                if light_edges[k] {
                    edge_mismatches += 1;
                } else {
                    failures.push(format!("light {l} texel {k}: {why}"));
                }
            }
        }
        let lit = cpu.texels.iter().filter(|t| t.is_some()).count();
        eprintln!(
            "light {l} ({} faces): {lit} lit texels, edge texels {:.2}% ({edge_mismatches} \
             differ), worst flux {worst_flux:.2e} relative; {} failures",
            cpu.faces,
            100.0 * fraction(&light_edges),
            failures.len()
        );
        assert!(
            failures.is_empty(),
            "{:?}",
            &failures[..failures.len().min(8)]
        );
        assert!(fraction(&light_edges) <= MAX_EDGE_FRACTION, "light {l}");
        assert!(lit > 0, "light {l} lights nothing");
        edges.extend(light_edges);
        floors.extend(std::iter::repeat_n(floor, cpu.texels.len()));
        cpu_maps.push(cpu);
        gpu_maps.push(gpu);
    }
    let cpu_vpls = generate_vpls(&cpu_maps, SEED, LobeSelection::Both);
    let gpu_vpls = VplGenPass::new(ctx)
        .unwrap()
        .generate(ctx, &gpu_maps, SEED, VplLobes::Both)
        .unwrap()
        .read_back(ctx)
        .unwrap();
    compare_vpls(&cpu_vpls, &gpu_vpls, &edges, &floors);
}

/// The VPL checks of the module documentation.
fn compare_vpls(cpu: &[Vpl], gpu: &[Vpl], edges: &[bool], floors: &[f32]) {
    let texel = |v: &Vpl| (v.id / 2) as usize;
    let by_id: HashMap<u32, &Vpl> = gpu.iter().map(|v| (v.id, v)).collect();
    let cpu_ids: HashMap<u32, &Vpl> = cpu.iter().map(|v| (v.id, v)).collect();
    let mut one_sided = 0;
    for v in cpu.iter().filter(|v| !by_id.contains_key(&v.id)) {
        assert!(
            edges[texel(v)],
            "VPL {} only on the CPU, not at an edge texel",
            v.id
        );
        one_sided += 1;
    }
    for v in gpu.iter().filter(|v| !cpu_ids.contains_key(&v.id)) {
        assert!(
            edges[texel(v)],
            "VPL {} only on the GPU, not at an edge texel",
            v.id
        );
        one_sided += 1;
    }
    let mut compared = 0;
    for c in cpu {
        let Some(g) = by_id.get(&c.id) else { continue };
        assert_eq!(c.xi.to_bits(), g.xi.to_bits(), "xi of VPL {}", c.id);
        assert_eq!(c.lobe, g.lobe, "lobe of VPL {}", c.id);
        if edges[texel(c)] {
            continue;
        }
        compared += 1;
        let flux = flux_error(g.flux, c.flux, floors[texel(c)]);
        assert!(flux <= 1.0, "VPL {}: flux {} vs {}", c.id, g.flux, c.flux);
        assert!(
            (g.normal - c.normal).length() <= DIRECTION_TOLERANCE
                && (g.geometric_normal - c.geometric_normal).length() <= DIRECTION_TOLERANCE,
            "VPL {}",
            c.id
        );
        assert!(
            (g.omega_i - c.omega_i).length() <= DIRECTION_TOLERANCE,
            "VPL {}",
            c.id
        );
        let same_anisotropy = match (g.brdf.anisotropy, c.brdf.anisotropy) {
            (None, None) => true,
            (Some(a), Some(b)) => {
                (a.tangent - b.tangent).length() <= DIRECTION_TOLERANCE
                    && (a.alpha_t - b.alpha_t).abs() <= 1e-6
            }
            _ => false,
        };
        assert!(same_anisotropy, "VPL {}: anisotropy", c.id);
        assert!(
            (g.position - c.position).length()
                <= POSITION_TOLERANCE * c.position.length().max(1.0) * 10.0,
            "VPL {}: position {} vs {}",
            c.id,
            g.position,
            c.position
        );
    }
    // The GPU keeps the CPU's order (texel-major, diffuse first).
    let order = |vs: &[Vpl]| vs.windows(2).all(|w| w[0].id < w[1].id);
    assert!(order(cpu) && order(gpu));
    let total = |vs: &[Vpl]| vs.iter().fold(Vec3::ZERO, |s, v| s + v.flux);
    let (tc, tg) = (total(cpu), total(gpu));
    let relative = ((tg - tc).abs() / tc).max_element();
    eprintln!(
        "VPLs: CPU {}, GPU {}, {one_sided} on one side only (edge texels), {compared} compared \
         outside edges; total flux {tg} vs {tc} ({relative:.2e} relative)",
        cpu.len(),
        gpu.len()
    );
    assert!(relative <= TOTAL_FLUX_TOLERANCE, "total flux {tg} vs {tc}");
    assert!(compared > cpu.len() / 2);
}

#[test]
fn vpl_lobe_selection_follows_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let (scene, _) = default_scene();
    let gpu_scene = GpuScene::upload(&ctx, &scene).unwrap();
    let pass = RsmPass::new(&ctx).unwrap();
    let maps: Vec<_> = scene
        .lights
        .iter()
        .map(|l| pass.render(&ctx, &gpu_scene, l, 8).unwrap())
        .collect();
    let generator = VplGenPass::new(&ctx).unwrap();
    let all = generator
        .generate(&ctx, &maps, 3, VplLobes::Both)
        .unwrap()
        .read_back(&ctx)
        .unwrap();
    for (lobes, parity) in [(VplLobes::Diffuse, 0), (VplLobes::Glossy, 1)] {
        let some = generator
            .generate(&ctx, &maps, 3, lobes)
            .unwrap()
            .read_back(&ctx)
            .unwrap();
        let want: Vec<_> = all.iter().filter(|v| v.id % 2 == parity).copied().collect();
        assert!(!want.is_empty());
        assert_eq!(some, want, "{lobes:?}");
    }
}

#[test]
fn invalid_lights_and_resolutions_are_errors() {
    let Some(ctx) = gpu() else { return };
    let (scene, _) = default_scene();
    let gpu_scene = GpuScene::upload(&ctx, &scene).unwrap();
    let pass = RsmPass::new(&ctx).unwrap();
    let light = scene.lights[1].clone();
    for n in [0, 4097] {
        let r = pass.render(&ctx, &gpu_scene, &light, n);
        assert!(matches!(r, Err(GpuError::Input(_))), "{n}");
    }
    let bad = Light::Point {
        position: Vec3::new(f32::NAN, 0.0, 0.0),
        intensity: Vec3::ONE,
    };
    assert!(matches!(
        pass.render(&ctx, &gpu_scene, &bad, 8),
        Err(GpuError::Input(_))
    ));
    // Six faces of 4096² texels of 112 bytes are beyond the storage-binding limit.
    let r = pass.render(&ctx, &gpu_scene, &light, 4096);
    assert!(
        matches!(r, Err(GpuError::BufferTooLarge { .. })),
        "{:?}",
        r.err()
    );
}

/// The bound factor the GPU forms for its own VPLs (`vpl_bound_factor` in vpl/gvpl.wesl, in
/// f32) is never below the CPU's (`GpuVpl::new`, f64) and at most 3e-4 above it, on the
/// normal-mapped materials scene and the anisotropy scene, where it is not 1.
#[test]
fn gpu_vpl_bound_factors_cover_the_cpus() {
    let Some(ctx) = gpu() else { return };
    for (name, (scene, _)) in [("materials", materials()), ("anisotropy", anisotropy())] {
        let gpu_scene = GpuScene::upload(&ctx, &scene).unwrap();
        let pass = RsmPass::new(&ctx).unwrap();
        let maps: Vec<_> = scene
            .lights
            .iter()
            .map(|l| pass.render(&ctx, &gpu_scene, l, RESOLUTION).unwrap())
            .collect();
        let generated = VplGenPass::new(&ctx)
            .unwrap()
            .generate(&ctx, &maps, SEED, VplLobes::Both)
            .unwrap();
        let raw: Vec<GpuVpl> = generated
            .buffers
            .read_back(&ctx, generated.read_count(&ctx).unwrap() as usize)
            .unwrap();
        let vpls = generated.read_back(&ctx).unwrap();
        let mut not_one = 0;
        for (i, (v, g)) in vpls.iter().zip(&raw).enumerate() {
            let cpu = GpuVpl::new(v, i, 1e-3).unwrap().geometric_tilt[3];
            let gpu = g.geometric_tilt[3];
            assert!(
                gpu >= cpu && gpu <= cpu * (1.0 + 3e-4),
                "{name} VPL {i} ({:?}): GPU {gpu}, CPU {cpu}",
                v.lobe
            );
            not_one += usize::from(cpu != 1.0);
        }
        eprintln!(
            "{name}: {} VPLs, {not_one} with a factor other than 1",
            vpls.len()
        );
        assert!(not_one > 100, "{name}: {not_one}");
    }
}
