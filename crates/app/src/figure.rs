//! Labelled figures of images, as standalone SVG: a title, one labelled column per variant
//! (strategy, δ…), one labelled row per kind of image (total, heat map, error map), and, where
//! heat maps are shown, their legend: the two variables of the paper's Fig. 9 (brightness =
//! VPLs per pixel, hue = false discovery rate) as a colour field with axes, drawn by `plotters`.
//! The images are embedded as base64 PNG, so the file can be moved, mailed or put in a paper
//! on its own. Sized for the screen or for print ([`crate::print`]).
use crate::heatmap::{heat_colour, HeatScale};
use crate::plot::{draw_error, tick_label};
use crate::print::Style;
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
    /// Adds the legend of heat maps at this scale.
    pub heat_legend: Option<HeatScale>,
    pub style: Style,
}

/// Narrowest and widest a panel is drawn on the screen (user units; the embedded image keeps
/// its full resolution and is scaled without smoothing). In print the panels share the width.
const PANEL_WIDTH: (f64, f64) = (220.0, 420.0);
/// The screen's heat-map legend; in print it spans the figure, at this share of its width high.
const LEGEND: (f64, f64) = (460.0, 170.0);

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
        let st = &self.style;
        let (iw, ih) = self
            .rows
            .iter()
            .flat_map(|r| r.images.first())
            .map(|i| (i.width().max(1) as f64, i.height().max(1) as f64))
            .next()
            .unwrap_or((1.0, 1.0));
        let columns = self.columns.len().max(1) as f64;
        let line = 1.25 * st.label;
        // Row labels run up the left edge, in as many lines as a panel's height needs (the
        // panels' size depends on their width, which depends on the labels' lines).
        let lines_of = |ph: f64| {
            self.rows
                .iter()
                .map(|r| Style::wrap(&r.label, ph, st.label))
                .collect::<Vec<_>>()
        };
        let panel = |row_label: f64| {
            let pw = match st.inches {
                Some(_) => (st.width - row_label - columns * st.gap) / columns,
                None => iw.clamp(PANEL_WIDTH.0, PANEL_WIDTH.1),
            };
            (pw, pw * ih / iw)
        };
        let (_, first_ph) = panel(line + 0.4 * st.label);
        let row_lines = lines_of(first_ph).iter().map(Vec::len).max().unwrap_or(1);
        let row_label = line * row_lines as f64 + 0.4 * st.label;
        let (pw, ph) = panel(row_label);
        let row_labels = lines_of(ph);
        let labels: Vec<Vec<String>> = self
            .columns
            .iter()
            .map(|c| {
                c.lines()
                    .flat_map(|l| Style::wrap(l, pw, st.label))
                    .collect()
            })
            .collect();
        let label_lines = labels.iter().map(Vec::len).max().unwrap_or(0);
        let column_label = line * label_lines as f64 + st.gap;
        let title = 1.7 * st.title;
        let grid_width = row_label + columns * (pw + st.gap);
        let grid_height = title + column_label + self.rows.len() as f64 * (ph + st.gap);
        let legend = match st.inches {
            Some(_) => {
                let w = (st.width - row_label).floor();
                (w, (w * 0.3).max(10.0 * st.small).floor())
            }
            None => LEGEND,
        };
        let legend_height = if self.heat_legend.is_some() {
            legend.1 + st.gap
        } else {
            0.0
        };
        let width = match st.inches {
            Some(_) => st.width,
            None => grid_width.max(legend.0 + row_label),
        };
        let height = grid_height + legend_height;
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" {} font-family="sans-serif">"#,
            st.root_size(width, height)
        );
        let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="{}">{}</text>"#,
            width / 2.0,
            1.15 * st.title,
            st.title,
            xml_escape(&self.title)
        );
        for (c, lines) in labels.iter().enumerate() {
            let x = row_label + c as f64 * (pw + st.gap) + pw / 2.0;
            for (l, text) in lines.iter().enumerate() {
                let _ = writeln!(
                    s,
                    r#"<text x="{x}" y="{}" text-anchor="middle" font-size="{}">{}</text>"#,
                    title + line * (l + 1) as f64 - 0.25 * st.label,
                    st.label,
                    xml_escape(text)
                );
            }
        }
        for (r, row) in self.rows.iter().enumerate() {
            let y = title + column_label + r as f64 * (ph + st.gap);
            let lines = &row_labels[r];
            for (l, text) in lines.iter().enumerate() {
                let _ = writeln!(
                    s,
                    r#"<text transform="translate({} {}) rotate(-90)" text-anchor="middle" font-size="{}">{}</text>"#,
                    row_label - 0.55 * st.label - line * (lines.len() - 1 - l) as f64,
                    y + ph / 2.0,
                    st.label,
                    xml_escape(text)
                );
            }
            for (c, image) in row.images.iter().enumerate() {
                let _ = writeln!(
                    s,
                    r#"<image x="{}" y="{y}" width="{pw}" height="{ph}" preserveAspectRatio="none" style="image-rendering:pixelated" xlink:href="{}"/>"#,
                    row_label + c as f64 * (pw + st.gap),
                    png_data_uri(image)?
                );
            }
        }
        if let Some(scale) = self.heat_legend {
            let size = (legend.0 as u32, legend.1 as u32);
            let _ = writeln!(
                s,
                r#"<g transform="translate({row_label} {grid_height})">{}</g>"#,
                heat_legend_svg(scale, size, st)?
            );
        }
        s.push_str("</svg>\n");
        Ok(s)
    }
}

