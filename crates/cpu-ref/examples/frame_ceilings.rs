//! The CPU frame's passes against their own ceilings (docs/cpu-frame.md): primary rays per
//! second of the G-buffer against obvhs's own traversal of the same rays (its closest-hit
//! `ray_traverse` with its own Möller-Trumbore triangle test, no surface), and the filter's
//! taps per second on the frame against the same kernel on an image that stays in cache.
//!
//! `cargo run --release -p slc-cpu-ref --example frame_ceilings -- SCENE WIDTH HEIGHT ROUNDS`
use glam::Vec3A;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use rayon::prelude::*;
use slc_core::{load_scene, Image};
use slc_cpu_ref::denoise::{BilateralParams, CrossBilateral};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample, PrimaryRays};
use slc_cpu_ref::tracer::Rays8;
use slc_cpu_ref::Tracer;
use std::time::{Duration, Instant};

/// The shortest of `rounds` timings of `f`, after one warm-up.
fn best<T>(rounds: usize, mut f: impl FnMut() -> T) -> f64 {
    f();
    (0..rounds)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(f());
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.into());
    let scene = load_scene(arg(0, "default"))?;
    let (w, h): (u32, u32) = (arg(1, "1920").parse()?, arg(2, "1080").parse()?);
    let rounds: usize = arg(3, "3").parse()?;
    let camera = scene.camera_or_default();
    let tracer = Tracer::new(&scene);
    let primary = PrimaryRays::new(&camera, w, h);
    let dirs: Vec<Vec3A> = (0..w * h)
        .map(|p| primary.direction(p % w, p / w, 0.5, 0.5).into())
        .collect();
    let rays = (w * h) as f64;
    let threads = rayon::current_num_threads();
    println!(
        "{} at {w}x{h}, {threads} threads, best of {rounds}",
        scene.name
    );

    // obvhs alone: its BVH of the same triangles, its own triangle test, closest hits.
    let tris: Vec<Triangle> = scene
        .meshes
        .iter()
        .flat_map(|m| {
            m.triangles.iter().map(|t| {
                let [v0, v1, v2] = t.map(|i| Vec3A::from(m.positions[i as usize]));
                Triangle { v0, v1, v2 }
            })
        })
        .collect();
    let bvh = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    let origin: Vec3A = camera.position.into();
    let obvhs = best(rounds, || {
        dirs.par_iter()
            .map(|&d| {
                let mut hit = RayHit::none();
                bvh.ray_traverse(Ray::new_inf(origin, d), &mut hit, |r, id| {
                    tris[bvh.primitive_indices[id] as usize].intersect(r)
                });
                hit.t
            })
            .sum::<f32>()
    });
    // slc's watertight tracer, ray by ray and in packets of 4x2 pixels, hits only.
    let alone = best(rounds, || {
        dirs.par_iter()
            .map(|&d| {
                tracer
                    .closest(camera.position, d.into(), 0.0, f32::INFINITY)
                    .map_or(0.0, |h| h.0)
            })
            .sum::<f32>()
    });
    let packets = best(rounds, || {
        (0..h / 2)
            .into_par_iter()
            .map(|jb| {
                let mut sum = 0.0;
                for i0 in (0..w - w % 4).step_by(4) {
                    let mut r = Rays8 {
                        used: 0xff,
                        ..Rays8::default()
                    };
                    for l in 0..8 {
                        r.origin[l] = camera.position;
                        r.dir[l] =
                            dirs[((2 * jb + l as u32 / 4) * w + i0 + l as u32 % 4) as usize].into();
                    }
                    sum += tracer
                        .closest8(&r)
                        .iter()
                        .flatten()
                        .map(|h| h.0)
                        .sum::<f32>();
                }
                sum
            })
            .sum::<f32>()
    });
    let gbuffer = best(rounds, || {
        trace_gbuffer(&scene, &tracer, &camera, w, h, PixelSample::Centre)
    });
    let mrays = |s: f64| rays / s / 1e6;
    println!("primary rays, M rays/s (ms):");
    println!(
        "  obvhs ray_traverse, its own triangle test: {:8.1} ({:.1})",
        mrays(obvhs),
        obvhs * 1e3
    );
    println!(
        "  slc, ray by ray, hits only:                {:8.1} ({:.1})",
        mrays(alone),
        alone * 1e3
    );
    println!(
        "  slc, packets of 4x2, hits only:            {:8.1} ({:.1})",
        mrays(packets),
        packets * 1e3
    );
    println!(
        "  slc G-buffer (packets and surfaces):       {:8.1} ({:.1})",
        mrays(gbuffer),
        gbuffer * 1e3
    );

    // The filter on the frame's G-buffer, and on a small frame cut from it (in cache).
    let g = trace_gbuffer(&scene, &tracer, &camera, w, h, PixelSample::Centre);
    let image = Image {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|p| glam::Vec3::splat((p % 7) as f32))
            .collect(),
    };
    let params = BilateralParams::default();
    let taps_per_pixel = 2 * (2 * params.radius as usize + 1);
    let surfaces = g.samples.iter().flatten().count();
    let mut filter = CrossBilateral::default();
    let frame = best(rounds, || filter.filter(&image, &g, params));
    let (sw, sh) = (64u32.min(w), 32u32.min(h));
    let (x0, y0) = ((w - sw) / 2, (h - sh) / 2);
    let small_g = slc_core::GBuffer {
        width: sw,
        height: sh,
        samples: (0..sw * sh)
            .map(|p| g.samples[((y0 + p / sw) * w + x0 + p % sw) as usize])
            .collect(),
    };
    let small = Image {
        width: sw,
        height: sh,
        pixels: image.pixels[..(sw * sh) as usize].to_vec(),
    };
    let small_surfaces = small_g.samples.iter().flatten().count();
    let repeats = (surfaces / small_surfaces.max(1)).max(1);
    let in_cache = best(rounds, || {
        (0..repeats)
            .into_par_iter()
            .map_init(CrossBilateral::default, |f, _| {
                f.filter(&small, &small_g, params).map(|i| i.pixels.len())
            })
            .count()
    });
    let gtaps = |taps: usize, s: f64| taps as f64 / s / 1e9;
    println!("filter, G taps/s (ms):");
    println!(
        "  the frame ({surfaces} pixels with a surface):   {:8.2} ({:.1})",
        gtaps(surfaces * taps_per_pixel, frame),
        frame * 1e3
    );
    println!(
        "  {sw}x{sh} from its middle, {repeats} times:      {:8.2} ({:.1})",
        gtaps(small_surfaces * taps_per_pixel * repeats, in_cache),
        in_cache * 1e3
    );
    Ok(())
}
