//! The PDF beside each figure's SVG, for papers and tools that take PDF: the same figure
//! converted by `svg2pdf` (typst's converter), vector where the SVG is (paths, and text set
//! in the system's sans-serif font, embedded and subset), its images embedded, at the SVG's
//! size (a `--print-width` figure is 3.5 or 7 inches wide in the PDF too).
use slc_app::out_dir::OutDir;
use std::sync::{Arc, OnceLock};
use svg2pdf::usvg::{self, fontdb};
use svg2pdf::{ConversionOptions, PageOptions};

/// Families a figure's `sans-serif` text is set in, the first one installed.
const SANS_SERIF: [&str; 5] = [
    "DejaVu Sans",
    "Liberation Sans",
    "Arial",
    "Helvetica",
    "Noto Sans",
];

/// The system's fonts, loaded once; `sans-serif` is the first of [`SANS_SERIF`] there.
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    Arc::clone(FONTS.get_or_init(|| {
        let mut db = fontdb::Database::new();
        db.load_system_fonts();
        let installed = SANS_SERIF.iter().find(|name| {
            db.faces()
                .any(|f| f.families.iter().any(|(family, _)| family == *name))
        });
        if let Some(name) = installed {
            db.set_sans_serif_family(*name);
        }
        Arc::new(db)
    }))
}

/// The PDF of `svg`, one page of its size (SVG units at 72 per inch: a user unit is a point);
/// an error where it cannot be parsed, or where no font is installed for its text.
pub fn pdf_of(svg: &str) -> Result<Vec<u8>, String> {
    let fontdb = fonts();
    if !fontdb.faces().any(|f| {
        f.families
            .iter()
            .any(|(family, _)| SANS_SERIF.contains(&family.as_str()))
    }) {
        return Err(format!(
            "none of the fonts {} is installed for its text (Debian: fonts-dejavu-core)",
            SANS_SERIF.join(", ")
        ));
    }
    let options = usvg::Options {
        dpi: 72.0,
        fontdb,
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| format!("cannot read: {e}"))?;
    svg2pdf::to_pdf(
        &tree,
        ConversionOptions::default(),
        PageOptions { dpi: 72.0 },
    )
    .map_err(|e| format!("cannot convert: {e}"))
}

/// Stages the figure `name`: `name.svg` and, where it can be made, `name.pdf` (else a
/// warning says why; the SVG is the figure). Returns the files staged.
pub fn write_figure(out: &mut OutDir, name: &str, svg: &str) -> Result<Vec<String>, String> {
    let svg_file = format!("{name}.svg");
    out.write(&svg_file, svg.as_bytes())?;
    match pdf_of(svg) {
        Ok(pdf) => {
            let pdf_file = format!("{name}.pdf");
            out.write(&pdf_file, &pdf)?;
            Ok(vec![svg_file, pdf_file])
        }
        Err(e) => {
            eprintln!("warning: {name}.pdf not written: {e}");
            Ok(vec![svg_file])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{log_log_plot_svg, PlotPoint, Series};
    use crate::print::PrintWidth;

    #[test]
    fn a_print_figure_becomes_a_pdf_page_of_its_size_with_its_text() {
        let series = [Series {
            name: "ellipsoid".into(),
            points: vec![PlotPoint::at(1.0, 0.1), PlotPoint::at(3.0, 0.02)],
        }];
        let style = PrintWidth::Column.style();
        let svg = log_log_plot_svg("sweep", "ms", "RMSE", &series, &style).unwrap();
        let pdf = pdf_of(&svg).unwrap();
        assert!(pdf.starts_with(b"%PDF-"));
        // One page 3.5 inches (252 points) wide: its media box.
        let text = String::from_utf8_lossy(&pdf);
        let media = text
            .split("/MediaBox [")
            .nth(1)
            .and_then(|s| s.split(']').next())
            .unwrap();
        let numbers: Vec<f64> = media
            .split_whitespace()
            .map(|n| n.parse().unwrap())
            .collect();
        assert_eq!(numbers[2] - numbers[0], 252.0, "{media}");
        // The text is set in an embedded font.
        assert!(text.contains("/FontFile2") || text.contains("/FontFile3"));
    }

    #[test]
    fn a_broken_svg_is_an_error() {
        assert!(pdf_of("<svg").is_err());
    }
}
