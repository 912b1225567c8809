//! A camera and a light as the tables of a settings file (`[camera]`, `[[lights]]`), both
//! ways: a front end that sets them from its own data (the Python package's dicts) gets the
//! settings file's keys, defaults and checks, and shows them in the same form.
//!
//! ```
//! use slc_core::settings_tables::{light_from_table, light_table};
//!
//! let table: toml::Table = toml::from_str(
//!     "type = \"spot\"\nposition = [0, 2, 0]\ntarget = [0, 0, 0]\nintensity = 10\n",
//! )?;
//! let light = light_from_table(table)?;
//! assert_eq!(light_table(&light)["outer_cone_deg"].as_float(), Some(45.0));
//! let typo: toml::Table = toml::from_str("type = \"point\"\nposition = [0, 1, 0]\nintensty = 1")?;
//! assert!(light_from_table(typo).unwrap_err().contains("intensty"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
use crate::camera::Camera;
use crate::light::Light;
use crate::settings::{RawCamera, RawLight};
use glam::Vec3;
use serde::Deserialize;
use toml::{Table, Value};

/// A camera from the keys of a settings file's `[camera]` table, checked as there.
pub fn camera_from_table(table: Table) -> Result<Camera, String> {
    RawCamera::deserialize(Value::Table(table))
        .map_err(one_line)?
        .validate()
}

/// A light from the keys of a settings file's `[[lights]]` table, checked as there.
pub fn light_from_table(table: Table) -> Result<Light, String> {
    RawLight::deserialize(Value::Table(table))
        .map_err(one_line)?
        .validate()
}

/// A deserialization error as one line.
fn one_line(e: toml::de::Error) -> String {
    e.to_string()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// `camera` as a `[camera]` table (`target` one unit ahead), which
/// [`camera_from_table`] reads back to the same camera up to rounding.
pub fn camera_table(camera: &Camera) -> Table {
    Table::from_iter([
        ("position".into(), vec3(camera.position)),
        ("target".into(), vec3(camera.position + camera.forward)),
        ("up".into(), vec3(camera.up)),
        ("yfov_deg".into(), float(degrees(camera.yfov))),
        ("znear".into(), float(camera.znear)),
        ("zfar".into(), float(camera.zfar)),
    ])
}

/// `light` as a `[[lights]]` table (a spot light by its direction), which
/// [`light_from_table`] reads back to the same light up to rounding.
pub fn light_table(light: &Light) -> Table {
    let kind = |name: &str| ("type".to_string(), Value::String(name.into()));
    match light {
        Light::Point {
            position,
            intensity,
        } => Table::from_iter([
            kind("point"),
            ("position".into(), vec3(*position)),
            ("intensity".into(), vec3(*intensity)),
        ]),
        Light::Spot {
            position,
            direction,
            intensity,
            inner_cone_angle,
            outer_cone_angle,
        } => {
            let outer = degrees(*outer_cone_angle).min(90.0);
            Table::from_iter([
                kind("spot"),
                ("position".into(), vec3(*position)),
                ("direction".into(), vec3(*direction)),
                ("intensity".into(), vec3(*intensity)),
                (
                    "inner_cone_deg".into(),
                    float(degrees(*inner_cone_angle).min(outer)),
                ),
                ("outer_cone_deg".into(), float(outer)),
            ])
        }
        Light::Directional {
            direction,
            irradiance,
        } => Table::from_iter([
            kind("directional"),
            ("direction".into(), vec3(*direction)),
            ("irradiance".into(), vec3(*irradiance)),
        ]),
    }
}

/// `v` as the shortest decimal that reads back to it (0.1, not 0.10000000149011612).
fn float(v: f32) -> Value {
    Value::Float(v.to_string().parse().unwrap_or(f64::from(v)))
}

/// Radians as degrees, rounded to f32 (30, not 30.000002).
fn degrees(radians: f32) -> f32 {
    f64::from(radians).to_degrees() as f32
}

fn vec3(v: Vec3) -> Value {
    Value::Array(v.to_array().map(float).to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> Table {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn tables_read_back_to_the_same_camera_and_lights() {
        let camera = camera_from_table(table(
            "position = [1, 2, 3]\ntarget = [0, 1, -1]\nyfov_deg = 40\nzfar = 50",
        ))
        .unwrap();
        let back = camera_from_table(camera_table(&camera)).unwrap();
        assert!(back.position.abs_diff_eq(camera.position, 1e-6));
        assert!(back.forward.abs_diff_eq(camera.forward, 1e-6));
        assert!(back.up.abs_diff_eq(camera.up, 1e-6));
        assert!((back.yfov - camera.yfov).abs() < 1e-6);
        assert_eq!((back.znear, back.zfar), (0.01, 50.0));
        for text in [
            "type = \"point\"\nposition = [0, 1, 0]\nintensity = [1, 2, 3]",
            "type = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 1]\nintensity = 4\n\
             inner_cone_deg = 10\nouter_cone_deg = 30",
            "type = \"directional\"\ndirection = [1, -1, 0]\nirradiance = 2",
        ] {
            let light = light_from_table(table(text)).unwrap();
            let back = light_from_table(light_table(&light)).unwrap();
            let (a, b) = (light_table(&light), light_table(&back));
            assert_eq!(
                a.keys().collect::<Vec<_>>(),
                b.keys().collect::<Vec<_>>(),
                "{text}"
            );
            assert_eq!(a["type"], b["type"]);
            let close = numbers(&a)
                .iter()
                .zip(numbers(&b))
                .all(|(x, y)| (x - y).abs() <= 1e-5 * x.abs().max(1.0));
            assert!(close, "{text}: {a} against {b}");
        }
    }

    /// Every number of a table, in key order.
    fn numbers(t: &Table) -> Vec<f64> {
        t.values()
            .flat_map(|v| match v {
                Value::Float(f) => vec![*f],
                Value::Array(a) => a.iter().filter_map(Value::as_float).collect(),
                _ => Vec::new(),
            })
            .collect()
    }

    #[test]
    fn the_settings_file_checks_apply() {
        let e = camera_from_table(table(
            "position = [0, 0, 0]\ntarget = [0, 0, 0]\nyfov_deg = 40",
        ))
        .unwrap_err();
        assert!(e.contains("target equals position"), "{e}");
        let e = camera_from_table(table(
            "position = [0, 0, 1]\ntarget = [0, 0, 0]\nyfov_deg = 180",
        ))
        .unwrap_err();
        assert!(e.contains("yfov_deg 180"), "{e}");
        let e = light_from_table(table(
            "type = \"spot\"\nposition = [0, 1, 0]\nintensity = 1",
        ))
        .unwrap_err();
        assert!(e.contains("exactly one of direction and target"), "{e}");
        let e = light_from_table(table(
            "type = \"point\"\nposition = [0, 1, 0]\nintensity = -1",
        ))
        .unwrap_err();
        assert!(e.contains("intensity"), "{e}");
        let e = light_from_table(table("type = \"area\"\nposition = [0, 1, 0]")).unwrap_err();
        assert!(e.contains("area"), "{e}");
        let e = light_from_table(table(
            "type = \"point\"\nposition = [0, nan, 0]\nintensity = 1",
        ))
        .unwrap_err();
        assert!(e.contains("not finite"), "{e}");
    }
}
