//! Rough culling times of every strategy on the built-in default scene.
//!
//! `cargo run --release -p slc-cull --example timing [WIDTH HEIGHT [RSM]]` (default 512 512
//! 80: 6 x 80² RSM texels, about 65,000 VPLs like the paper's 256² map). Prints the best of
//! five runs per strategy and interleaving factor, with the mean list length per pixel.
use slc_core::frame::LobeSelection;
use slc_core::Strategy;
use slc_core::{builtin, CullInput, Interleaving};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::rsm::{trace_rsm, TexelSample};
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::Tracer;
use slc_cull::culler;
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("WIDTH HEIGHT [RSM] as integers"))
        .collect();
    let (width, height) = (
        args.first().copied().unwrap_or(512),
        args.get(1).copied().unwrap_or(512),
    );
    let rsm = args.get(2).copied().unwrap_or(80);
    let scene = builtin("default").expect("built-in default scene");
    let camera = scene.camera_or_default();
    let tracer = Tracer::new(&scene);
    let gbuffer = trace_gbuffer(&scene, &tracer, &camera, width, height, PixelSample::Centre);
    let maps: Vec<_> = scene
        .lights
        .iter()
        .map(|l| trace_rsm(&scene, &tracer, l, rsm, TexelSample::Centre))
        .collect();
    let vpls = generate_vpls(&maps, 0, LobeSelection::Both);
    println!(
        "default scene {width}x{height}, {} VPLs, delta 1e-3, {} rayon threads",
        vpls.len(),
        rayon::current_num_threads()
    );
    for k in [8, 4, 1] {
        let input = CullInput {
            gbuffer: &gbuffer,
            camera: &camera,
            vpls: &vpls,
            delta: 1e-3,
            interleaving: Interleaving { k, seed: 0 },
        };
        println!(
            "K = {k} ({} VPLs per subregion)",
            vpls.len() / (k * k) as usize
        );
        for name in Strategy::on_cpu() {
            let culler = culler(name);
            let mut best = Duration::MAX;
            let mut lists = None;
            for _ in 0..5 {
                let t = Instant::now();
                lists = Some(culler.cull(&input).expect("culling"));
                best = best.min(t.elapsed());
            }
            let lists = lists.expect("five runs");
            let mean = lists.indices.len() as f64 / lists.len().max(1) as f64;
            let per_pixel = (0..lists.pixel_list.len())
                .map(|p| lists.for_pixel(p).len())
                .sum::<usize>() as f64
                / lists.pixel_list.len() as f64;
            println!(
                "{name:>27}: {:>9.2} ms  {:>6} lists (mean {mean:>7.1})  {per_pixel:>7.1} lights/pixel",
                best.as_secs_f64() * 1e3,
                lists.len()
            );
        }
    }
}
