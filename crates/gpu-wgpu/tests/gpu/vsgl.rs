//! GPU VSGL shading (`VsglShadePass`) against `slc_cpu_ref::vsgl::shade_vsgls(…, visibility
//! = false, …)` for identical inputs (the CPU's G-buffer uploaded, the same VSGLs): every
//! pixel must agree within `max_c |gpu − cpu| <= 1e-4 · max(max_c |cpu|, 1e-3 · m)`, m the
//! largest channel of the CPU image's mean, and the GPU image must be finite.
//!
//! Both evaluate the SG algebra in f32 with series where f32 would cancel: the GPU in WGSL
//! (`vsgl/shade/sg.wesl`), the CPU's VSGL shading in Rust (`slc_bounds`' `sg/single.rs`, held
//! to its f64 forms by its tests; before it shaded in f64, which these tests were first
//! measured against: at most 6.2e-7 on the default scene and 1.0e-5 on the extremes).
//! Measured on lavapipe (the worst pixel ratio `max_c |gpu − cpu| / max(max_c |cpu|,
//! floor)`, printed by the tests), at f400650 (the three stretched SGs of the specular lobe,
//! the CPU summing in chunk order): built-in default scene at most 1.2e-5 for 16, 256 and
//! 4096 samples (16, ~240 and ~3200 distinct VSGLs) with either importance; the synthetic
//! frame of extremes 2.6e-5 with its 64 VSGLs together and 2.8e-5 with each VSGL alone
//! (with one SG per lobe: 5.3e-7, 4.1e-7 and 3.2e-6). The 1e-4
//! target holds in every regime tested. Breaking a formula fails the tests: a Langevin series coefficient off by 2 %
//! (2.9e-4 on the default scene), the specular weight without its `ωo·n` (1.9), and the naive
//! f32 `coth λ − 1/λ` below λ = 1 instead of its series (4.7e-4 on a broad lobe, one VSGL at
//! a time).
use crate::common::{crafted_fresnel, crafted_kd, gpu};
use glam::Vec3;
use slc_bounds::sg::MeanMap;
use slc_bounds::Brdf;
use slc_core::frame::DiffuseEmission;
use slc_core::{builtin, GBuffer, GSample, Image};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::rsm::{trace_rsm, TexelSample};
use slc_cpu_ref::sampled_lights::{sample_vsgls, sigma2_floor};
use slc_cpu_ref::vsgl::{bidirectional_importance, shade_vsgls, ImportanceMap, MipRsm, Vsgl};
use slc_cpu_ref::Tracer;
use slc_gpu_wgpu::device::buffers::upload;
use slc_gpu_wgpu::frame::raster::gbuffer::GpuGBuffer;
use slc_gpu_wgpu::frame::raster::records::{gpu_position, GpuSample};
use slc_gpu_wgpu::shade::lists::read_image;
use slc_gpu_wgpu::vsgl::shade::records::{VsglInput, VsglLobe};
use slc_gpu_wgpu::vsgl::shade::{GpuVsgls, VsglShadePass};
use slc_gpu_wgpu::{GpuContext, GpuError};

const TOLERANCE: f32 = 1e-4;
const FLOOR_OF_MEAN: f32 = 1e-3;

/// Both forms of the diffuse emission, the default first.
const EMISSIONS: [DiffuseEmission; 2] = [DiffuseEmission::ClampedCosine, DiffuseEmission::Sg];

/// A CPU VSGL as the GPU's VSGL shading pass takes it.
pub fn input(v: &Vsgl, diffuse: DiffuseEmission) -> VsglInput {
    VsglInput {
        clamped_diffuse: match diffuse {
            DiffuseEmission::Sg => None,
            DiffuseEmission::ClampedCosine => Some(v.normal_concentration),
        },
        mu: v.mu,
        sigma2: v.sigma2,
        specular_normal: v.specular_normal,
        lobes: [
            VsglLobe {
                c: v.c_diffuse,
                xi: v.xi_diffuse,
                lambda: v.lambda_diffuse,
            },
            VsglLobe {
                c: v.c_specular,
                xi: v.xi_specular,
                lambda: v.lambda_specular,
            },
        ],
    }
}

/// The worst pixel ratio `max_c |gpu − cpu| / max(max_c |cpu|, floor)` and its pixel; fails
/// on a non-finite GPU value.
fn worst_error(gpu: &Image, cpu: &Image) -> (f32, usize) {
    let floor = FLOOR_OF_MEAN * cpu.mean().max_element();
    let mut worst = (0.0f32, 0);
    for (p, (g, c)) in gpu.pixels.iter().zip(&cpu.pixels).enumerate() {
        assert!(g.is_finite(), "pixel {p}: GPU {g}");
        let err = (*g - *c).abs().max_element();
        let scale = c.abs().max_element().max(floor);
        let ratio = if scale > 0.0 {
            err / scale
        } else if err > 0.0 {
            f32::INFINITY
        } else {
            0.0
        };
        if ratio > worst.0 {
            worst = (ratio, p);
        }
    }
    worst
}

