//! How each strategy's culling and shading grow with the VPL count (`slc bench` over several
//! `--rsms`): log-log plots of each against the VPLs (`scaling_culling.svg`,
//! `scaling_shading.svg`) and each curve's slope, the exponent b of the least-squares fit
//! ms ≈ a·N^b over its points, so that "cost follows what is lit" reads as a number: b near 0
//! is flat in the VPLs, b = 1 linear in them.
use crate::plot::{log_log_plot_svg, PlotPoint, Series};
use crate::print::Style;
use serde::Serialize;
use slc_core::Strategy;
use std::fmt::Write;

/// One strategy timed on one frame: the medians of its culling and shading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub resolution: (u32, u32),
    pub strategy: Strategy,
    pub vpls: usize,
    pub culling_ms: f64,
    pub shading_ms: f64,
}

/// One curve's slopes: a strategy at one resolution over the VPL counts it ran at.
#[derive(Serialize, Clone, Debug, PartialEq)]
pub struct Slopes {
    pub resolution: String,
    pub strategy: &'static str,
    /// Distinct VPL counts the fit runs over.
    pub points: usize,
    pub vpls_min: usize,
    pub vpls_max: usize,
    /// The fitted exponents; `None` with fewer than two distinct counts or a time ≤ 0.
    pub culling: Option<f64>,
    pub shading: Option<f64>,
    pub culling_plus_shading: Option<f64>,
    /// Culling + shading at the most VPLs over that at the fewest.
    pub growth: Option<f64>,
    /// Culling + shading at the most VPLs over the fastest strategy's at the fewest VPLs run
    /// at this resolution: the ratio docs/many-vpls.md states its targets in.
    pub over_fastest_at_fewest: Option<f64>,
}

/// The slope b of the least-squares line through (ln x, ln y): y ≈ a·x^b. `None` with fewer
/// than two distinct x or where any value is not a positive finite number.
pub fn log_log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let ok = |v: f64| v.is_finite() && v > 0.0;
    if points.iter().any(|&(x, y)| !ok(x) || !ok(y)) {
        return None;
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(sx, sy), &(x, y)| (sx + x / n, sy + y / n));
    let (sxy, sxx) = logs.iter().fold((0.0, 0.0), |(sxy, sxx), &(x, y)| {
        (sxy + (x - mx) * (y - my), sxx + (x - mx) * (x - mx))
    });
    (sxx > 1e-12).then(|| sxy / sxx)
}

/// The curves of `samples`: one per (resolution, strategy), in the order they first appear,
/// each with its samples by ascending VPL count.
fn curves(samples: &[Sample]) -> Vec<((u32, u32), Strategy, Vec<Sample>)> {
    let mut curves: Vec<((u32, u32), Strategy, Vec<Sample>)> = Vec::new();
    for s in samples {
        match curves
            .iter_mut()
            .find(|(r, st, _)| *r == s.resolution && *st == s.strategy)
        {
            Some((_, _, c)) => c.push(*s),
            None => curves.push((s.resolution, s.strategy, vec![*s])),
        }
    }
    for (_, _, c) in &mut curves {
        c.sort_by_key(|s| s.vpls);
    }
    curves
}

/// The fastest culling + shading at the fewest VPLs run at `resolution` (`None` without
/// samples there).
fn fastest_at_fewest(samples: &[Sample], resolution: (u32, u32)) -> Option<f64> {
    let here = || samples.iter().filter(move |s| s.resolution == resolution);
    let fewest = here().map(|s| s.vpls).min()?;
    here()
        .filter(|s| s.vpls == fewest)
        .map(|s| s.culling_ms + s.shading_ms)
        .min_by(f64::total_cmp)
}

/// Each curve's slopes.
pub fn slopes(samples: &[Sample]) -> Vec<Slopes> {
    curves(samples)
        .into_iter()
        .map(|((w, h), strategy, c)| {
            let fit = |y: &dyn Fn(&Sample) -> f64| {
                log_log_slope(&c.iter().map(|s| (s.vpls as f64, y(s))).collect::<Vec<_>>())
            };
            let both = |s: &Sample| s.culling_ms + s.shading_ms;
            let (first, last) = (c[0], c[c.len() - 1]);
            let mut counts: Vec<usize> = c.iter().map(|s| s.vpls).collect();
            counts.dedup();
            Slopes {
                resolution: format!("{w}x{h}"),
                strategy: strategy.name(),
                points: counts.len(),
                vpls_min: first.vpls,
                vpls_max: last.vpls,
                culling: fit(&|s| s.culling_ms),
                shading: fit(&|s| s.shading_ms),
                culling_plus_shading: fit(&both),
                growth: (counts.len() > 1 && both(&first) > 0.0)
                    .then(|| both(&last) / both(&first)),
                over_fastest_at_fewest: fastest_at_fewest(samples, (w, h))
                    .filter(|&fastest| counts.len() > 1 && fastest > 0.0)
                    .map(|fastest| both(&last) / fastest),
            }
        })
        .collect()
}

