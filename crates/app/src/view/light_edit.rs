//! Moving the lights from the panel: the position of point and spot lights, the aim of spot
//! and directional lights (azimuth and elevation in degrees). Every change re-renders the
//! frame from its RSMs on.
use egui::{DragValue, Ui};
use glam::Vec3;
use slc_core::Light;

/// The panel's section for `lights`; `selected` is the light being edited (the session sees
/// the change and renders again).
pub fn show(ui: &mut Ui, lights: &mut [Light], selected: &mut usize, step: f32) {
    if lights.is_empty() {
        ui.label("no lights");
        return;
    }
    *selected = (*selected).min(lights.len() - 1);
    egui::ComboBox::from_label("light")
        .selected_text(label(*selected, &lights[*selected]))
        .show_ui(ui, |ui| {
            for (i, l) in lights.iter().enumerate() {
                ui.selectable_value(selected, i, label(i, l));
            }
        });
    match &mut lights[*selected] {
        Light::Point { position, .. } => edit_position(ui, position, step),
        Light::Spot {
            position,
            direction,
            ..
        } => {
            edit_position(ui, position, step);
            edit_aim(ui, direction);
        }
        Light::Directional { direction, .. } => edit_aim(ui, direction),
    }
}

fn label(i: usize, light: &Light) -> String {
    format!("{} {}", i + 1, light.kind())
}

fn edit_position(ui: &mut Ui, position: &mut Vec3, step: f32) {
    ui.horizontal(|ui| {
        ui.label("position");
        for v in [&mut position.x, &mut position.y, &mut position.z] {
            ui.add(DragValue::new(v).speed(step));
        }
    });
}

/// Edits a unit direction as azimuth (about +y, 0 along -z) and elevation, in degrees.
fn edit_aim(ui: &mut Ui, direction: &mut Vec3) {
    let (mut azimuth, mut elevation) = angles(*direction);
    let changed = ui
        .horizontal(|ui| {
            ui.label("aim");
            let a = ui.add(
                DragValue::new(&mut azimuth)
                    .speed(0.5)
                    .range(-180.0..=180.0)
                    .suffix("° az"),
            );
            let e = ui.add(
                DragValue::new(&mut elevation)
                    .speed(0.5)
                    .range(-89.9..=89.9)
                    .suffix("° el"),
            );
            a.changed() || e.changed()
        })
        .inner;
    if changed {
        *direction = from_angles(azimuth, elevation);
    }
}

/// Azimuth and elevation in degrees of a unit direction.
fn angles(d: Vec3) -> (f32, f32) {
    (
        d.x.atan2(-d.z).to_degrees(),
        d.y.clamp(-1.0, 1.0).asin().to_degrees(),
    )
}

/// The unit direction of an azimuth and elevation in degrees.
fn from_angles(azimuth: f32, elevation: f32) -> Vec3 {
    let (a, e) = (azimuth.to_radians(), elevation.to_radians());
    Vec3::new(a.sin() * e.cos(), e.sin(), -a.cos() * e.cos())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_round_trip() {
        for d in [
            Vec3::new(0.3, -0.8, 0.2),
            Vec3::new(-0.5, 0.1, 0.9),
            Vec3::NEG_Z,
        ] {
            let d = d.normalize();
            let (a, e) = angles(d);
            assert!((from_angles(a, e) - d).length() < 1e-5, "{d}");
        }
    }
}
