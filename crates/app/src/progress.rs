//! The progress bar of long commands, and the warning before a run of hours: once a second of
//! work has passed, a bar whose pace projects an hour or more says so (with the projected
//! time) while the run can still be stopped.
use indicatif::{ProgressBar, ProgressStyle};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Runs projected to take this long or longer are announced.
pub const LONG_RUN: Duration = Duration::from_secs(3600);

/// A progress bar that warns when its pace projects a run of [`LONG_RUN`] or more.
pub struct Bar {
    bar: ProgressBar,
    start: Instant,
    warned: AtomicBool,
    /// Whether the warning is printed (not for the hidden bars of library calls).
    warns: bool,
}

impl Bar {
    /// Counts `n` more units done.
    pub fn inc(&self, n: u64) {
        self.bar.inc(n);
        if !self.warns || self.warned.load(Ordering::Relaxed) {
            return;
        }
        let elapsed = self.start.elapsed();
        let (done, total) = (self.bar.position(), self.bar.length().unwrap_or(0));
        if let Some(w) = long_run_warning(&self.bar.message(), elapsed, done, total) {
            if !self.warned.swap(true, Ordering::Relaxed) {
                self.bar.suspend(|| eprintln!("warning: {w}"));
            }
        }
    }

    pub fn finish_and_clear(&self) {
        self.bar.finish_and_clear();
    }
}

/// The warning for work of which `done` of `total` units took `elapsed`, when it projects
/// [`LONG_RUN`] or more (judged after a second of work, not before).
pub fn long_run_warning(what: &str, elapsed: Duration, done: u64, total: u64) -> Option<String> {
    if elapsed < Duration::from_secs(1) || done == 0 || total <= done {
        return None;
    }
    let projected = elapsed.as_secs_f64() * total as f64 / done as f64;
    (projected >= LONG_RUN.as_secs_f64()).then(|| {
        format!(
            "{what}: at its pace so far ({:.1} s for {:.2}% of the work) this run takes about {}; stop it (Ctrl-C) and lower --spp, --repeat, --seeds, the size or the counts if that is not meant",
            elapsed.as_secs_f64(),
            100.0 * done as f64 / total as f64,
            duration_text(projected)
        )
    })
}

/// Seconds as hours or days.
fn duration_text(seconds: f64) -> String {
    match seconds / 3600.0 {
        h if h < 48.0 => format!("{h:.1} hours"),
        h if h < 24.0 * 730.0 => format!("{:.1} days", h / 24.0),
        h => format!("{:.0} years", h / (24.0 * 365.25)),
    }
}

/// [`bar`] when `show`, else a hidden bar that does not warn either (the Python package shows
/// progress only when asked).
pub fn bar_if(show: bool, total: u64, message: String) -> Bar {
    if show {
        bar(total, message)
    } else {
        Bar {
            bar: ProgressBar::hidden(),
            start: Instant::now(),
            warned: AtomicBool::new(false),
            warns: false,
        }
    }
}

/// A bar over `total` pixel-passes with a message. It ticks on its own, showing the time
/// spent, so a backend that reports work only at the end of a pass (the GPU's dispatches)
/// still shows that it runs.
pub fn bar(total: u64, message: String) -> Bar {
    let bar = ProgressBar::new(total);
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} {msg} [{bar:40}] {percent}% ({elapsed} spent, {eta} left)",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    Bar {
        bar,
        start: Instant::now(),
        warned: AtomicBool::new(false),
        warns: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_of_hours_is_announced_with_its_projected_time() {
        // --spp 4294967295 at 0.2 s a pass: the first pass projects 27 years.
        let s = Duration::from_secs_f64;
        let w = long_run_warning("render", s(1.0), 5, 5 * 4_294_967_295).unwrap();
        assert!(w.contains("136 years") && w.contains("Ctrl-C"), "{w}");
        let w = long_run_warning("render", s(2.0), 1, 3600).unwrap();
        assert!(w.contains("2.0 hours"), "{w}");
        let w = long_run_warning("render", s(2.0), 1, 3 * 24 * 3600).unwrap();
        assert!(w.contains("6.0 days"), "{w}");
        // Under an hour, before a second of work, or done: nothing.
        assert!(long_run_warning("render", s(2.0), 1, 1700).is_none());
        assert!(long_run_warning("render", s(0.5), 1, 1 << 40).is_none());
        assert!(long_run_warning("render", s(9.0), 10, 10).is_none());
    }
}