/// Shades `vsgls` on `gbuffer` on both backends and holds them to the tolerance.
fn agree(
    ctx: &GpuContext,
    tracer: &Tracer,
    gbuffer: &GBuffer,
    vsgls: &[Vsgl],
    diffuse: DiffuseEmission,
    what: &str,
) -> f32 {
    let cpu = shade_vsgls(tracer, gbuffer, vsgls, diffuse, false, &|_| {}).unwrap();
    let inputs: Vec<_> = vsgls.iter().map(|v| input(v, diffuse)).collect();
    let pass = VsglShadePass::new(ctx).unwrap();
    let gpu = pass
        .shade(ctx, gbuffer, &GpuVsgls::upload(ctx, &inputs).unwrap())
        .unwrap();
    let (worst, p) = worst_error(&gpu, &cpu);
    println!(
        "{what} ({}): {} VSGLs, worst {worst:.3e} at pixel {p} (gpu {}, cpu {}), mean {}",
        diffuse.name(),
        vsgls.len(),
        gpu.pixels[p],
        cpu.pixels[p],
        cpu.mean()
    );
    assert!(cpu.mean().max_element() > 0.0, "{what}: a black image");
    assert!(worst <= TOLERANCE, "{what}: worst {worst} at pixel {p}");
    worst
}

/// The built-in default scene: VSGLs built and sampled as `shade_vsgl` of
/// `slc_cpu_ref::sampled_lights` does (Toksvig mip, flux or bidirectional importance,
/// filtered footprint, weights applied), 16 to 4096 of them.
#[test]
fn vsgl_shading_matches_the_cpu_on_the_default_scene() {
    let Some(ctx) = gpu() else { return };
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let tracer = Tracer::new(&scene);
    let gbuffer = trace_gbuffer(
        &scene,
        &tracer,
        &camera,
        48,
        36,
        PixelSample::Jittered { seed: 3, index: 0 },
    );
    let maps: Vec<_> = scene
        .lights
        .iter()
        .map(|l| trace_rsm(&scene, &tracer, l, 32, TexelSample::Centre))
        .collect();
    let floor = sigma2_floor(&tracer);
    let mips: Vec<_> = maps
        .iter()
        .map(|m| MipRsm::build(m, MeanMap::Toksvig).unwrap())
        .collect();
    let flux: Vec<_> = mips.iter().map(ImportanceMap::from_mip).collect();
    let mut worst = 0.0f32;
    for diffuse in EMISSIONS {
        let bidirectional =
            bidirectional_importance(&gbuffer, &camera, &maps, 64, 7, floor, diffuse).unwrap();
        for (name, importance) in [("flux", &flux), ("bidirectional", &bidirectional)] {
            for count in [16, 256, 4096] {
                let vsgls = sample_vsgls(&mips, importance, count, 7, floor).unwrap();
                worst = worst.max(agree(&ctx, &tracer, &gbuffer, &vsgls, diffuse, name));
            }
        }
    }
    println!("default scene: worst {worst:.3e}");
}

/// A plane z = 0 of receivers: sky pixels, views from head-on to grazing (ωo·n = 1e-4) and
/// from below, α from 1e-3 to 1, Schlick and dielectric Fresnel, zero kd.
fn extreme_gbuffer() -> GBuffer {
    let (w, h) = (24u32, 20u32);
    let mut samples = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if y < 2 || (x + 2 * y) % 13 == 0 {
                samples.push(None);
                continue;
            }
            let omega_o = match x % 5 {
                0 => Vec3::new(1.0, 0.0, 1e-4).normalize(),
                1 => Vec3::new(-0.3, 0.2, 1.0).normalize(),
                2 => Vec3::Z,
                3 => Vec3::new(0.0, -1.0, 0.02).normalize(),
                _ => Vec3::new(0.3, 0.0, -1.0).normalize(),
            };
            let (fresnel, kd) = (crafted_fresnel((x / 2) % 2 == 0), crafted_kd(y % 5 == 0));
            samples.push(Some(GSample {
                position: Vec3::new(x as f32 * 0.25 - 3.0, y as f32 * 0.25 - 2.5, 0.0),
                normal: Vec3::Z,
                geometric_normal: Vec3::Z,
                omega_o,
                depth: 1.0,
                brdf: Brdf {
                    kd,
                    fresnel,
                    alpha: [1e-3, 0.02, 0.3, 1.0][(y % 4) as usize],
                    anisotropy: None,
                },
            }));
        }
    }
    GBuffer {
        width: w,
        height: h,
        samples,
    }
}

