//! Labelled figures of images, as standalone SVG: a title, one labelled column per variant
//! (strategy, δ…), one labelled row per kind of image (total, heat map, error map), and, where
//! heat maps are shown, their legend: the two variables of the paper's Fig. 9 (brightness =
//! VPLs per pixel, hue = false discovery rate) as a colour field with axes, drawn by `plotters`.
//! The images are embedded as base64 PNG, so the file can be moved, mailed or put in a paper
//! on its own.
use crate::heatmap::heat_colour;
use crate::plot::{draw_error, tick_label};
use base64::Engine as _;
use image::codecs::png::PngEncoder;
use image::{ImageEncoder, RgbImage};
use plotters::prelude::*;
use std::fmt::Write;

/// One row of panels: its label and one image per column (all of one size).
pub struct FigureRow<'a> {
    pub label: String,
    pub images: Vec<&'a RgbImage>,
}

/// A grid of labelled image panels.
pub struct Figure<'a> {
    pub title: String,
    /// Column labels; a label may have several lines.
    pub columns: Vec<String>,
    pub rows: Vec<FigureRow<'a>>,
    /// Adds the heat-map legend for heat maps at full brightness at this many lights per pixel.
    pub heat_legend: Option<u32>,
}

/// Narrowest and widest a panel is drawn (user units; the embedded image keeps its full
/// resolution and is scaled without smoothing).
const PANEL_WIDTH: (f64, f64) = (220.0, 420.0);
const GAP: f64 = 8.0;
const ROW_LABEL: f64 = 28.0;
const TITLE: f64 = 34.0;
/// Height of one line of a column label.
const LINE: f64 = 16.0;
const LEGEND: (u32, u32) = (460, 170);

/// `s` with the characters XML gives meaning to escaped.
pub fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Widest an image is embedded, in pixels: twice the widest panel, enough to print a panel
/// at its size; the full-resolution images are the files beside the figure.
const EMBED_WIDTH: u32 = 2 * PANEL_WIDTH.1 as u32;

/// `image` as a `data:` URI of its PNG encoding, scaled down (triangle filter) to
/// [`EMBED_WIDTH`] where it is wider.
fn png_data_uri(image: &RgbImage) -> Result<String, String> {
    let scaled;
    let image = if image.width() > EMBED_WIDTH {
        let height = (u64::from(image.height()) * u64::from(EMBED_WIDTH) / u64::from(image.width()))
            .max(1) as u32;
        scaled = image::imageops::resize(
            image,
            EMBED_WIDTH,
            height,
            image::imageops::FilterType::Triangle,
        );
        &scaled
    } else {
        image
    };
    let mut png = Vec::new();
    PngEncoder::new(&mut png)
        .write_image(
            image.as_raw(),
            image.width(),
            image.height(),
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| format!("cannot encode a figure panel: {e}"))?;
    Ok(format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png)
    ))
}

impl Figure<'_> {
    /// The figure as an SVG document.
    pub fn svg(&self) -> Result<String, String> {
        let (iw, ih) = self
            .rows
            .iter()
            .flat_map(|r| r.images.first())
            .map(|i| (i.width().max(1) as f64, i.height().max(1) as f64))
            .next()
            .unwrap_or((1.0, 1.0));
        let pw = iw.clamp(PANEL_WIDTH.0, PANEL_WIDTH.1);
        let ph = pw * ih / iw;
        let columns = self.columns.len().max(1) as f64;
        let label_lines = self.columns.iter().map(|c| c.lines().count()).max();
        let column_label = LINE * label_lines.unwrap_or(0) as f64 + 6.0;
        let grid_width = ROW_LABEL + columns * (pw + GAP);
        let grid_height = TITLE + column_label + self.rows.len() as f64 * (ph + GAP);
        let legend_height = if self.heat_legend.is_some() {
            f64::from(LEGEND.1) + GAP
        } else {
            0.0
        };
        let width = grid_width.max(f64::from(LEGEND.0) + ROW_LABEL);
        let height = grid_height + legend_height;
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif">"#
        );
        let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="22" text-anchor="middle" font-size="17">{}</text>"#,
            width / 2.0,
            xml_escape(&self.title)
        );
        for (c, label) in self.columns.iter().enumerate() {
            let x = ROW_LABEL + c as f64 * (pw + GAP) + pw / 2.0;
            for (l, line) in label.lines().enumerate() {
                let _ = writeln!(
                    s,
                    r#"<text x="{x}" y="{}" text-anchor="middle" font-size="13">{}</text>"#,
                    TITLE + LINE * (l + 1) as f64 - 3.0,
                    xml_escape(line)
                );
            }
        }
        for (r, row) in self.rows.iter().enumerate() {
            let y = TITLE + column_label + r as f64 * (ph + GAP);
            let _ = writeln!(
                s,
                r#"<text transform="translate({} {}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
                ROW_LABEL - 9.0,
                y + ph / 2.0,
                xml_escape(&row.label)
            );
            for (c, image) in row.images.iter().enumerate() {
                let _ = writeln!(
                    s,
                    r#"<image x="{}" y="{y}" width="{pw}" height="{ph}" preserveAspectRatio="none" style="image-rendering:pixelated" xlink:href="{}"/>"#,
                    ROW_LABEL + c as f64 * (pw + GAP),
                    png_data_uri(image)?
                );
            }
        }
        if let Some(max_lights) = self.heat_legend {
            let _ = writeln!(
                s,
                r#"<g transform="translate({ROW_LABEL} {grid_height})">{}</g>"#,
                heat_legend_svg(max_lights)?
            );
        }
        s.push_str("</svg>\n");
        Ok(s)
    }
}

