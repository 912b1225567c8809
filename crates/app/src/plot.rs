//! Log-log line plots as SVG through `plotters`: ticks at 1, 2 and 5 × 10^k (every integer
//! multiple where a decade holds fewer than three), axis titles, a legend. Used for the
//! speed-versus-accuracy curves of `slc sweep` and the error-versus-count curves of the VSGL
//! sweep.
use plotters::prelude::*;

/// One curve: a name and its (x, y) points in drawing order.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// Series colours (matplotlib's "tab10", readable in print and by most colour-blind readers).
pub const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Whether a point can be drawn on log-log axes.
fn drawable(&(x, y): &(f64, f64)) -> bool {
    x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0
}

/// The axis range of positive finite `values`, widened by 5% on each side in log space
/// (a factor of 2 around a single value).
fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        return (1.0, 10.0);
    }
    let span = (hi / lo).log10();
    if span < 1e-9 {
        return (lo / 2.0, hi * 2.0);
    }
    let pad = 10f64.powf(0.05 * span);
    (lo / pad, hi * pad)
}

/// Tick values in `[lo, hi]`: 1, 2, 5 × 10^k, or every integer multiple of 10^k when that
/// gives fewer than three, or evenly spaced round values (steps of 1, 2 or 5 × 10^k) when the
/// range is too narrow for either.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let pick = |mantissas: &[f64]| -> Vec<f64> {
        let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
        (k0..=k1)
            .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
            .filter(|v| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9))
            .collect()
    };
    let coarse = pick(&[1.0, 2.0, 5.0]);
    if coarse.len() >= 3 {
        return coarse;
    }
    let fine = pick(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    if fine.len() >= 3 {
        return fine;
    }
    // The largest round step that still gives at least three ticks.
    let decade = 10f64.powf(((hi - lo) / 3.0).log10().floor());
    let step = [5.0, 2.0, 1.0]
        .map(|m| m * decade)
        .into_iter()
        .find(|step| (hi / step).floor() - (lo / step).ceil() >= 2.0)
        .unwrap_or(decade);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last)
        .map(|i| i as f64 * step)
        .filter(|v| (lo..=hi).contains(v))
        .collect()
}

/// A tick label with at most three significant digits and no trailing zeros: `0.002`, `50`,
/// `1500`, and scientific notation (`2e-5`, `3e6`) outside [10⁻³, 10⁵).
pub fn tick_label(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    if !(-3..5).contains(&magnitude) {
        let s = format!("{v:.2e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let decimals = (2 - magnitude).max(0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A plotters error as slc reports it.
pub fn draw_error<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> String {
    format!("cannot draw a figure: {e}")
}

/// Renders `series` on log-log axes as an SVG document of 760 × 500 user units. Non-finite and
/// non-positive points are left out.
pub fn log_log_plot_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<String, String> {
    let all = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().filter(|p| drawable(p)))
    };
    let (x0, x1) = log_range(all().map(|p| p.0));
    let (y0, y1) = log_range(all().map(|p| p.1));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (760, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 21))
            .margin(14)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d(
                (x0..x1).log_scale().with_key_points(log_ticks(x0, x1)),
                (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)),
            )
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 16))
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .light_line_style(WHITE)
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(draw_error)?;
        for (i, s) in series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let points: Vec<(f64, f64)> = s.points.iter().copied().filter(drawable).collect();
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                .map_err(draw_error)?
                .label(s.name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 22, y)], colour.stroke_width(2))
                });
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(draw_error)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .label_font(("sans-serif", 16))
            .draw()
            .map_err(draw_error)?;
        root.present().map_err(draw_error)?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plot_contains_every_series_and_skips_bad_points() {
        let series = vec![
            Series {
                name: "ellipsoid".into(),
                points: vec![(1.0, 0.1), (2.0, 0.05), (f64::NAN, 1.0)],
            },
            Series {
                name: "sphere <1>".into(),
                points: vec![(3.0, 0.2), (0.0, 0.3)],
            },
        ];
        let svg = log_log_plot_svg("t", "ms", "RMSE", &series).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("ellipsoid") && svg.contains("sphere &lt;1&gt;"));
        assert!(svg.contains("\nms\n</text>") && svg.contains("\nRMSE\n</text>"));
        assert_eq!(
            svg.matches("<circle").count(),
            3,
            "NaN and log-invalid points are dropped"
        );
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
    }

    #[test]
    fn ticks_are_round_numbers_inside_the_range() {
        assert_eq!(
            log_ticks(0.8, 120.0),
            vec![1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0]
        );
        // Less than a decade: every integer multiple.
        assert_eq!(log_ticks(2.5, 7.5), vec![3.0, 4.0, 5.0, 6.0, 7.0]);
        // Narrower than one step of 10^k: round linear steps.
        let t = log_ticks(0.0121, 0.0135);
        assert!(
            t.len() >= 2 && t.iter().all(|v| (0.0121..=0.0135).contains(v)),
            "{t:?}"
        );
        assert!(t.iter().all(|v| tick_label(*v).len() <= 6), "{t:?}");
        let t = log_ticks(207.9, 1296.1);
        assert_eq!(
            t,
            vec![300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 900.0, 1000.0]
        );
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(0.002), "0.002");
        assert_eq!(tick_label(50.0), "50");
        assert_eq!(tick_label(1500.0), "1500");
        assert_eq!(tick_label(0.25), "0.25");
        assert_eq!(tick_label(2e-5), "2e-5");
        assert_eq!(tick_label(3e6), "3e6");
        assert_eq!(tick_label(1.5e-4), "1.5e-4");
    }
}
