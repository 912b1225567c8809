//! Repeated timings (`--repeat N`): one warm-up run, then N measured runs, each timing given
//! as its median, minimum and maximum, so noise is seen instead of landing in a table.
use crate::progress::long_run_warning;
use serde::Serialize;
use slc_core::Timings;

/// One timing over the measured runs, in milliseconds.
#[derive(Serialize, Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    /// Of at least one value (the median of an even count is the mean of the middle two).
    pub fn of(values: &[f64]) -> Self {
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        };
        Self {
            median,
            min: v[0],
            max: v[n - 1],
        }
    }

    /// A pass (or the sum of passes) over `runs`.
    pub fn of_passes(runs: &[Timings], passes: &[&str]) -> Self {
        let values: Vec<f64> = runs
            .iter()
            .map(|t| passes.iter().map(|p| t.get(p)).sum())
            .collect();
        Self::of(&values)
    }

    /// The sum of every pass over `runs`.
    pub fn of_totals(runs: &[Timings]) -> Self {
        Self::of(&runs.iter().map(Timings::total).collect::<Vec<_>>())
    }

    /// `median` alone for one run, else `median (min–max)`.
    pub fn text(&self, runs: usize) -> String {
        match runs {
            1 => format!("{:.1}", self.median),
            _ => format!("{:.1} ({:.1}–{:.1})", self.median, self.min, self.max),
        }
    }
}

/// Runs `run` once as a warm-up when `repeat` > 1 (its result is dropped), then `repeat`
/// times; returns the measured results in order. Warns when the first runs project a run of
/// hours ([`long_run_warning`]).
pub fn repeated<T>(
    repeat: u32,
    mut run: impl FnMut() -> Result<T, String>,
) -> Result<Vec<T>, String> {
    if repeat == 0 {
        return Err("--repeat must be at least 1".into());
    }
    let start = std::time::Instant::now();
    let total = u64::from(repeat) + u64::from(repeat > 1);
    if repeat > 1 {
        run()?;
    }
    let mut out = Vec::with_capacity(repeat as usize);
    for _ in 0..repeat {
        out.push(run()?);
        let done = u64::from(repeat > 1) + out.len() as u64;
        if done <= 2 {
            let w = long_run_warning("--repeat", start.elapsed(), done, total);
            if let Some(w) = w {
                eprintln!("warning: {w}");
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_min_max() {
        assert_eq!(
            Spread::of(&[5.0, 1.0, 3.0]),
            Spread {
                median: 3.0,
                min: 1.0,
                max: 5.0
            }
        );
        assert_eq!(Spread::of(&[4.0, 1.0, 2.0, 3.0]).median, 2.5);
        assert_eq!(Spread::of(&[7.0]).text(1), "7.0");
        assert_eq!(Spread::of(&[1.0, 2.0, 9.0]).text(3), "2.0 (1.0–9.0)");
    }

    #[test]
    fn one_warm_up_then_the_measured_runs() {
        let mut calls = 0;
        let runs = repeated(3, || {
            calls += 1;
            Ok(calls)
        })
        .unwrap();
        assert_eq!(runs, [2, 3, 4]);
        let mut single = 0;
        assert_eq!(
            repeated(1, || {
                single += 1;
                Ok(single)
            })
            .unwrap(),
            [1]
        );
        assert!(repeated(0, || Ok(())).is_err());
    }
}
