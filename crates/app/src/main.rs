//! `slc`: single-bounce global illumination with many virtual point lights.
mod output;
mod render_cmd;
mod report;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "slc",
    version,
    about = "Stochastic light culling for VPLs on GGX microsurfaces: render, measure, compare"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene: direct, indirect and total images (EXR + PNG) and report.json.
    Render(render_cmd::RenderArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render_cmd::run(&args),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
