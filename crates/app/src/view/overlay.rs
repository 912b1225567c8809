//! What the viewport shows: the chosen layer as sRGB, or the heat map of lights per pixel
//! and FDR (the paper's Fig. 9) with its colour bar, or the tile grid drawn over the picture.
use super::controls::{Controls, Layer, Overlay};
use super::frame::ViewFrame;
use crate::heatmap::{heat_colour, heat_map};
use crate::output::to_srgb8;
use egui::{Align2, Color32, FontId, Painter, Pos2, Rect, Stroke};
use image::RgbImage;
use slc_core::culling::TILE_SIZE;
use slc_core::Layout;

/// The picture of `frame` as `controls` show it, with a note where the overlay asked for is
/// not available.
pub fn picture(frame: &ViewFrame, controls: &Controls) -> (RgbImage, Option<&'static str>) {
    if controls.overlay == Overlay::Heatmap {
        match &frame.metrics {
            Some(m) => {
                let (w, h) = (frame.direct.width, frame.direct.height);
                let heat = heat_map(
                    w,
                    h,
                    &m.lights_per_pixel,
                    &m.fdr_per_pixel,
                    controls.heat_max,
                );
                return (heat, None);
            }
            None => return (layer(frame, controls), Some("heat map: VPL shader only")),
        }
    }
    (layer(frame, controls), None)
}

fn layer(frame: &ViewFrame, controls: &Controls) -> RgbImage {
    let image = match controls.layer {
        Layer::Direct => &frame.direct,
        Layer::Indirect => &frame.indirect,
        Layer::Total => &frame.direct.add(&frame.indirect),
    };
    to_srgb8(image, controls.exposure)
}

/// Draws the overlay's marks over the picture shown in `rect` (of a `width` x `height`
/// frame): the colour bar of the heat map, or the tile grid.
pub fn paint(painter: &Painter, rect: Rect, width: u32, controls: &Controls) {
    match controls.overlay {
        Overlay::Heatmap if controls.measures() => colour_bar(painter, rect, controls.heat_max),
        Overlay::Grid => {
            let k = controls.pipeline.interleave.max(1);
            grid(painter, rect, width, TILE_SIZE * k);
            let layout = controls.strategy().map(|s| s.parts().0);
            let what = match layout {
                Ok(Layout::Clustered | Layout::ClusteredRaster) => {
                    ", each cut into 32 depth slices (not drawn)"
                }
                Ok(Layout::Splatting) => " (splatting draws meshes, not tiles)",
                Ok(Layout::Unculled) => " (strategy none culls no tiles)",
                _ => "",
            };
            let label = format!("cells of {k}×{k} interleaved 16×16 tiles{what}");
            painter.text(
                rect.left_top() + egui::vec2(4.0, 4.0),
                Align2::LEFT_TOP,
                label,
                FontId::proportional(11.0),
                Color32::YELLOW,
            );
        }
        _ => {}
    }
}

/// Lines every `cell` pixels of a `width`-pixel frame shown in `rect`.
fn grid(painter: &Painter, rect: Rect, width: u32, cell: u32) {
    let step = rect.width() * cell as f32 / width.max(1) as f32;
    let stroke = Stroke::new(1.0, Color32::from_rgba_unmultiplied(255, 255, 0, 110));
    let mut x = rect.left() + step;
    while x < rect.right() {
        painter.vline(x, rect.y_range(), stroke);
        x += step;
    }
    let mut y = rect.top() + step;
    while y < rect.bottom() {
        painter.hline(rect.x_range(), y, stroke);
        y += step;
    }
}

/// The heat map's legend along the bottom of `rect`: hue is the FDR from 0 (blue) to 1
/// (red), brightness rises to full at `max_lights` lights per pixel.
fn colour_bar(painter: &Painter, rect: Rect, max_lights: u32) {
    let bar = Rect::from_min_max(
        Pos2::new(rect.left() + 8.0, rect.bottom() - 26.0),
        Pos2::new(rect.right() - 8.0, rect.bottom() - 14.0),
    );
    painter.rect_filled(bar.expand(2.0), 2.0, Color32::from_black_alpha(200));
    let steps = 64;
    for i in 0..steps {
        let t = i as f32 / (steps - 1) as f32;
        let c = heat_colour(max_lights, t, max_lights).0;
        let x0 = bar.left() + bar.width() * i as f32 / steps as f32;
        let x1 = bar.left() + bar.width() * (i + 1) as f32 / steps as f32;
        let cell = Rect::from_min_max(Pos2::new(x0, bar.top()), Pos2::new(x1, bar.bottom()));
        painter.rect_filled(cell, 0.0, Color32::from_rgb(c[0], c[1], c[2]));
    }
    let font = FontId::proportional(11.0);
    let text = Color32::WHITE;
    let above = bar.top() - 2.0;
    painter.text(
        Pos2::new(bar.left(), above),
        Align2::LEFT_BOTTOM,
        "FDR 0",
        font.clone(),
        text,
    );
    painter.text(
        Pos2::new(bar.right(), above),
        Align2::RIGHT_BOTTOM,
        "1",
        font.clone(),
        text,
    );
    painter.text(
        Pos2::new(bar.center().x, above),
        Align2::CENTER_BOTTOM,
        format!("brightness: lights/pixel, full at {max_lights}"),
        font,
        text,
    );
}