/// The heat-map legend: the colour of every (lights per pixel, FDR) pair, with both axes; at
/// a per-frame scale the x axis is the share of each frame's maximum.
pub fn heat_legend_svg(scale: HeatScale, size: (u32, u32), st: &Style) -> Result<String, String> {
    const CELLS: (u32, u32) = (64, 20);
    // The colours are those of heat maps at full brightness at `full` lights.
    let (full, max, x_desc) = match scale {
        HeatScale::Fixed(max) => (
            max.max(1),
            f64::from(max.max(1)),
            format!("VPLs per pixel (full brightness at {max})"),
        ),
        HeatScale::PerFrame => (
            CELLS.0,
            1.0,
            "VPLs per pixel / the frame's maximum (under its column)".to_string(),
        ),
    };
    let font = |s: f64| ("sans-serif", Style::plotters(s));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "heat map: brightness = VPLs per pixel, hue = false discovery rate",
                font(st.label),
            )
            .margin(st.gap)
            .x_label_area_size(2.6 * st.small)
            .y_label_area_size(3.2 * st.small)
            .build_cartesian_2d(0.0..max, 0.0..1.0)
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_desc)
            .y_desc("FDR")
            .x_labels(5)
            .y_labels(3)
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .label_style(font(st.small))
            .axis_desc_style(font(st.small))
            .draw()
            .map_err(draw_error)?;
        let cell = (max / f64::from(CELLS.0), 1.0 / f64::from(CELLS.1));
        chart
            .draw_series((0..CELLS.0).flat_map(|i| {
                (0..CELLS.1).map(move |j| {
                    let (x, y) = (f64::from(i) * cell.0, f64::from(j) * cell.1);
                    let lights = ((x + 0.5 * cell.0) / max * f64::from(full)) as u32;
                    let c = heat_colour(lights.min(full), (y + 0.5 * cell.1) as f32, full).0;
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
    use crate::print::{PrintWidth, MIN_PRINT_POINTS};
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
            heat_legend: Some(HeatScale::Fixed(64)),
            style: PrintWidth::Screen.style(),
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
    fn a_print_figure_spans_its_column_with_text_of_8_pt_or_more() {
        let a = RgbImage::from_pixel(64, 36, Rgb([200, 10, 10]));
        let columns: Vec<String> = ["none", "sphere", "ellipsoid", "clustered", "tight"]
            .iter()
            .map(|s| format!("{s}\n12.3 lights/px, FDR 0.12\nheat full at 34"))
            .collect();
        for width in [PrintWidth::Column, PrintWidth::Page] {
            let style = width.style();
            let figure = Figure {
                title: "sponza: culling strategies at δ = 0.001, K = 8".into(),
                columns: columns.clone(),
                rows: vec![FigureRow {
                    label: "heat map".into(),
                    images: vec![&a; 5],
                }],
                heat_legend: Some(HeatScale::PerFrame),
                style,
            };
            let svg = figure.svg().unwrap();
            let inches = style.inches.unwrap();
            assert!(svg.contains(&format!(r#"width="{inches}in""#)), "{width:?}");
            assert!(svg.contains(&format!(r#"viewBox="0 0 {} "#, style.width)));
            let sizes = crate::plot::font_sizes(&svg);
            let smallest = sizes.iter().copied().fold(f64::INFINITY, f64::min);
            assert!(
                sizes.len() > 20 && smallest >= MIN_PRINT_POINTS,
                "{smallest}"
            );
            assert!(
                svg.contains("maximum (under its column)"),
                "the per-frame legend says so"
            );
            // Every panel lies inside the figure's width.
            for x in svg.split("<image x=\"").skip(1) {
                let x: f64 = x.split('"').next().unwrap().parse().unwrap();
                assert!(x < style.width);
            }
        }
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