/// The heat-map legend: the colour of every (lights per pixel, FDR) pair, with both axes.
pub fn heat_legend_svg(max_lights: u32) -> Result<String, String> {
    const CELLS: (u32, u32) = (64, 20);
    let max = f64::from(max_lights.max(1));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, LEGEND).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "heat map: brightness = VPLs per pixel, hue = false discovery rate",
                ("sans-serif", 16),
            )
            .margin(8)
            .x_label_area_size(38)
            .y_label_area_size(46)
            .build_cartesian_2d(0.0..max, 0.0..1.0)
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("VPLs per pixel (full brightness at {max_lights})"))
            .y_desc("FDR")
            .x_labels(5)
            .y_labels(3)
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(draw_error)?;
        let cell = (max / f64::from(CELLS.0), 1.0 / f64::from(CELLS.1));
        chart
            .draw_series((0..CELLS.0).flat_map(|i| {
                (0..CELLS.1).map(move |j| {
                    let (x, y) = (f64::from(i) * cell.0, f64::from(j) * cell.1);
                    let lights = ((x + 0.5 * cell.0) as u32).min(max_lights);
                    let c = heat_colour(lights, (y + 0.5 * cell.1) as f32, max_lights).0;
                    Rectangle::new(
                        [(x, y), (x + cell.0, y + cell.1)],
                        RGBColor(c[0], c[1], c[2]).filled(),
                    )
                })
            }))
            .map_err(draw_error)?;
        root.present().map_err(draw_error)?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    #[test]
    fn every_panel_and_label_is_in_the_figure() {
        let a = RgbImage::from_pixel(8, 4, Rgb([255, 0, 0]));
        let b = RgbImage::from_pixel(8, 4, Rgb([0, 0, 255]));
        let figure = Figure {
            title: "t <1>".into(),
            columns: vec!["ellipsoid".into(), "sphere & co\n2 lines".into()],
            rows: vec![
                FigureRow {
                    label: "total".into(),
                    images: vec![&a, &b],
                },
                FigureRow {
                    label: "heat map".into(),
                    images: vec![&b, &a],
                },
            ],
            heat_legend: Some(64),
        };
        let svg = figure.svg().unwrap();
        assert_eq!(svg.matches("<image ").count(), 4);
        assert_eq!(svg.matches("data:image/png;base64,").count(), 4);
        for label in [
            ">t &lt;1&gt;<",
            ">ellipsoid<",
            ">sphere &amp; co<",
            ">2 lines<",
            ">total<",
            ">heat map<",
        ] {
            assert!(svg.contains(label), "{label} missing");
        }
        assert!(svg.contains("full brightness at 64") && svg.contains("FDR"));
        // The legend's cells carry the heat-map colours: its brightest corners are the colours
        // of the most lights at the lowest and at the highest FDR.
        let hex = |c: image::Rgb<u8>| format!("#{:02X}{:02X}{:02X}", c[0], c[1], c[2]);
        assert!(svg.contains(&hex(heat_colour(63, 0.025, 64))));
        assert!(svg.contains(&hex(heat_colour(63, 0.975, 64))));
        assert!(
            svg.matches("<rect").count() > 64 * 20,
            "one cell per colour"
        );
    }

    #[test]
    fn wide_images_are_embedded_scaled_down() {
        let wide = RgbImage::from_pixel(EMBED_WIDTH * 2 + 1, 100, Rgb([10, 200, 30]));
        let uri = png_data_uri(&wide).unwrap();
        let png = base64::engine::general_purpose::STANDARD
            .decode(uri.trim_start_matches("data:image/png;base64,"))
            .unwrap();
        let back = image::load_from_memory(&png).unwrap().to_rgb8();
        assert_eq!((back.width(), back.height()), (EMBED_WIDTH, 49));
        assert_eq!(back.get_pixel(7, 7), &Rgb([10, 200, 30]));
    }

    #[test]
    fn a_panel_decodes_back_to_its_image() {
        let a = RgbImage::from_fn(5, 3, |x, y| Rgb([x as u8 * 40, y as u8 * 80, 7]));
        let uri = png_data_uri(&a).unwrap();
        let png = base64::engine::general_purpose::STANDARD
            .decode(uri.trim_start_matches("data:image/png;base64,"))
            .unwrap();
        let back = image::load_from_memory(&png).unwrap().to_rgb8();
        assert_eq!(back, a);
    }
}
