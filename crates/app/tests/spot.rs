//! Spot lights as users set them, on both backends: on its axis a spot of any cone, down to
//! 0.01° (and a hard-edged one), lights a surface exactly as the point light of the same
//! intensity does. The camera looks straight down at a floor through the middle of an odd
//! image, so the middle pixel's surface point lies on the spot's axis; the falloff that clamped
//! `cos θi − cos θo` at 1e-3 gave 0.37 of the point light for 2°, 0.023 for 1° and 0 for 0.01°.
use std::path::Path;

mod common;
use common::{gpu_available, out_dir, read_exr, slc};

/// A floor under a light 1 above its centre, seen from 2 above.
fn scene(dir: &Path, light: &str) -> std::path::PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("floor.obj"),
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 3 2\nf 1 4 3\n",
    )
    .unwrap();
    let toml = dir.join("scene.toml");
    std::fs::write(
        &toml,
        format!(
            "scene = \"floor.obj\"\n[camera]\nposition = [0.0, 2.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\nyfov_deg = 60.0\n[[lights]]\nposition = [0.0, 1.0, 0.0]\nintensity = 2.0\n{light}\n"
        ),
    )
    .unwrap();
    toml
}

/// The direct light of the middle pixel of a 33 x 33 render of `light` on `backend`.
fn middle(dir: &Path, light: &str, backend: &str) -> [f32; 3] {
    let toml = scene(dir, light);
    let out = dir.join("out");
    let o = slc()
        .arg("render")
        .arg(&toml)
        .args([
            "--width",
            "33",
            "--height",
            "33",
            "--rsm",
            "16",
            "--backend",
            backend,
        ])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    read_exr(&out.join("direct.exr"))[16 * 33 + 16]
}

fn check(backend: &str) {
    let dir = out_dir(&format!("spot-{backend}"));
    let point = middle(&dir, "type = \"point\"", backend);
    assert!(point[0] > 0.0, "{point:?}");
    for (inner, outer) in [
        (0.0, 2.0),
        (0.0, 1.0),
        (0.0, 0.01),
        (0.01, 0.01),
        (30.0, 45.0),
    ] {
        let spot = middle(
            &dir,
            &format!("type = \"spot\"\ndirection = [0.0, -1.0, 0.0]\ninner_cone_deg = {inner}\nouter_cone_deg = {outer}"),
            backend,
        );
        for c in 0..3 {
            assert!(
                (spot[c] - point[c]).abs() <= 1e-3 * point[c],
                "{backend}: spot {inner}°..{outer}°: {spot:?}, point {point:?}"
            );
        }
    }
}

#[test]
fn on_its_axis_a_spot_of_any_cone_is_the_point_light_on_the_cpu() {
    check("cpu");
}

#[test]
fn on_its_axis_a_spot_of_any_cone_is_the_point_light_on_the_gpu() {
    if gpu_available() {
        check("gpu");
    }
}
