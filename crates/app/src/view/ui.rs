//! One frame of the window's contents in egui: the side panel and the picture with its
//! overlay, drawn from the session.
use super::display::Paint;
use super::overlay;
use super::panel::{self, Actions, PanelInfo};
use super::session::Session;
use super::window::{Running, PANEL_WIDTH};

impl Running {
    /// The picture's rectangle in window pixels: left, top, right, bottom.
    pub fn picture_rect_px(&self) -> [f64; 4] {
        let ppp = f64::from(self.egui.pixels_per_point());
        let r = self.picture_rect;
        [r.left(), r.top(), r.right(), r.bottom()].map(|v| f64::from(v) * ppp)
    }

    /// Makes the picture again if the frame or how it is shown changed.
    pub fn update_picture(&mut self, s: &Session) {
        let Some(frame) = &s.frame else {
            return;
        };
        let c = &s.controls;
        let key = (
            s.generation,
            format!(
                "{:?} {} {:?} {}",
                c.layer, c.exposure, c.overlay, c.heat_max
            ),
        );
        if self.picture_key.as_ref() == Some(&key) {
            return;
        }
        let (rgb, note) = overlay::picture(frame, c);
        let size = [rgb.width() as usize, rgb.height() as usize];
        let image = egui::ColorImage::from_rgb(size, rgb.as_raw());
        let options = egui::TextureOptions::NEAREST;
        match &mut self.texture {
            Some(t) => t.set(image, options),
            None => self.texture = Some(self.egui.load_texture("frame", image, options)),
        }
        self.note = note;
        self.picture_key = Some(key);
    }

    /// The panel and the picture for this frame: what the panel asked for and what to draw.
    pub fn run_ui(&mut self, s: &mut Session) -> (Actions, Paint) {
        let raw = self.egui_state.take_egui_input(&self.window);
        let adapter = self.renderer.renderer_label();
        let info = PanelInfo {
            scene: &s.scene.name,
            adapter: &adapter,
            software: self.renderer.software_gpu(),
            capabilities: self.renderer.capabilities(),
            frame: s.frame.as_ref(),
            display_ms: self.display_ms,
            note: self.note,
            status: &s.status,
            speed: s.fly.speed,
        };
        let mut actions = Actions::default();
        let mut picture_rect = self.picture_rect;
        let ppp = self.egui.pixels_per_point();
        let (controls, lights, selected) =
            (&mut s.controls, &mut s.scene.lights, &mut s.selected_light);
        let output = self.egui.run_ui(raw, |ui| {
            egui::Panel::right("panel")
                .resizable(false)
                .exact_size(PANEL_WIDTH as f32 / ppp)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        actions = panel::show(ui, controls, lights, selected, &info);
                    });
                });
            egui::CentralPanel::no_frame().show(ui, |ui| {
                let area = ui.max_rect();
                let size = egui::vec2(s.width as f32, s.height as f32) / ppp;
                let scale = (area.width() / size.x).min(area.height() / size.y).min(1.0);
                let rect = egui::Rect::from_center_size(area.center(), size * scale);
                if let Some(t) = &self.texture {
                    let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
                    ui.painter().image(t.id(), rect, uv, egui::Color32::WHITE);
                }
                overlay::paint(ui.painter(), rect, s.width, controls);
                picture_rect = rect;
            });
        });
        self.picture_rect = picture_rect;
        self.egui_state
            .handle_platform_output(&self.window, output.platform_output);
        let paint = Paint {
            jobs: self.egui.tessellate(output.shapes, output.pixels_per_point),
            textures: output.textures_delta,
            pixels_per_point: output.pixels_per_point,
        };
        (actions, paint)
    }
}
