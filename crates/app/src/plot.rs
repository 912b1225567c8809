//! Log-log line plots as SVG through `plotters`: ticks at 1, 2 and 5 × 10^k (every integer
//! multiple where a decade holds fewer than three), axis titles, a legend, and at each point
//! its label (which δ it is) and the spread of its x (the min–max of repeated timings). Used
//! for the speed-versus-accuracy curves of `slc sweep` and the error-versus-count curves of
//! the VSGL sweep; sized for the screen or for print ([`crate::print`]).
use crate::print::Style;
use plotters::prelude::*;

/// One point of a curve.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotPoint {
    pub x: f64,
    pub y: f64,
    /// Written beside the point (e.g. `δ=1e-3`).
    pub label: Option<String>,
    /// The range x spans (min, max), drawn as a bar through the point.
    pub x_range: Option<(f64, f64)>,
}

impl PlotPoint {
    /// A point without label or spread.
    pub fn at(x: f64, y: f64) -> Self {
        Self {
            x,
            y,
            label: None,
            x_range: None,
        }
    }
}

/// One curve: a name and its points in drawing order.
#[derive(Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<PlotPoint>,
}

/// Series colours (matplotlib's "tab10", readable in print and by most colour-blind readers,
/// then black and navy): one for each strategy.
pub const COLOURS: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(0, 0, 0),
    RGBColor(0, 0, 128),
];

