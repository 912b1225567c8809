//! Times every pass of the CPU frame, frame after frame, in one process (the loop `slc
//! bench` runs, without the command around it): `cargo run --release -p slc-cpu-ref
//! --example frame_passes -- SCENE WIDTH HEIGHT RSM FRAMES [OUT.exr-less prefix]`.
//! Prints each pass's median milliseconds over the frames after the first.
use slc_core::frame::{LobeSelection, Method, RenderSettings, Stochastic};
use slc_core::{load_scene, Renderer};
use slc_cpu_ref::CpuRenderer;
use std::collections::BTreeMap;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.into());
    let scene = load_scene(arg(0, "default"))?;
    let settings = RenderSettings {
        width: arg(1, "1920").parse()?,
        height: arg(2, "1080").parse()?,
        rsm_resolution: arg(3, "256").parse()?,
        seed: 0,
        method: Method::Stochastic(Stochastic::PAPER),
        visibility: false,
        spp: 1,
        lobes: LobeSelection::Glossy,
    };
    let frames: usize = arg(4, "4").parse()?;
    let renderer = CpuRenderer::default();
    let loaded = renderer.load(&scene)?;
    let mut times: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    for f in 0..frames {
        let frame = slc_core::render_loaded(&renderer, &scene, &loaded, &settings, &|_| {})?;
        if f == 0 && frames > 1 {
            continue;
        }
        for &(name, ms) in &frame.timings.0 {
            times.entry(name).or_default().push(ms);
        }
        times
            .entry("frame")
            .or_default()
            .push(frame.timings.total());
    }
    for (name, mut v) in times {
        v.sort_by(f64::total_cmp);
        println!(
            "{name:<16} {:>9.1}  ({:.1}-{:.1})",
            v[v.len() / 2],
            v[0],
            v[v.len() - 1]
        );
    }
    Ok(())
}
