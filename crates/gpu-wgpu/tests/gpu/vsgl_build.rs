//! VSGLs built on the GPU (`VsglBuildPass`) against the CPU's construction from the same
//! RSMs and G-buffer read back (`slc_cpu_ref::vsgl`): the mipmaps texel by texel, the sampled
//! clusters light by light, the total flux the lights carry, and whole frames of the renderer,
//! which must read back no RSM.
//!
//! The GPU sums in f32 where the CPU sums in f64, and warps the samples in f32: a sample
//! whose point falls within f32 rounding of a branch's edge may land in the neighbouring
//! cluster. The tests count those lights and hold them to a small share.
use crate::common::gpu;
use crate::raster_common::{anisotropy, default_scene, lit_scene};
use crate::vsgl::input as vsgl_input;
use glam::Vec3;
use slc_bounds::sg::MeanMap;
use slc_core::frame::{DiffuseEmission, Importance, LightSampling, Method, RenderSettings};
use slc_core::rng::uniform;
use slc_core::shader::SampledLights;
use slc_core::{Camera, Light, Renderer, Scene};
use slc_cpu_ref::sampled_lights::{sample_vsgls, shade_vsgl};
use slc_cpu_ref::vsgl::{
    bidirectional_importance, sample_points, ClusterSums, FilteredSampler, Footprint,
    ImportanceMap, MipRsm, Quadtree, SampleSet,
};
use slc_cpu_ref::{CpuPrepared, Tracer};
use slc_gpu_wgpu::device::buffers::read_back;
use slc_gpu_wgpu::device::buffers::upload;
use slc_gpu_wgpu::frame::light::records::{GpuRsmTexel, GpuShadowTexel};
use slc_gpu_wgpu::frame::light::rsm::{GpuRsm, RsmLayout, RsmPass};
use slc_gpu_wgpu::frame::raster::gbuffer::{GbufferPass, GpuGBuffer};
use slc_gpu_wgpu::frame::raster::scene::GpuScene;
use slc_gpu_wgpu::renderer::GpuRenderer;
use slc_gpu_wgpu::shade::lists::read_image;
use slc_gpu_wgpu::vsgl::build::records::GpuSums;
use slc_gpu_wgpu::vsgl::build::{SumsBuffers, VsglBuildPass, VsglSampling};
use slc_gpu_wgpu::vsgl::readback::cpu_rsm;
use slc_gpu_wgpu::vsgl::shade::records::GpuVsgl;
use slc_gpu_wgpu::vsgl::shade::{GpuVsgls, VsglShadePass};
use slc_gpu_wgpu::{GpuContext, GpuError};
use std::sync::Arc;

/// The RSMs of every light at `resolution` and a 40x30 G-buffer from `camera`.
fn frame(
    ctx: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    resolution: u32,
) -> (Vec<GpuRsm>, GpuGBuffer) {
    let gpu_scene = GpuScene::upload(ctx, scene).unwrap();
    let pass = RsmPass::new(ctx).unwrap();
    let maps = scene
        .lights
        .iter()
        .map(|l| pass.render(ctx, &gpu_scene, l, resolution).unwrap())
        .collect();
    let gbuffer = GbufferPass::new(ctx)
        .unwrap()
        .render(ctx, &gpu_scene, camera, 40, 30, (0.5, 0.5))
        .unwrap();
    (maps, gbuffer)
}

/// The GPU's cluster sums of a pyramid, read back (five arrays, one per field).
fn read_sums(ctx: &GpuContext, sums: &SumsBuffers, len: usize) -> Vec<GpuSums> {
    let fields: Vec<Vec<[f32; 4]>> = sums
        .iter()
        .map(|b| read_back(ctx, "sums", b, len).unwrap())
        .collect();
    (0..len)
        .map(|i| GpuSums {
            diffuse_m2: fields[0][i],
            specular_w: fields[1][i],
            diffuse_mean: fields[2][i],
            specular_mean: fields[3][i],
            mu: fields[4][i],
        })
        .collect()
}