/// VSGLs of extreme parameters: λ from 0 to 1e6 on both lobes, normal concentrations κ from 0
/// to 1.7e7 (the clamped diffuse emission), σ² from 1e-6 to 10, μ_v on a
/// receiver (the constant positional lobe), near and far above the plane and below it, zero
/// lobes, lobes facing the plane and away from it.
fn extreme_vsgls() -> Vec<Vsgl> {
    let lambdas = [0.0, 1e-6, 1e-3, 0.5, 3.0, 30.0, 1e4, 1e6];
    let sigmas = [1e-6, 1e-3, 0.1, 10.0];
    let mut vsgls = Vec::new();
    for (i, &ld) in lambdas.iter().enumerate() {
        for (j, &ls) in lambdas.iter().rev().enumerate() {
            let k = i * lambdas.len() + j;
            let mu = match k % 6 {
                // A receiver's own position (pixel (4, 10) of the extreme G-buffer).
                0 => Vec3::new(-2.0, 0.0, 0.0),
                1 => Vec3::new(0.3, -0.2, 1e-3),
                2 => Vec3::new(-1.0, 1.0, 2.0),
                3 => Vec3::new(0.5, 0.5, -0.5),
                4 => Vec3::new(20.0, -30.0, 5.0),
                _ => Vec3::new(-0.1 * k as f32, 0.2, 0.7),
            };
            let down = Vec3::new(0.2 * (k % 3) as f32 - 0.2, 0.1, -1.0).normalize();
            vsgls.push(Vsgl {
                c_diffuse: if k % 7 == 3 {
                    Vec3::ZERO
                } else {
                    Vec3::new(1.0, 0.5, 0.25)
                },
                xi_diffuse: if k % 4 == 1 { -down } else { down },
                lambda_diffuse: ld,
                // Coplanar texels (at most 1.7e7, `Vsgl::normal_concentration`) down to a
                // broad spread of normals.
                normal_concentration: [1.7e7, 1e3, 10.0, 0.3, 0.0][k % 5],
                c_specular: if k % 5 == 2 {
                    Vec3::ZERO
                } else {
                    Vec3::new(0.3, 0.6, 0.9)
                },
                xi_specular: down,
                lambda_specular: ls,
                // Stretched in a plane of incidence now and then, at grazing too; isotropic
                // where unknown.
                specular_normal: match k % 4 {
                    0 => Vec3::ZERO,
                    1 => Vec3::new(0.6, 0.0, 0.8),
                    2 => Vec3::new(-0.2, 0.97, 0.1).normalize(),
                    _ => -Vec3::Z,
                },
                mu,
                sigma2: sigmas[k % sigmas.len()],
                weight: 1.0,
            });
        }
    }
    vsgls
}

#[test]
fn vsgl_shading_matches_the_cpu_on_extremes() {
    let Some(ctx) = gpu() else { return };
    let tracer = Tracer::new(&builtin("default").unwrap());
    let gbuffer = extreme_gbuffer();
    let vsgls = extreme_vsgls();
    let mut worst = 0.0f32;
    for diffuse in EMISSIONS {
        agree(&ctx, &tracer, &gbuffer, &vsgls, diffuse, "extremes");
        // Each VSGL alone, so no regime hides behind a brighter one.
        for v in &vsgls {
            let cpu = shade_vsgls(
                &tracer,
                &gbuffer,
                std::slice::from_ref(v),
                diffuse,
                false,
                &|_| {},
            )
            .unwrap();
            let pass = VsglShadePass::new(&ctx).unwrap();
            let gpu = pass
                .shade(
                    &ctx,
                    &gbuffer,
                    &GpuVsgls::upload(&ctx, &[input(v, diffuse)]).unwrap(),
                )
                .unwrap();
            let (w, p) = worst_error(&gpu, &cpu);
            assert!(
                w <= TOLERANCE,
                "{v:?} ({}): worst {w} at pixel {p}",
                diffuse.name()
            );
            worst = worst.max(w);
        }
    }
    println!("extremes, one VSGL at a time: worst {worst:.3e}");
}

