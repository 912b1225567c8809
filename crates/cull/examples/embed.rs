//! Embedding the CPU culler in an engine: a hand-made G-buffer (a floor seen from above) and
//! hand-made VPLs, no scene loading, culled with every strategy and checked against the
//! brute-force truth.
//!
//! `cargo run --release -p slc-cull --example embed`; `cargo test` runs it too.
use glam::Vec3;
use slc_bounds::{Brdf, Fresnel};
use slc_core::{Camera, CullInput, GBuffer, GSample, Interleaving, Strategy, Vpl, VplLobe};

/// Culls the example frame with every strategy; an error if one misses a contributing pair.
fn run() -> Result<(), Box<dyn std::error::Error>> {
    let camera = Camera::look_at(Vec3::new(0.0, 4.0, 0.0), Vec3::ZERO, Vec3::Z, 1.0)
        .ok_or("degenerate camera")?;
    let floor = Brdf {
        kd: Vec3::splat(0.5),
        fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
        alpha: 0.2,
        anisotropy: None,
    };
    let (w, h) = (64, 48);
    let samples = (0..w * h)
        .map(|p| {
            let dir = camera.ray_direction(p % w, p / w, 0.5, 0.5, w, h);
            let position = camera.position + dir * (camera.position.y / -dir.y);
            Some(GSample {
                position,
                normal: Vec3::Y,
                geometric_normal: Vec3::Y,
                omega_o: -dir,
                depth: camera.view_depth(position),
                brdf: floor,
            })
        })
        .collect();
    let gbuffer = GBuffer {
        width: w,
        height: h,
        samples,
    };
    // A grid of VPLs half a unit above the floor, facing it (a lit ceiling patch, ωi towards
    // a light below it): every other one glossy; ξ spread over (0, 1).
    let vpls: Vec<Vpl> = (0..256u32)
        .map(|id| {
            let (i, j) = ((id % 16) as f32, (id / 16) as f32);
            let glossy = id % 2 == 1;
            Vpl {
                position: Vec3::new(i * 0.4 - 3.0, 0.5, j * 0.4 - 3.0),
                normal: Vec3::NEG_Y,
                geometric_normal: Vec3::NEG_Y,
                omega_i: Vec3::new(0.3, -1.0, 0.1).normalize(),
                flux: Vec3::splat(0.02),
                brdf: Brdf {
                    alpha: 0.1,
                    ..floor
                },
                lobe: if glossy {
                    VplLobe::Glossy
                } else {
                    VplLobe::Diffuse
                },
                id,
                xi: (id as f32 + 0.5) / 256.0,
            }
        })
        .collect();
    let input = CullInput {
        gbuffer: &gbuffer,
        camera: &camera,
        vpls: &vpls,
        delta: 1e-3,
        interleaving: Interleaving { k: 2, seed: 0 },
    };
    for strategy in Strategy::on_cpu() {
        let lists = slc_cull::culler(strategy).cull(&input)?;
        let m = slc_cull::metrics::measure(&input, &lists)?;
        println!(
            "{strategy:>27}: {:6.2} lights/pixel, {:6} true and {:7} false positives, {} missed",
            m.lights_per_pixel_mean, m.true_positive_pairs, m.false_positive_pairs, m.missed_pairs
        );
        if m.missed_pairs != 0 {
            return Err(format!("{strategy} missed {} contributing pairs", m.missed_pairs).into());
        }
        if m.true_positive_pairs == 0 {
            return Err(
                format!("{strategy}: no VPL contributes; the example frame is wrong").into(),
            );
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_example_culls_with_every_strategy_and_misses_nothing() {
        super::run().unwrap();
    }
}
