//! Agreement with Mitsuba 3 on anisotropic GGX (glTF `KHR_materials_anisotropy`):
//! - pointwise: `scenes/anisotropy/reference/brdf_table.json` holds f(ωi, ωo) cos θo from
//!   Mitsuba's own anisotropic GGX and separable Smith G (`tools/mitsuba/brdf_table.py`) for
//!   five (α, α_t, rotation), rotations of both signs, in Mitsuba's shading frame
//!   (s = +x, t = n × s = +y, n = +z); slc's BRDF with the tangent cos(rot) s + sin(rot) t
//!   must give the same values;
//! - rendered: `scenes/anisotropy/reference` holds 32768-spp direct and one-bounce indirect
//!   images of `scenes/anisotropy/anisotropy.gltf` (a brushed floor whose tangents slc must
//!   generate, a brushed panel with stored tangents and its anisotropy rotated by 0.7 rad).
//!   A lobe turned by 90°, a rotation of the wrong sign, or α_t and α swapped fails them;
//!   how "within noise" is tested: `mitsuba/mod.rs`.
mod mitsuba;

use glam::Vec3;
use mitsuba::{assert_agrees, render_pair};
use slc_bounds::{Anisotropy, Brdf, Fresnel};
use slc_core::frame::Method;
use std::path::{Path, PathBuf};

fn scene_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/anisotropy")
}

fn vec3(v: &serde_json::Value) -> Vec3 {
    let c = |i: usize| v[i].as_f64().unwrap() as f32;
    Vec3::new(c(0), c(1), c(2))
}

#[test]
fn brdf_matches_mitsubas_anisotropic_ggx() {
    let path = scene_dir().join("reference/brdf_table.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let table: serde_json::Value = serde_json::from_str(&text).unwrap();
    let rows = table["rows"].as_array().unwrap();
    assert!(rows.len() >= 300);
    let mut worst = 0.0f64;
    let mut turned_worst = 0.0f64;
    for row in rows {
        let get = |k: &str| row[k].as_f64().unwrap() as f32;
        let (wi, wo) = (vec3(&row["wi"]), vec3(&row["wo"]));
        let rotation = get("rotation");
        let brdf = |rotation: f32| Brdf {
            kd: Vec3::ZERO,
            fresnel: Fresnel::Schlick(Vec3::ONE),
            alpha: get("alpha"),
            anisotropy: Some(Anisotropy {
                tangent: Vec3::new(rotation.cos(), rotation.sin(), 0.0),
                alpha_t: get("alpha_t"),
            }),
        };
        let want = row["f_cos"].as_f64().unwrap();
        let ours = f64::from(brdf(rotation).eval(Vec3::Z, wi, wo).x * wo.z);
        let error = (ours - want).abs() / want.max(1e-3);
        assert!(
            error < 1e-4,
            "{row}: slc {ours} vs Mitsuba {want} (relative {error:e})"
        );
        worst = worst.max(error);
        // The opposite rotation is a different lobe wherever it is anisotropic.
        let turned = f64::from(brdf(-rotation).eval(Vec3::Z, wi, wo).x * wo.z);
        turned_worst = turned_worst.max((turned - want).abs() / want.max(1e-3));
    }
    println!("largest relative difference {worst:e}; with the rotation negated {turned_worst:e}");
    assert!(turned_worst > 0.1, "the table must see the rotation's sign");
}

#[test]
fn path_reference_agrees_with_mitsuba() {
    let dir = scene_dir();
    let pairs = render_pair(&dir.join("anisotropy.gltf"), Method::Path, true, 128, 1, 64);
    assert_agrees("path", pairs, &dir.join("reference"), 1, 0.01);
}

#[test]
fn vpl_reference_with_visibility_agrees_with_mitsuba() {
    let dir = scene_dir();
    let pairs = render_pair(
        &dir.join("anisotropy.gltf"),
        Method::VplReference,
        true,
        128,
        24,
        8,
    );
    assert_agrees("vpl", pairs, &dir.join("reference"), 1, 0.02);
}
