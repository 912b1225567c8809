//! A small SVG line plot (no dependencies): axes with ticks, one polyline and marker set per
//! series, a legend. Used for the speed-versus-accuracy curves of `slc sweep`.
use std::fmt::Write;

/// One curve: a name and its (x, y) points in drawing order.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

const COLOURS: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
];

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Axis range with `log` scale: returns (min, max) in plot units (log10 when `log`).
fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        let v = if log { v.log10() } else { v };
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        return (lo - 0.5, hi + 0.5);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

/// Renders the plot as an SVG document. Non-finite points (and non-positive ones on a log
/// axis) are left out.
pub fn line_plot_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    log_x: bool,
    log_y: bool,
) -> String {
    let (w, h) = (720.0, 480.0);
    let (left, right, top, bottom) = (80.0, 180.0, 40.0, 60.0);
    let ok = |(x, y): &(f64, f64)| {
        x.is_finite() && y.is_finite() && (!log_x || *x > 0.0) && (!log_y || *y > 0.0)
    };
    let (x0, x1) = range(
        series
            .iter()
            .flat_map(|s| s.points.iter().filter(|p| ok(p)).map(|p| p.0)),
        log_x,
    );
    let (y0, y1) = range(
        series
            .iter()
            .flat_map(|s| s.points.iter().filter(|p| ok(p)).map(|p| p.1)),
        log_y,
    );
    let px =
        |x: f64| left + ((if log_x { x.log10() } else { x }) - x0) / (x1 - x0) * (w - left - right);
    let py = |y: f64| {
        h - bottom - ((if log_y { y.log10() } else { y }) - y0) / (y1 - y0) * (h - top - bottom)
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="22" text-anchor="middle" font-size="15">{}</text>"#,
        (left + w - right) / 2.0,
        escape(title)
    );
    let _ = writeln!(
        s,
        r#"<rect x="{left}" y="{top}" width="{}" height="{}" fill="none" stroke="black"/>"#,
        w - left - right,
        h - top - bottom
    );
    for k in 0..=5 {
        let t = k as f64 / 5.0;
        let (vx, vy) = (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
        let (lx, ly) = (
            if log_x { 10f64.powf(vx) } else { vx },
            if log_y { 10f64.powf(vy) } else { vy },
        );
        let (sx, sy) = (
            left + t * (w - left - right),
            h - bottom - t * (h - top - bottom),
        );
        let _ = writeln!(
            s,
            r#"<line x1="{sx}" y1="{}" x2="{sx}" y2="{}" stroke="black"/><text x="{sx}" y="{}" text-anchor="middle">{lx:.3}</text>"#,
            h - bottom,
            h - bottom + 5.0,
            h - bottom + 18.0
        );
        let _ = writeln!(
            s,
            r#"<line x1="{}" y1="{sy}" x2="{left}" y2="{sy}" stroke="black"/><text x="{}" y="{}" text-anchor="end">{ly:.3e}</text>"#,
            left - 5.0,
            left - 8.0,
            sy + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        (left + w - right) / 2.0,
        h - 15.0,
        escape(x_label)
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate(18 {}) rotate(-90)" text-anchor="middle">{}</text>"#,
        (top + h - bottom) / 2.0,
        escape(y_label)
    );
    for (i, ser) in series.iter().enumerate() {
        let c = COLOURS[i % COLOURS.len()];
        let pts: Vec<String> = ser
            .points
            .iter()
            .filter(|p| ok(p))
            .map(|&(x, y)| format!("{:.2},{:.2}", px(x), py(y)))
            .collect();
        let _ = writeln!(
            s,
            r#"<polyline fill="none" stroke="{c}" stroke-width="2" points="{}"/>"#,
            pts.join(" ")
        );
        for p in &pts {
            let (cx, cy) = p.split_once(',').unwrap_or(("0", "0"));
            let _ = writeln!(s, r#"<circle cx="{cx}" cy="{cy}" r="3" fill="{c}"/>"#);
        }
        let ly = top + 10.0 + 20.0 * i as f64;
        let _ = writeln!(
            s,
            r#"<line x1="{}" y1="{ly}" x2="{}" y2="{ly}" stroke="{c}" stroke-width="2"/><text x="{}" y="{}">{}</text>"#,
            w - right + 10.0,
            w - right + 30.0,
            w - right + 35.0,
            ly + 4.0,
            escape(&ser.name)
        );
    }
    s.push_str("</svg>\n");
    s
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
        let svg = line_plot_svg("t", "ms", "RMSE", &series, true, true);
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
        assert!(svg.contains("ellipsoid") && svg.contains("sphere &lt;1&gt;"));
        assert_eq!(
            svg.matches("<circle").count(),
            3,
            "NaN and log-invalid points are dropped"
        );
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
    }
}