/// Whether a point can be drawn on log-log axes.
fn drawable(p: &&PlotPoint) -> bool {
    p.x.is_finite() && p.y.is_finite() && p.x > 0.0 && p.y > 0.0
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

/// Curves whose legend goes inside the plot, in its emptiest corner; more get a column of
/// their own beside it.
const LEGEND_INSIDE: usize = 4;

/// The width of the legend column beside the plot: the key and the longest name (text about
/// 0.6 of its size wide a character).
fn legend_width(series: &[Series], style: &Style) -> u32 {
    let longest = series
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(0);
    (34.0 + longest as f64 * style.small * 0.6) as u32
}

/// The corner of the plot the legend covers fewest points in: points are given as fractions
/// of the axes (0 at the left and bottom, 1 at the right and top), and a legend is taken to
/// cover the 45% of each axis next to its corner. Upper right, then upper left, lower right
/// and lower left where they tie.
fn emptiest_corner(points: impl Iterator<Item = (f64, f64)>) -> SeriesLabelPosition {
    use SeriesLabelPosition::{LowerLeft, LowerRight, UpperLeft, UpperRight};
    let corners = [
        (UpperRight, true, true),
        (UpperLeft, false, true),
        (LowerRight, true, false),
        (LowerLeft, false, false),
    ];
    let mut covered = [0usize; 4];
    for (x, y) in points {
        for (n, &(_, right, top)) in covered.iter_mut().zip(&corners) {
            let near = |v: f64, high: bool| if high { v >= 0.55 } else { v <= 0.45 };
            *n += usize::from(near(x, right) && near(y, top));
        }
    }
    let best = (0..4).min_by_key(|&i| covered[i]).unwrap_or(0);
    corners[best].0.clone()
}

/// A plotters error as slc reports it.
pub fn draw_error<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> String {
    format!("cannot draw a figure: {e}")
}

/// Renders `series` on log-log axes as an SVG document sized by `style` (760 × 500 for the
/// screen; the print width × two thirds of it, in points, for print). Non-finite and
/// non-positive points are left out; a spread reaches as far as its positive part.
pub fn log_log_plot_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    style: &Style,
) -> Result<String, String> {
    let all = || series.iter().flat_map(|s| s.points.iter().filter(drawable));
    let xs = all().flat_map(|p| {
        let (lo, hi) = p.x_range.unwrap_or((p.x, p.x));
        [p.x, lo, hi]
    });
    let (x0, x1) = log_range(xs.filter(|x| x.is_finite() && *x > 0.0));
    let (y0, y1) = log_range(all().map(|p| p.y));
    // Many curves on the screen: the legend in a column of its own right of the plot, where
    // it covers nothing, the figure widened by it (a printed figure keeps its width and its
    // legend inside).
    let beside = (series.len() > LEGEND_INSIDE && style.inches.is_none())
        .then(|| legend_width(series, style));
    let size = (
        (style.width as u32) + beside.unwrap_or(0),
        (style.width * 500.0 / 760.0) as u32,
    );
    let font = |s: f64| ("sans-serif", Style::plotters(s));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let (plot_area, legend_area) = match beside {
            Some(legend) => {
                let below_title = root.titled(title, font(style.title)).map_err(draw_error)?;
                let (plot, legend) = below_title.split_horizontally(size.0 - legend);
                (plot, Some(legend))
            }
            None => (root.clone(), None),
        };
        let mut builder = ChartBuilder::on(&plot_area);
        if beside.is_none() {
            builder.caption(title, font(style.title));
        }
        let mut chart = builder
            .margin(style.gap * 1.75)
            .x_label_area_size(style.label * 3.0)
            .y_label_area_size(style.small * 5.5)
            .build_cartesian_2d(
                (x0..x1).log_scale().with_key_points(log_ticks(x0, x1)),
                (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)),
            )
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .axis_desc_style(font(style.label))
            .label_style(font(style.small))
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .light_line_style(WHITE)
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(draw_error)?;
        let stroke = style.stroke as u32;
        let marker = (style.stroke * 1.5).max(2.0) as i32;
        for (i, s) in series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let points: Vec<&PlotPoint> = s.points.iter().filter(drawable).collect();
            chart
                .draw_series(LineSeries::new(
                    points.iter().map(|p| (p.x, p.y)),
                    colour.stroke_width(stroke),
                ))
                .map_err(draw_error)?
                .label(s.name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(stroke))
                });
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|p| Circle::new((p.x, p.y), marker, colour.filled())),
                )
                .map_err(draw_error)?;
            let spreads = points.iter().filter_map(|p| {
                let (lo, hi) = p.x_range?;
                let (lo, hi) = (lo.max(x0), hi.min(x1));
                (lo < hi)
                    .then(|| PathElement::new(vec![(lo, p.y), (hi, p.y)], colour.stroke_width(1)))
            });
            chart.draw_series(spreads).map_err(draw_error)?;
            // Above the points of every other curve, below the others', so that the labels
            // of two curves through nearby points do not overlap.
            let dy = if i % 2 == 0 {
                -(style.small as i32) - 2
            } else {
                3
            };
            let labels = points.iter().filter_map(|p| {
                let label = p.label.clone()?;
                let text = Text::new(label, (3, dy), font(style.small).into_font().color(&colour));
                Some(EmptyElement::at((p.x, p.y)) + text)
            });
            chart.draw_series(labels).map_err(draw_error)?;
        }
        match legend_area {
            Some(area) => {
                let line = style.small * 1.6;
                let top = style.gap * 1.75 + style.small;
                for (i, s) in series.iter().enumerate() {
                    let colour = COLOURS[i % COLOURS.len()];
                    let y = (top + line * i as f64) as i32;
                    let key = PathElement::new(vec![(2, y), (20, y)], colour.stroke_width(stroke));
                    area.draw(&key).map_err(draw_error)?;
                    area.draw(&Circle::new((11, y), marker, colour.filled()))
                        .map_err(draw_error)?;
                    let text = Text::new(
                        s.name.as_str(),
                        (26, y - (style.small * 0.6) as i32),
                        font(style.small),
                    );
                    area.draw(&text).map_err(draw_error)?;
                }
            }
            None => {
                let corner = emptiest_corner(all().map(|p| {
                    let at = |v: f64, lo: f64, hi: f64| (v / lo).ln() / (hi / lo).ln();
                    (at(p.x, x0, x1), at(p.y, y0, y1))
                }));
                chart
                    .configure_series_labels()
                    .position(corner)
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK.mix(0.4))
                    .label_font(font(style.small))
                    .draw()
                    .map_err(draw_error)?;
            }
        }
        root.present().map_err(draw_error)?;
    }
    Ok(style.sized(&svg, size))
}

