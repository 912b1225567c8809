//! The side panel: the render controls, the lights, per-pass times and lights per pixel,
//! and the screenshot and save buttons.
use super::controls::{value_name, Controls, Layer, Overlay};
use super::frame::ViewFrame;
use super::light_edit;
use crate::args::{Lobes, Shader};
use egui::{DragValue, Grid, Slider, Ui};
use slc_core::{Capabilities, Light, Strategy};

/// RSM sizes the panel offers (texels per face side).
const RSM_SIZES: [u32; 6] = [16, 32, 64, 128, 256, 512];

/// What the panel shows besides the controls.
pub struct PanelInfo<'a> {
    pub scene: &'a str,
    /// Who renders: the GPU adapter, or the CPU and its threads.
    pub adapter: &'a str,
    /// Whether the renderer is a software GPU.
    pub software: bool,
    /// What the renderer runs: the strategies offered.
    pub capabilities: Capabilities,
    pub frame: Option<&'a ViewFrame>,
    /// Wall-clock milliseconds of the view's own work in the last frame (picture upload,
    /// egui, blit, present).
    pub display_ms: f64,
    /// Why the overlay asked for is not shown, if it is not.
    pub note: Option<&'a str>,
    /// The last message: a saved file or an error.
    pub status: &'a str,
    /// The fly camera's speed (m/s) and a step for dragging light positions.
    pub speed: f32,
}

/// What the user asked for in the panel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Actions {
    pub screenshot: bool,
    pub save_settings: bool,
    pub reset_camera: bool,
}

/// Shows the panel's contents in `ui`.
pub fn show(
    ui: &mut Ui,
    controls: &mut Controls,
    lights: &mut [Light],
    selected_light: &mut usize,
    info: &PanelInfo,
) -> Actions {
    let mut actions = Actions::default();
    ui.heading(info.scene);
    ui.label(info.adapter);
    if info.software {
        ui.colored_label(
            egui::Color32::YELLOW,
            "software rasterizer: times say nothing about a GPU",
        );
    }
    ui.horizontal(|ui| {
        actions.screenshot = ui.button("screenshot (P)").clicked();
        actions.save_settings = ui.button("save settings (K)").clicked();
    });
    if !info.status.is_empty() {
        ui.label(info.status);
    }
    ui.separator();
    render_controls(ui, controls, &info.capabilities);
    ui.separator();
    show_controls(ui, controls);
    if let Some(note) = info.note {
        ui.label(note);
    }
    ui.separator();
    light_edit::show(ui, lights, selected_light, 0.02 * info.speed);
    ui.horizontal(|ui| {
        actions.reset_camera = ui.button("reset camera (R)").clicked();
        ui.label(format!("speed {:.2} m/s (wheel)", info.speed));
    });
    ui.separator();
    if let Some(frame) = info.frame {
        timings(ui, frame, info.display_ms);
        lights_per_pixel(ui, frame);
    }
    actions
}

/// Strategy, δ, K, RSM size, shader and N, lobes, denoise.
fn render_controls(ui: &mut Ui, c: &mut Controls, capabilities: &Capabilities) {
    ui.horizontal(|ui| {
        ui.radio_value(&mut c.shader, Shader::Vpl, "VPL");
        ui.radio_value(&mut c.shader, Shader::Vsgl, "VSGL");
    });
    match c.shader {
        Shader::Vpl => {
            let current = c.strategy().map_or("?", Strategy::name);
            egui::ComboBox::from_label("strategy")
                .selected_text(current)
                .show_ui(ui, |ui| {
                    for s in Strategy::every().filter(|&s| capabilities.runs(s)) {
                        if ui.selectable_label(current == s.name(), s.name()).clicked() {
                            c.estimate.culling = s.name().to_string();
                        }
                    }
                });
            ui.add(
                Slider::new(&mut c.estimate.delta, 1e-6..=1.0)
                    .logarithmic(true)
                    .text("δ"),
            );
            ui.add(Slider::new(&mut c.pipeline.interleave, 1..=16).text("K (K×K interleave)"));
            let mut denoise = !c.pipeline.no_denoise;
            if ui.checkbox(&mut denoise, "denoise").changed() {
                c.pipeline.no_denoise = !denoise;
            }
        }
        Shader::Vsgl => {
            ui.add(
                Slider::new(&mut c.estimate.vsgls, 1..=65536)
                    .logarithmic(true)
                    .text("N (VSGLs)"),
            );
        }
    }
    egui::ComboBox::from_label("RSM size")
        .selected_text(c.rsm.to_string())
        .show_ui(ui, |ui| {
            for r in RSM_SIZES {
                ui.selectable_value(&mut c.rsm, r, r.to_string());
            }
        });
    ui.horizontal(|ui| {
        ui.label("lobes");
        for l in [Lobes::Both, Lobes::Diffuse, Lobes::Glossy] {
            ui.radio_value(&mut c.lobes, l, value_name(l));
        }
    });
}

/// Layer, exposure, overlay.
fn show_controls(ui: &mut Ui, c: &mut Controls) {
    ui.horizontal(|ui| {
        for l in [Layer::Direct, Layer::Indirect, Layer::Total] {
            ui.radio_value(&mut c.layer, l, value_name(l));
        }
    });
    ui.add(Slider::new(&mut c.exposure, -8.0..=8.0).text("exposure (stops)"));
    ui.horizontal(|ui| {
        ui.label("overlay");
        for o in [Overlay::None, Overlay::Heatmap, Overlay::Grid] {
            ui.radio_value(&mut c.overlay, o, value_name(o));
        }
    });
    ui.horizontal(|ui| {
        ui.checkbox(&mut c.measure, "measure lights/pixel");
        ui.add(
            DragValue::new(&mut c.heat_max)
                .range(1..=1 << 20)
                .prefix("heat max "),
        );
    });
}

/// Per-pass milliseconds, labelled with how they were measured.
fn timings(ui: &mut Ui, frame: &ViewFrame, display_ms: f64) {
    ui.label(format!("ms per pass ({})", frame.clock.label()));
    Grid::new("timings").striped(true).show(ui, |ui| {
        for (name, ms) in &frame.timings.0 {
            ui.label(*name);
            ui.label(format!("{ms:.2}"));
            ui.end_row();
        }
        ui.strong("frame");
        ui.strong(format!("{:.2}", frame.timings.total()));
        ui.end_row();
        ui.label("whole frame (wall clock)");
        ui.label(format!("{:.2}", frame.render_ms));
        ui.end_row();
        ui.label("display (wall clock)");
        ui.label(format!("{display_ms:.2}"));
        ui.end_row();
    });
}

fn lights_per_pixel(ui: &mut Ui, frame: &ViewFrame) {
    let lights = match frame.sampled_lights {
        Some(n) => format!("{n} VSGLs shaded at every pixel"),
        None => format!("{} VPLs", frame.vpl_count),
    };
    ui.label(lights);
    match &frame.metrics {
        Some(m) => ui.label(format!(
            "lights/pixel {:.1}, FDR {:.3}",
            m.lights_per_pixel_mean, m.false_discovery_rate
        )),
        None => ui.label("lights/pixel: not measured (tick 'measure' or the heat map)"),
    };
}