/// Out-of-domain input is an error, not a NaN: σ² ≤ 0 or with an infinite 1/(2πσ²),
/// non-finite μ or c, a λ_σ beyond f32 at some pixel (found by the shader), invalid surfaces
/// of an uploaded G-buffer (the CPU's check) and of a GPU G-buffer (found by the shader).
#[test]
fn vsgl_shading_refuses_out_of_domain_input() {
    let Some(ctx) = gpu() else { return };
    let pass = VsglShadePass::new(&ctx).unwrap();
    let gbuffer = extreme_gbuffer();
    let good = input(&extreme_vsgls()[5], DiffuseEmission::Sg);
    for sigma2 in [0.0, -1.0, f32::NAN, 1e-45] {
        let r = GpuVsgls::upload(&ctx, &[VsglInput { sigma2, ..good }]);
        assert!(matches!(r, Err(GpuError::Input(_))), "σ² {sigma2}");
    }
    let mut bad = good;
    bad.lobes[0].c.y = f32::INFINITY;
    assert!(GpuVsgls::upload(&ctx, &[bad]).is_err());
    // σ² = 1e-38 keeps 1/(2πσ²) finite, but λ_σ = r²/σ² overflows for every receiver.
    let tiny = GpuVsgls::upload(
        &ctx,
        &[
            good,
            VsglInput {
                sigma2: 1e-38,
                ..good
            },
        ],
    )
    .unwrap();
    match pass.shade(&ctx, &gbuffer, &tiny) {
        Err(GpuError::Input(m)) => assert!(m.starts_with("VSGL 1:"), "{m}"),
        r => panic!("expected an overflow error, got {:?}", r.map(|_| ())),
    }
    let vsgls = GpuVsgls::upload(&ctx, &[good]).unwrap();
    let mut broken = gbuffer.clone();
    broken.samples[100].as_mut().unwrap().brdf.alpha = 0.0;
    assert!(pass.shade(&ctx, &broken, &vsgls).is_err());
    // The same sample on a G-buffer already on the GPU: the shader records it.
    let camera = builtin("default").unwrap().camera_or_default();
    let samples: Vec<_> = broken
        .samples
        .iter()
        .map(|s| GpuSample::new(s.as_ref()))
        .collect();
    let positions: Vec<_> = broken
        .samples
        .iter()
        .map(|s| gpu_position(s.as_ref()))
        .collect();
    let on_gpu = GpuGBuffer {
        width: broken.width,
        height: broken.height,
        camera,
        samples: upload(&ctx, "samples", &samples).unwrap(),
        geometric_normals: upload(&ctx, "normals", &positions).unwrap(),
        positions: upload(&ctx, "positions", &positions).unwrap(),
        offset: (0.5, 0.5),
    };
    let shade_on_gpu = |g: &GpuGBuffer| {
        let (rgb, _) = pass.shade_gpu_gbuffer_on_gpu(&ctx, g, &vsgls, None)?;
        read_image(&ctx, &rgb, g.width, g.height)
    };
    match shade_on_gpu(&on_gpu) {
        Err(GpuError::Input(m)) => assert!(m.starts_with("G-buffer pixel 100:"), "{m}"),
        r => panic!("expected a surface error, got {:?}", r.map(|_| ())),
    }
    // Without the broken sample the GPU G-buffer shades as the uploaded one.
    let samples: Vec<_> = gbuffer
        .samples
        .iter()
        .map(|s| GpuSample::new(s.as_ref()))
        .collect();
    let fixed = GpuGBuffer {
        samples: upload(&ctx, "samples", &samples).unwrap(),
        ..on_gpu
    };
    let a = shade_on_gpu(&fixed).unwrap();
    let b = pass.shade(&ctx, &gbuffer, &vsgls).unwrap();
    assert_eq!(a.pixels, b.pixels);
}

/// On Mesa's llvmpipe, which ends a shader invocation's loops after 65,535 iterations in all,
/// a pixel's sum over 16,384 VSGLs came out 15% dark: there shading 8,184 VSGLs or more is
/// refused with the typed error naming the count and `--vsgls`, and 8,183 are shaded; other
/// adapters shade both.
#[test]
fn vsgls_beyond_the_adapters_loop_budget_are_refused() {
    let Some(ctx) = gpu() else { return };
    let pass = VsglShadePass::new(&ctx).unwrap();
    let gbuffer = extreme_gbuffer();
    let good = input(&extreme_vsgls()[5], DiffuseEmission::Sg);
    let shaded = |n: usize| {
        let vsgls = GpuVsgls::upload(&ctx, &vec![good; n]).unwrap();
        pass.shade(&ctx, &gbuffer, &vsgls).map(|_| ())
    };
    assert!(shaded(8_183).is_ok());
    match (shaded(8_184), ctx.loop_budget) {
        (Err(e @ GpuError::LoopBudget { .. }), Some(_)) => {
            let text = e.to_string();
            assert!(
                text.contains("8184 VSGLs") && text.contains("--vsgls"),
                "{text}"
            );
        }
        (Ok(()), None) => {}
        (got, budget) => panic!("with a loop budget {budget:?}: {got:?}"),
    }
}