/// The font sizes an SVG sets, in order (for tests of the print sizes).
#[cfg(test)]
pub(crate) fn font_sizes(svg: &str) -> Vec<f64> {
    svg.split("font-size=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap().parse().unwrap())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::print::{PrintWidth, MIN_PRINT_POINTS};

    fn points(xy: &[(f64, f64)]) -> Vec<PlotPoint> {
        xy.iter().map(|&(x, y)| PlotPoint::at(x, y)).collect()
    }

    #[test]
    fn plot_contains_every_series_and_skips_bad_points() {
        let series = vec![
            Series {
                name: "ellipsoid".into(),
                points: points(&[(1.0, 0.1), (2.0, 0.05), (f64::NAN, 1.0)]),
            },
            Series {
                name: "sphere <1>".into(),
                points: points(&[(3.0, 0.2), (0.0, 0.3)]),
            },
        ];
        let svg =
            log_log_plot_svg("t", "ms", "RMSE", &series, &PrintWidth::Screen.style()).unwrap();
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
    fn points_carry_their_label_and_spread_and_print_text_is_8_pt_or_more() {
        let series = vec![Series {
            name: "tight".into(),
            points: vec![
                PlotPoint {
                    x: 14.0,
                    y: 0.1,
                    label: Some("δ=1e-3".into()),
                    x_range: Some((10.0, 13.0)),
                },
                PlotPoint {
                    label: Some("δ=1e-2".into()),
                    ..PlotPoint::at(8.0, 0.3)
                },
            ],
        }];
        for width in [PrintWidth::Screen, PrintWidth::Column, PrintWidth::Page] {
            let style = width.style();
            let svg = log_log_plot_svg("t", "ms", "RMSE", &series, &style).unwrap();
            assert!(
                svg.contains("\nδ=1e-3\n") && svg.contains("\nδ=1e-2\n"),
                "{width:?}"
            );
            // The spread is a line of its own from 10 to 13 ms: one more polyline.
            let mut plain = series.clone();
            plain[0].points[0].x_range = None;
            let without = log_log_plot_svg("t", "ms", "RMSE", &plain, &style).unwrap();
            let lines = |svg: &str| svg.matches("<polyline").count();
            assert_eq!(lines(&svg), lines(&without) + 1, "{width:?}");
            let smallest = font_sizes(&svg).into_iter().fold(f64::INFINITY, f64::min);
            assert!(smallest >= style.small, "{width:?}: {smallest}");
            if let Some(inches) = style.inches {
                assert!(svg.contains(&format!("width=\"{inches}in\"")), "{width:?}");
                assert!(smallest >= MIN_PRINT_POINTS);
            }
        }
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

    /// The legend goes where it hides fewest points: upper left above rising curves, upper
    /// right above falling ones and where nothing is covered.
    #[test]
    fn the_legend_avoids_the_points() {
        let rising = [(0.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.9, 0.7)];
        assert_eq!(
            emptiest_corner(rising.into_iter()),
            SeriesLabelPosition::UpperLeft
        );
        let falling = [(0.0, 1.0), (0.5, 0.5), (1.0, 0.0)];
        assert_eq!(
            emptiest_corner(falling.into_iter()),
            SeriesLabelPosition::UpperRight
        );
        let everywhere_but_lower_right = [(0.9, 0.9), (0.1, 0.9), (0.1, 0.1)];
        assert_eq!(
            emptiest_corner(everywhere_but_lower_right.into_iter()),
            SeriesLabelPosition::LowerRight
        );
    }

    /// More than four curves on the screen: the legend is a column right of the plot, each
    /// name once, none of it over the axes.
    #[test]
    fn many_curves_get_their_legend_beside_the_plot() {
        let style = PrintWidth::Screen.style();
        let series: Vec<Series> = (0..9)
            .map(|i| Series {
                name: format!("strategy-{i} (0.9{i})"),
                points: points(&[(1e4, 1.0 + i as f64), (1e6, 100.0 * (1.0 + i as f64))]),
            })
            .collect();
        let svg = log_log_plot_svg("t", "VPLs", "ms", &series, &style).unwrap();
        // The plot keeps the figure's width; the legend is added right of it.
        let width = style.width as u32 + legend_width(&series, &style);
        assert!(svg.contains(&format!("width=\"{width}\"")), "{width}");
        for s in &series {
            let at = svg.find(&format!("\n{}\n</text>", s.name)).unwrap();
            let tag = &svg[svg[..at].rfind("<text").unwrap()..at];
            let x: f64 = tag
                .split("x=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            assert!(x > style.width, "{}: x {x}, plot {}", s.name, style.width);
        }
        // In print the figure keeps its width, the legend inside.
        let print = PrintWidth::Column.style();
        let svg = log_log_plot_svg("t", "VPLs", "ms", &series, &print).unwrap();
        assert!(svg.contains("width=\"3.5in\""));
    }

    /// Every strategy's curve gets a colour of its own in one plot.
    #[test]
    fn a_distinct_colour_for_every_strategy() {
        let mut colours: Vec<_> = COLOURS.iter().map(|c| (c.0, c.1, c.2)).collect();
        colours.sort_unstable();
        colours.dedup();
        assert_eq!(colours.len(), COLOURS.len());
        assert!(COLOURS.len() >= slc_core::Strategy::every().count());
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
