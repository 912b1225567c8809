//! `slc`: single-bounce global illumination with many virtual point lights.
mod args;
mod backend;
mod bench_cmd;
mod ceiling;
mod compare_cmd;
mod compare_summary;
mod figure;
mod flip;
mod heatmap;
mod page;
mod pdf;
mod plot;
mod print;
mod render_cmd;
mod sampled;
mod scaling;
mod sweep_cmd;
mod table;
#[cfg(feature = "view")]
mod view;
mod vsgl_sweep;

use clap::{Parser, Subcommand};
// Shared with the Python package (`slc_app`), named here as the command's own modules.
use slc_app::{layers_exr, output};

#[derive(Parser)]
#[command(
    name = "slc",
    version,
    about = "Stochastic light culling for VPLs on GGX microsurfaces: render, compare, sweep, bench"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene: direct, indirect and total images (EXR + PNG) and report.json.
    Render(render_cmd::RenderArgs),
    /// Every culling strategy on the same VPLs: images, heat maps, report.md, side-by-side.
    Compare(compare_cmd::CompareArgs),
    /// Speed against accuracy over δ per strategy (CSV, SVG plot, equal-time comparison), or
    /// with --shader vsgl error against light count for VSGLs and equal-count VPLs.
    Sweep(sweep_cmd::SweepArgs),
    /// Per-pass times over resolutions and VPL counts for each strategy: bench.md, bench.csv,
    /// and culling and shading against the VPL count with each strategy's slope (scaling_*.svg).
    Bench(bench_cmd::BenchArgs),
    /// An interactive window on the GPU renderer: fly camera, movable lights, render controls,
    /// overlays (heat map, tile grid), per-pass times; screenshots and settings (.toml).
    #[cfg(feature = "view")]
    View(view::ViewArgs),
}

fn main() {
    slc_app::provenance::start();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render_cmd::run(&args),
        Command::Compare(args) => compare_cmd::run(&args),
        Command::Sweep(args) => sweep_cmd::run(&args),
        Command::Bench(args) => bench_cmd::run(&args),
        #[cfg(feature = "view")]
        Command::View(args) => view::run(&args),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