/// The section of `bench.md` that gives the slopes.
pub fn markdown(slopes: &[Slopes]) -> String {
    let mut md = String::from(
        "\n## Against the VPL count\n\nEach strategy's culling and shading (medians) against \
         the VPLs, fitted as ms ≈ a·N^b by least squares on log-log axes: the slope b (0: flat \
         in the VPLs, 1: linear), culling + shading at the most VPLs over that at the \
         fewest, and over the fastest strategy's at the fewest VPLs of the resolution (the \
         ratio docs/many-vpls.md states its targets in). `scaling_culling.svg` and \
         `scaling_shading.svg` plot the points.\n\n\
         | resolution | strategy | VPLs | culling slope | shading slope | culling + shading \
         slope | culling + shading growth | over the fastest at the fewest |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    let slope = |b: Option<f64>| b.map_or("n/a".into(), |b| format!("{b:.2}"));
    for s in slopes {
        let _ = writeln!(
            md,
            "| {} | {} | {}–{} ({} counts) | {} | {} | {} | {} | {} |",
            s.resolution,
            s.strategy,
            s.vpls_min,
            s.vpls_max,
            s.points,
            slope(s.culling),
            slope(s.shading),
            slope(s.culling_plus_shading),
            s.growth.map_or("n/a".into(), |g| format!("{g:.1}×")),
            s.over_fastest_at_fewest
                .map_or("n/a".into(), |g| format!("{g:.2}×"))
        );
    }
    md
}

/// The two plots, `(name, svg)`: culling and shading ms against the VPLs, one curve per
/// strategy (and resolution, where there are several), each named with its slope from
/// `slopes` (the [`slopes`] of the same `samples`, curve by curve).
pub fn plots(
    samples: &[Sample],
    slopes: &[Slopes],
    scene: &str,
    backend: &str,
    style: &Style,
) -> Result<[(&'static str, String); 2], String> {
    let curves = curves(samples);
    let many_resolutions = curves.iter().any(|(r, _, _)| *r != curves[0].0);
    let plot = |pass: &str, ms: fn(&Sample) -> f64, fitted: fn(&Slopes) -> Option<f64>| {
        let series: Vec<Series> = curves
            .iter()
            .zip(slopes)
            .map(|(((w, h), strategy, c), fit)| {
                let slope = fitted(fit).map_or(String::new(), |b| format!(" ({b:.2})"));
                let at = if many_resolutions {
                    format!(" {w}x{h}")
                } else {
                    String::new()
                };
                Series {
                    name: format!("{}{at}{slope}", strategy.name()),
                    points: c
                        .iter()
                        .map(|s| PlotPoint::at(s.vpls as f64, ms(s)))
                        .collect(),
                }
            })
            .collect();
        log_log_plot_svg(
            &format!("{scene}, {backend}: {pass} against the VPLs (slope)"),
            "VPLs",
            &format!("{pass} ms"),
            &series,
            style,
        )
    };
    Ok([
        (
            "scaling_culling",
            plot("culling", |s| s.culling_ms, |f| f.culling)?,
        ),
        (
            "scaling_shading",
            plot("shading", |s| s.shading_ms, |f| f.shading)?,
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::print::PrintWidth;

    fn sample(strategy: Strategy, vpls: usize, culling_ms: f64, shading_ms: f64) -> Sample {
        Sample {
            resolution: (480, 270),
            strategy,
            vpls,
            culling_ms,
            shading_ms,
        }
    }

    /// A power law's exponent comes back exactly; noise about it leaves the fit near it; too
    /// few points or a time of 0 give none.
    #[test]
    fn the_slope_is_the_exponent_of_a_power_law() {
        let law = |b: f64| -> Vec<(f64, f64)> {
            [1e4, 5e4, 2e5, 8e5, 3.2e6]
                .iter()
                .map(|&n| (n, 0.3 * f64::powf(n, b)))
                .collect()
        };
        for b in [0.0, 0.25, 1.0, 1.5] {
            assert!((log_log_slope(&law(b)).unwrap() - b).abs() < 1e-12, "{b}");
        }
        let mut noisy = law(0.5);
        for (i, p) in noisy.iter_mut().enumerate() {
            p.1 *= if i % 2 == 0 { 1.05 } else { 0.95 };
        }
        assert!((log_log_slope(&noisy).unwrap() - 0.5).abs() < 0.05);
        assert_eq!(log_log_slope(&[(1e4, 3.0)]), None);
        assert_eq!(log_log_slope(&[(1e4, 3.0), (1e4, 5.0)]), None);
        assert_eq!(log_log_slope(&[(1e4, 3.0), (4e4, 0.0)]), None);
        assert_eq!(log_log_slope(&[(1e4, 3.0), (4e4, f64::NAN)]), None);
    }

    /// One curve per strategy, by ascending VPLs whatever the order they were run in; the
    /// growth is the last point's culling + shading over the first's, and the ratio over
    /// the fastest the last point's over the fastest strategy's first (at its resolution).
    #[test]
    fn each_strategy_gets_its_slopes_and_growth() {
        let samples = [
            sample(Strategy::Binned, 200_000, 20.0, 20.0),
            sample(Strategy::Ellipsoid, 50_000, 10.0, 10.0),
            sample(Strategy::Binned, 50_000, 20.0, 20.0),
            // Ellipsoid linear in the VPLs, binned flat.
            sample(Strategy::Ellipsoid, 200_000, 40.0, 40.0),
        ];
        let s = slopes(&samples);
        assert_eq!(s.len(), 2);
        assert_eq!((s[0].strategy, s[1].strategy), ("binned", "ellipsoid"));
        assert_eq!(
            (s[1].vpls_min, s[1].vpls_max, s[1].points),
            (50_000, 200_000, 2)
        );
        assert!((s[1].culling.unwrap() - 1.0).abs() < 1e-12);
        assert!((s[1].culling_plus_shading.unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(s[1].growth, Some(4.0));
        assert!(s[0].shading.unwrap().abs() < 1e-12);
        assert_eq!(s[0].growth, Some(1.0));
        // Over ellipsoid's 20 ms at 50,000 VPLs, the fastest there.
        assert_eq!(s[0].over_fastest_at_fewest, Some(2.0));
        assert_eq!(s[1].over_fastest_at_fewest, Some(4.0));
        let md = markdown(&s);
        assert!(
            md.contains(
                "| 480x270 | ellipsoid | 50000–200000 (2 counts) | 1.00 | 1.00 | 1.00 | 4.0× | \
                 4.00× |"
            ),
            "{md}"
        );
        // Another resolution's faster frames are not this one's fastest.
        let mut other = samples.to_vec();
        other.push(Sample {
            resolution: (960, 540),
            ..sample(Strategy::Binned, 50_000, 0.5, 0.5)
        });
        let with_other = slopes(&other);
        assert_eq!(with_other[0].over_fastest_at_fewest, Some(2.0));
        assert_eq!(with_other[2].over_fastest_at_fewest, None);
        // A strategy run only at more VPLs is held to the fastest at the resolution's fewest
        // (ellipsoid's 20 ms at 50,000), not at its own (its 10 ms at 200,000).
        let mut later = samples.to_vec();
        later.push(sample(Strategy::Tight, 200_000, 5.0, 5.0));
        later.push(sample(Strategy::Tight, 800_000, 30.0, 30.0));
        let tight = &slopes(&later)[2];
        assert_eq!(
            (tight.growth, tight.over_fastest_at_fewest),
            (Some(6.0), Some(3.0))
        );
        // One count: no slope, no growth.
        let one = slopes(&samples[1..2]);
        assert_eq!(
            (one[0].culling, one[0].growth, one[0].over_fastest_at_fewest),
            (None, None, None)
        );
        assert!(markdown(&one).contains("| n/a | n/a | n/a | n/a | n/a |"));
    }

    /// Each plot has a curve per strategy named with its slope, and a point per sample; with
    /// two resolutions each curve names its own.
    #[test]
    fn the_plots_name_each_curve_with_its_slope() {
        let plot = |samples: &[Sample]| {
            plots(
                samples,
                &slopes(samples),
                "sponza",
                "cpu",
                &PrintWidth::Screen.style(),
            )
            .unwrap()
        };
        let mut samples = vec![
            sample(Strategy::Tight, 10_000, 1.0, 2.0),
            sample(Strategy::Tight, 40_000, 4.0, 2.0),
        ];
        let [(culling, svg), (shading, _)] = plot(&samples);
        assert_eq!((culling, shading), ("scaling_culling", "scaling_shading"));
        assert!(svg.contains("tight (1.00)"), "{svg}");
        assert_eq!(svg.matches("<circle").count(), 2);
        samples.push(Sample {
            resolution: (960, 540),
            ..sample(Strategy::Tight, 10_000, 2.0, 4.0)
        });
        let [(_, svg), _] = plot(&samples);
        assert!(svg.contains("tight 480x270 (1.00)") && svg.contains("tight 960x540"));
    }
}