/// The GPU's lights, read back.
fn read_lights(ctx: &GpuContext, vsgls: &GpuVsgls) -> Vec<GpuVsgl> {
    let count = vsgls.count.read(ctx, "vsgl count").unwrap();
    read_back(ctx, "vsgls", &vsgls.buffer, count as usize).unwrap()
}

/// The CPU's mipmaps of the read-back maps.
fn cpu_mips(ctx: &GpuContext, maps: &[GpuRsm]) -> Vec<MipRsm> {
    maps.iter()
        .map(|m| MipRsm::build(&cpu_rsm(ctx, m).unwrap(), MeanMap::Toksvig).unwrap())
        .collect()
}

/// The largest error of a GPU cluster's sums against the CPU's, each field relative to its
/// own scale: the weights, the lobes' mean sums and the specular-weighted normal to the
/// cluster's weight, `μ` to `extent`,
/// `σ²` to itself plus `1e-7 extent²`.
fn sums_error(cpu: &ClusterSums, gpu: &GpuSums, extent: f64) -> f64 {
    let w = cpu.weight();
    let v = |a: [f32; 4]| glam::DVec3::new(a[0].into(), a[1].into(), a[2].into());
    let gpu_w = f64::from(gpu.specular_w[3]);
    if w == 0.0 {
        return gpu_w.abs() + v(gpu.diffuse_m2).length() + v(gpu.specular_w).length();
    }
    let lobe = |s: &slc_bounds::ToksvigSum, g: [f32; 4]| {
        (s.mean_vector().as_dvec3() * s.weight() - v(g)).length() / w
    };
    let mu = cpu.weighted_position / w;
    let sigma2 = cpu.weighted_squared_norm / w - mu.length_squared();
    let gpu_sigma2 = f64::from(gpu.diffuse_m2[3]) / gpu_w;
    let gpu_normal = glam::DVec3::new(
        gpu.diffuse_mean[3].into(),
        gpu.specular_mean[3].into(),
        gpu.mu[3].into(),
    );
    [
        (gpu_w - w).abs() / w,
        (v(gpu.diffuse_m2) - cpu.diffuse_weight).length() / w,
        (v(gpu.specular_w) - cpu.specular_weight).length() / w,
        lobe(&cpu.diffuse_lobe, gpu.diffuse_mean),
        lobe(&cpu.specular_lobe, gpu.specular_mean),
        (v(gpu.mu) - mu).length() / extent,
        (gpu_sigma2 - sigma2).abs() / (sigma2.abs() + 1e-7 * extent * extent),
        (gpu_normal - cpu.specular_normal).length() / w,
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

/// Every texel of every level of the GPU's pyramids holds the CPU's sums (`MipRsm::build`)
/// within 2e-5 of its scale: a spot, a point light's six faces, a directional light's
/// orthographic map and a wide spot's six faces in one tree, at a resolution (24) whose
/// levels have odd sides; and the anisotropic scene (lobes on `sqrt(α_t α)`).
#[test]
fn gpu_mipmaps_match_the_cpus() {
    let Some(ctx) = gpu() else { return };
    let build = VsglBuildPass::new(&ctx).unwrap();
    let (aniso, aniso_camera) = anisotropy();
    let lit = lit_scene();
    let lit_camera = lit.camera_or_default();
    for (name, scene, camera) in [
        ("lit", &lit, lit_camera),
        ("anisotropy", &aniso, aniso_camera),
    ] {
        let (maps, _) = frame(&ctx, scene, &camera, 24);
        let extent = f64::from(crate::raster_common::extent(scene));
        let mip = build.mip(&ctx, &maps).unwrap();
        let gpu = read_sums(&ctx, &mip.sums, mip.tree.len());
        let cpu = cpu_mips(&ctx, &maps);
        let tree = Quadtree::new(24, mip.tree.faces);
        assert_eq!(tree.len(), gpu.len());
        let (mut worst, mut face0, mut clusters) = (0.0f64, 0, 0);
        for m in &cpu {
            for face in 0..m.faces() {
                for level in 0..m.levels() {
                    for y in 0..m.size(level) {
                        for x in 0..m.size(level) {
                            let g = &gpu[tree.index(face0 + face, level, x, y)];
                            let c = m.sums(face, level, x, y);
                            clusters += usize::from(c.weight() > 0.0);
                            let e = sums_error(c, g, extent);
                            assert!(
                                e <= 2e-5,
                                "{name}: face {} level {level} ({x}, {y}): error {e}\n{c:?}\n{g:?}",
                                face0 + face
                            );
                            worst = worst.max(e);
                        }
                    }
                }
            }
            face0 += m.faces();
        }
        println!("{name}: {clusters} clusters, worst sums error {worst:.2e}");
        assert!(clusters > 1000, "{name}: {clusters} lit clusters");
    }
}

/// The CPU's lights of `count` samples in the GPU's order: the VSGL of the cluster each
/// sample reaches first (`FilteredSampler::warp`, weight `m / (N P)`, `Vsgl::from_sums`,
/// packed by `GpuVsgl::new`), in the order of those first samples.
fn cpu_lights(
    importance: &[ImportanceMap],
    mips: &[MipRsm],
    sampling: &VsglSampling,
) -> Vec<GpuVsgl> {
    let n = sampling.count;
    let sampler = FilteredSampler::new(importance);
    let hits: Vec<_> = sample_points(n, sampling.seed, SampleSet::Lights)
        .into_iter()
        .map(|u| sampler.warp(u, n, Footprint::Filtered))
        .collect();
    (0..hits.len())
        .filter_map(|k| {
            let (cluster, probability) = hits[k]?;
            let same = |h: &Option<(_, f64)>| h.is_some_and(|h| h.0 == cluster);
            if hits[..k].iter().any(same) {
                return None;
            }
            let m = hits.iter().filter(|h| same(h)).count() as f64;
            let weight = m / (f64::from(n) * probability);
            let c = cluster;
            let v = mips[c.map as usize]
                .vsgl(c.face, c.level, c.x, c.y, sampling.sigma2_floor)
                .unwrap()
                .scaled(weight as f32);
            Some(GpuVsgl::new(&vsgl_input(&v, sampling.diffuse), k).unwrap())
        })
        .collect()
}

/// How many of the CPU's lights have no equal GPU light at their place or within 8 places
/// of it (a sample that lands in another cluster shifts the lights after it).
fn unmatched(cpu: &[GpuVsgl], gpu: &[GpuVsgl], extent: f32, what: &str) -> usize {
    let mut missing = 0;
    for (j, c) in cpu.iter().enumerate() {
        let near = j.saturating_sub(8)..(j + 9).min(gpu.len());
        if !gpu[near].iter().any(|g| same_vsgl(g, c, extent)) {
            missing += 1;
            if missing <= 3 {
                println!(
                    "{what}: light {j} differs:\n  cpu {c:?}\n  gpu {:?}",
                    gpu.get(j)
                );
            }
        }
    }
    missing
}

/// Whether two packed VSGLs agree: positions within 1e-5 of the extent, σ² and density
/// within 1e-4, colours within 1e-4 of their largest channel, axes within 1e-4 and
/// sharpnesses through their mean lengths `λ/(λ + 1)` within 2e-6 (a sharp lobe's λ is
/// `1/(1 − r)` of a mean length f32 resolves to 6e-8).
fn same_vsgl(a: &GpuVsgl, b: &GpuVsgl, extent: f32) -> bool {
    let close = |x: f32, y: f32, tol: f32| (x - y).abs() <= tol;
    let rel = |x: f32, y: f32, tol: f32| (x - y).abs() <= tol * x.abs().max(y.abs());
    let mean = |l: f32| l / (l + 1.0);
    let rgb = |x: [f32; 4], y: [f32; 4]| {
        let scale = x[..3]
            .iter()
            .chain(&y[..3])
            .fold(0.0f32, |m, v| m.max(v.abs()));
        (0..3).all(|i| close(x[i], y[i], 1e-4 * scale))
    };
    let lobe = |x: [f32; 4], y: [f32; 4]| {
        (0..3).all(|i| close(x[i], y[i], 1e-4)) && close(mean(x[3]), mean(y[3]), 2e-6)
    };
    (0..3).all(|i| close(a.mu_sigma2[i], b.mu_sigma2[i], 1e-5 * extent))
        && rel(a.mu_sigma2[3], b.mu_sigma2[3], 1e-4)
        && rel(a.diffuse_c_density[3], b.diffuse_c_density[3], 1e-4)
        && rgb(a.diffuse_c_density, b.diffuse_c_density)
        && rgb(a.specular_c, b.specular_c)
        && a.specular_c[3] == b.specular_c[3]
        && lobe(a.diffuse_lobe, b.diffuse_lobe)
        && lobe(a.specular_lobe, b.specular_lobe)
        && stretch(a, b)
}

/// The specular lobe's stretch of two packed VSGLs agrees: `cos θ` and its inverse within
/// 1e-4, and, where the stretch is more than a rounding (`cos θ` below 0.999), the tangent
/// and bitangent within 1e-3 up to their sign (the stretch depends on their squares).
fn stretch(a: &GpuVsgl, b: &GpuVsgl) -> bool {
    let (ta, tb) = (a.stretch_tangent, b.stretch_tangent);
    let (ba, bb) = (a.stretch_bitangent, b.stretch_bitangent);
    let near = |x: [f32; 4], y: [f32; 4]| {
        let d = |s: f32| (0..3).all(|i| (x[i] - s * y[i]).abs() <= 1e-3);
        d(1.0) || d(-1.0)
    };
    (ta[3] - tb[3]).abs() <= 1e-4
        && (ba[3] - bb[3]).abs() <= 1e-4 * ba[3].max(bb[3])
        && (ta[3] >= 0.999 || (near(ta, tb) && near(ba, bb)))
}

/// The total `Σ Φ (R_d + R_s)` a VSGL carries: `c_v A(λ_v)` of each lobe (the
/// clamped diffuse lobe holds the peak `c_v A(λ_v)/π`).
fn carried(v: &GpuVsgl) -> f64 {
    use slc_bounds::sg::{mixture_scale, sg_integral, MIXTURE_FROM};
    let total = |c: [f32; 4]| f64::from(c[0] + c[1] + c[2]);
    let lambda = v.specular_lobe[3];
    // The packed specular c carries the mixture's scale (GpuVsgl::specular_c).
    let scale = if lambda >= MIXTURE_FROM {
        mixture_scale(lambda)
    } else {
        1.0
    };
    let specular = total(v.specular_c) * f64::from(sg_integral(lambda) / scale);
    let diffuse = if v.specular_c[3] != 0.0 {
        total(v.diffuse_c_density) * std::f64::consts::PI
    } else {
        total(v.diffuse_c_density) * f64::from(sg_integral(v.diffuse_lobe[3]))
    };
    diffuse + specular
}

/// The GPU's sampled lights are the CPU's, light by light, for the flux and the bidirectional
/// importance, both diffuse emissions and 16 to 4096 samples, on the default scene and on
/// four lights of every kind in one tree; at most 1 % of the lights (a sample at a branch's
/// edge) may differ, and with the flux importance the lights carry the total flux within
/// 1e-4 (each sample carries total/N: the estimate is unbiased by construction).
#[test]
fn gpu_sampled_lights_match_the_cpus() {
    let Some(ctx) = gpu() else { return };
    let build = VsglBuildPass::new(&ctx).unwrap();
    let (default, default_camera) = default_scene();
    let lit = lit_scene();
    let lit_camera = lit.camera_or_default();
    for (name, scene, camera) in [
        ("default", &default, default_camera),
        ("lit", &lit, lit_camera),
    ] {
        let (maps, gbuffer) = frame(&ctx, scene, &camera, 32);
        let extent = crate::raster_common::extent(scene);
        let mips = cpu_mips(&ctx, &maps);
        let flux: Vec<_> = mips.iter().map(ImportanceMap::from_mip).collect();
        let total: f64 = flux
            .iter()
            .flat_map(|m| (0..m.layout().faces()).map(|f| m.face_mass(f)))
            .sum();
        let cpu_gbuffer = gbuffer.read_back(&ctx).unwrap();
        let cpu_maps: Vec<_> = maps.iter().map(|m| cpu_rsm(&ctx, m).unwrap()).collect();
        for importance in [
            Importance::Flux,
            Importance::Bidirectional { camera_vsgls: 64 },
        ] {
            for diffuse in [DiffuseEmission::ClampedCosine, DiffuseEmission::Sg] {
                for count in [16, 256, 4096] {
                    let sampling = VsglSampling {
                        count,
                        seed: 7,
                        sigma2_floor: 1e-8,
                        diffuse,
                    };
                    let mut mip = build.mip(&ctx, &maps).unwrap();
                    let weights = match importance {
                        Importance::Flux => flux.clone(),
                        Importance::Bidirectional { camera_vsgls } => {
                            build
                                .bidirectional(
                                    &ctx,
                                    &mut mip,
                                    &maps,
                                    &gbuffer,
                                    camera_vsgls,
                                    &sampling,
                                )
                                .unwrap();
                            bidirectional_importance(
                                &cpu_gbuffer,
                                &gbuffer.camera,
                                &cpu_maps,
                                camera_vsgls,
                                sampling.seed,
                                sampling.sigma2_floor,
                                diffuse,
                            )
                            .unwrap()
                        }
                    };
                    let vsgls = build.sample(&ctx, mip, &sampling).unwrap();
                    let gpu = read_lights(&ctx, &vsgls);
                    let cpu = cpu_lights(&weights, &mips, &sampling);
                    let what = format!("{name} {} {} N {count}", importance.name(), diffuse.name());
                    let differ = unmatched(&cpu, &gpu, extent, &what);
                    println!(
                        "{what}: {} lights, {} on the GPU, {differ} differ",
                        cpu.len(),
                        gpu.len()
                    );
                    assert!(!cpu.is_empty(), "{what}");
                    let tolerance = 0.01 * cpu.len() as f64;
                    assert!(differ as f64 <= tolerance, "{what}: {differ} lights differ");
                    assert!(gpu.len().abs_diff(cpu.len()) as f64 <= tolerance, "{what}");
                    if importance == Importance::Flux {
                        let sum: f64 = gpu.iter().map(carried).sum();
                        assert!(
                            (sum - total).abs() <= 1e-4 * total,
                            "{what}: the lights carry {sum}, the maps {total}"
                        );
                    }
                }
            }
        }
    }
}

/// Whole VSGL frames of the renderer against the CPU's `shade_vsgl` on the same prepared
/// frame read back (`CpuFrames`), flux and bidirectional importance: the images agree within
/// 1e-3 of the mean image (RMS) and the counts of lights within 1 %; and what the frame read
/// back is the image and the fault record, no RSM.
#[test]
fn gpu_vsgl_frames_match_the_cpu_and_read_back_no_rsm() {
    let Some(ctx) = gpu() else { return };
    let renderer = GpuRenderer::from_context(ctx).unwrap();
    let (scene, _) = default_scene();
    let loaded = renderer.load(&scene).unwrap();
    for importance in [
        Importance::Flux,
        Importance::Bidirectional { camera_vsgls: 64 },
    ] {
        let sampling = LightSampling {
            count: 1024,
            importance,
            diffuse: DiffuseEmission::ClampedCosine,
        };
        let settings = RenderSettings {
            width: 48,
            height: 48,
            rsm_resolution: 32,
            seed: 3,
            method: Method::Vsgl(sampling),
            visibility: false,
            spp: 1,
            lobes: slc_core::frame::LobeSelection::Both,
        };
        let p = renderer
            .prepare(&scene, &loaded, &settings, None, &|_| {})
            .unwrap();
        let before = renderer.readback_bytes().unwrap();
        let gpu = renderer
            .shade_sampled(
                &scene,
                &loaded,
                &p,
                SampledLights::Vsgl,
                &sampling,
                9,
                false,
                &|_| {},
            )
            .unwrap();
        let after = renderer.readback_bytes().unwrap();
        let read: Vec<_> = after
            .iter()
            .filter(|(k, v)| before.get(*k) != Some(v))
            .map(|(k, v)| (k.clone(), v - before.get(k).copied().unwrap_or(0)))
            .collect();
        let image_bytes = 48 * 48 * 3 * 4;
        assert_eq!(
            read,
            [
                ("indirect image".to_owned(), image_bytes),
                ("vsgl status".to_owned(), 32)
            ],
            "{}: what a frame read back",
            importance.name()
        );
        let data = renderer.read_frame(&p).unwrap();
        let cpu_frame = CpuPrepared::from_data(data, Arc::new(Tracer::new(&scene)));
        let cpu = shade_vsgl(&cpu_frame, &sampling, 9, false, &|_| {}).unwrap();
        let (g, c) = (&gpu.indirect, &cpu.indirect);
        let mean = c.mean().max_element();
        let rms = (g
            .pixels
            .iter()
            .zip(&c.pixels)
            .map(|(a, b)| f64::from((*a - *b).length_squared()))
            .sum::<f64>()
            / g.pixels.len() as f64)
            .sqrt() as f32;
        let (gl, cl) = (gpu.sampled_lights.unwrap(), cpu.sampled_lights.unwrap());
        println!(
            "{}: {gl} GPU lights, {cl} CPU lights, RMS difference {:.2e} of the mean {mean:.3e}",
            importance.name(),
            rms / mean
        );
        assert!(g.pixels.iter().all(|v| v.is_finite()));
        assert!(mean > 0.0 && rms <= 1e-3 * mean, "{}", importance.name());
        assert!(gl.abs_diff(cl) as f64 <= 0.01 * cl as f64, "{gl} vs {cl}");
    }
}

/// A unit vector from two uniform numbers.
fn direction(a: f32, b: f32) -> Vec3 {
    let z = 2.0 * a - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * b;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A map of `n`² crafted texels from a spot light at the origin looking down −z: random
/// positions in front of it, normals, light directions from the normal's own (`n · ωi` = 1)
/// to grazing (1e-7) and below, α from 1e-4 to 1 (a third anisotropic), Schlick or dielectric
/// Fresnel, fluxes from 1e-20 to 1e20 and a fifth of the texels empty; texel `bad` (if any)
/// with α = 0, outside the SG domain.
fn crafted_map(ctx: &GpuContext, n: u32, seed: u32, bad: Option<usize>) -> GpuRsm {
    map_of(ctx, n, &crafted_texels(n, seed, bad))
}

/// The texels of [`crafted_map`].
fn crafted_texels(n: u32, seed: u32, bad: Option<usize>) -> Vec<GpuRsmTexel> {
    let u = |k: u32, c: u32| uniform(seed, k, 0, c);
    let mut texels = Vec::new();
    for k in 0..n * n {
        let normal = direction(u(k, 0), u(k, 1));
        let tangent = normal.any_orthonormal_vector();
        let cos = [1.0, 0.5, 1e-3, 1e-7, -0.2][(k % 5) as usize];
        let omega_i = (normal * cos + tangent * (1.0 - cos * cos).max(0.0).sqrt()).normalize();
        let alpha = 10f32.powf(-4.0 * u(k, 2));
        let flux = 10f32.powf(40.0 * u(k, 3) - 20.0);
        let position = Vec3::new(
            2.0 * u(k, 4) - 1.0,
            2.0 * u(k, 5) - 1.0,
            -1.0 - 2.0 * u(k, 6),
        );
        let present = u(k, 7) > 0.2;
        let dielectric = k % 4 == 1;
        let mut t = GpuRsmTexel {
            position: position.extend(if present { 1.0 } else { 0.0 }).to_array(),
            normal_alpha: normal.extend(alpha).to_array(),
            omega_i_eta: omega_i.extend(1.5).to_array(),
            flux: [flux, 0.5 * flux, 0.25 * flux],
            fresnel: u32::from(dielectric),
            kd: [u(k, 8), 0.5, 0.0, 0.0],
            f0: [0.04, 0.9, 1.0, 0.0],
            geometric: normal.extend(0.0).to_array(),
            anisotropy: if k % 3 == 0 {
                tangent.extend(10f32.powf(-4.0 * u(k, 9))).to_array()
            } else {
                [0.0; 4]
            },
        };
        if bad == Some(k as usize) {
            t.position[3] = 1.0;
            t.normal_alpha[3] = 0.0;
        }
        texels.push(t);
    }
    texels
}

/// The spot light of [`crafted_map`] with `texels` (`n`² of them) and their shadow map.
fn map_of(ctx: &GpuContext, n: u32, texels: &[GpuRsmTexel]) -> GpuRsm {
    let light = Light::Spot {
        position: Vec3::ZERO,
        direction: Vec3::NEG_Z,
        intensity: Vec3::ONE,
        inner_cone_angle: 0.5,
        outer_cone_angle: 0.6,
    };
    let layout = RsmLayout::new(&light, (Vec3::splat(-4.0), Vec3::splat(4.0)));
    let shadow: Vec<_> = texels
        .iter()
        .map(|t| GpuShadowTexel {
            position: t.position,
            normal: t.geometric,
        })
        .collect();
    GpuRsm {
        light,
        layout,
        resolution: n,
        texels: upload(ctx, "crafted texels", texels).unwrap(),
        shadow: upload(ctx, "crafted shadow", &shadow).unwrap(),
    }
}

/// Texels at the extremes of the SG domain give the CPU's sums (within 2e-5 of their scale)
/// and the CPU's number of lights, which carry the maps' flux; a texel outside the domain, a
/// light of no area with no σ² floor, no maps and no samples are clear outcomes: typed errors
/// naming the texel or light, or no light.
#[test]
fn extreme_texels_match_the_cpu_or_are_errors() {
    let Some(ctx) = gpu() else { return };
    let build = VsglBuildPass::new(&ctx).unwrap();
    let (scene, camera) = default_scene();
    let (_, gbuffer) = frame(&ctx, &scene, &camera, 8);
    let shader = VsglShadePass::new(&ctx).unwrap();
    let shade = |vsgls: &GpuVsgls| shader.shade_gpu_gbuffer_on_gpu(&ctx, &gbuffer, vsgls, None);
    let sampling = VsglSampling {
        count: 512,
        seed: 1,
        sigma2_floor: 1e-12,
        diffuse: DiffuseEmission::ClampedCosine,
    };
    let maps = [
        crafted_map(&ctx, 13, 1, None),
        crafted_map(&ctx, 13, 2, None),
    ];
    let mip = build.mip(&ctx, &maps).unwrap();
    let gpu = read_sums(&ctx, &mip.sums, mip.tree.len());
    let cpu = cpu_mips(&ctx, &maps);
    let tree = Quadtree::new(13, 2);
    let mut worst = 0.0f64;
    for (f, m) in cpu.iter().enumerate() {
        for level in 0..m.levels() {
            for y in 0..m.size(level) {
                for x in 0..m.size(level) {
                    let e = sums_error(
                        m.sums(0, level, x, y),
                        &gpu[tree.index(f as u32, level, x, y)],
                        4.0,
                    );
                    assert!(e <= 2e-5, "map {f} level {level} ({x}, {y}): {e}");
                    worst = worst.max(e);
                }
            }
        }
    }
    println!("extreme texels: worst sums error {worst:.2e}");
    let total: f64 = cpu
        .iter()
        .map(|m| m.sums(0, m.levels() - 1, 0, 0).weight())
        .sum();
    let vsgls = build.sample(&ctx, mip, &sampling).unwrap();
    let lights = read_lights(&ctx, &vsgls);
    let sum: f64 = lights.iter().map(carried).sum();
    assert!((sum - total).abs() <= 1e-4 * total, "{sum} vs {total}");
    let (rgb, count) = shade(&vsgls).unwrap();
    let flux: Vec<_> = cpu.iter().map(ImportanceMap::from_mip).collect();
    let cpu_lights = sample_vsgls(&cpu, &flux, 512, 1, 1e-12).unwrap().len();
    assert_eq!(count as usize, cpu_lights);
    let image = read_image(&ctx, &rgb, gbuffer.width, gbuffer.height).unwrap();
    assert!(image.pixels.iter().all(|p| p.is_finite()));

    // A texel outside the domain: the error names the smallest such texel over the maps.
    let broken = [
        crafted_map(&ctx, 13, 1, None),
        crafted_map(&ctx, 13, 2, Some(40)),
    ];
    let vsgls = build
        .sample(&ctx, build.mip(&ctx, &broken).unwrap(), &sampling)
        .unwrap();
    match shade(&vsgls) {
        Err(GpuError::Input(m)) => assert!(m.starts_with("RSM texel 209:"), "{m}"),
        r => panic!("expected a texel error, got {:?}", r.map(|_| ())),
    }
    // A texel at the light itself has no cross-section: with no σ² floor its VSGL is a point
    // light, outside eq. (1).
    let mut at_light = crafted_texels(1, 3, None);
    at_light[0].position = [0.0, 0.0, 0.0, 1.0];
    let points = VsglSampling {
        sigma2_floor: 0.0,
        ..sampling
    };
    let vsgls = build
        .sample(
            &ctx,
            build.mip(&ctx, &[map_of(&ctx, 1, &at_light)]).unwrap(),
            &points,
        )
        .unwrap();
    match shade(&vsgls) {
        Err(GpuError::Input(m)) => assert!(m.starts_with("VSGL 0:"), "{m}"),
        r => panic!("expected a VSGL error, got {:?}", r.map(|_| ())),
    }
    // No maps, no samples: no lights, a black image.
    for (maps, count) in [(&[][..], 512), (&maps[..], 0)] {
        let vsgls = build
            .sample(
                &ctx,
                build.mip(&ctx, maps).unwrap(),
                &VsglSampling { count, ..sampling },
            )
            .unwrap();
        let (rgb, lights) = shade(&vsgls).unwrap();
        assert_eq!(lights, 0);
        let image = read_image(&ctx, &rgb, gbuffer.width, gbuffer.height).unwrap();
        assert!(image.pixels.iter().all(|p| *p == Vec3::ZERO));
    }
    // Maps of different resolutions are refused.
    let mixed = [crafted_map(&ctx, 4, 1, None), crafted_map(&ctx, 5, 1, None)];
    assert!(matches!(build.mip(&ctx, &mixed), Err(GpuError::Input(_))));
}

/// Six maps of 512² texels (as many faces as a point light's at RSM 512: 2,097,150 tree
/// texels) fit the storage bindings of lavapipe (128 MiB each), and their lights carry the
/// maps' flux.
#[test]
fn six_faces_of_512_squared_fit() {
    let Some(ctx) = gpu() else { return };
    let build = VsglBuildPass::new(&ctx).unwrap();
    let maps: Vec<_> = (0..6).map(|s| crafted_map(&ctx, 512, s, None)).collect();
    let mip = build.mip(&ctx, &maps).unwrap();
    assert_eq!(mip.tree.len(), 2_097_150);
    let weights = read_back::<[f32; 4]>(&ctx, "weights", &mip.sums[1], mip.tree.len()).unwrap();
    let face = mip.tree.len() / 6;
    let total: f64 = (1..=6).map(|f| f64::from(weights[f * face - 1][3])).sum();
    let sampling = VsglSampling {
        count: 4096,
        seed: 5,
        sigma2_floor: 1e-12,
        diffuse: DiffuseEmission::ClampedCosine,
    };
    let lights = read_lights(&ctx, &build.sample(&ctx, mip, &sampling).unwrap());
    let sum: f64 = lights.iter().map(carried).sum();
    assert!(lights.len() > 10, "{} lights", lights.len());
    assert!((sum - total).abs() <= 1e-4 * total, "{sum} vs {total}");
}
