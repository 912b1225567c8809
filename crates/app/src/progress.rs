//! The progress bar of long commands.
use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `total` pixel-passes with a message. It ticks on its own, showing the time
/// spent, so a backend that reports work only at the end of a pass (the GPU's dispatches)
/// still shows that it runs.
pub fn bar(total: u64, message: String) -> ProgressBar {
    let bar = ProgressBar::new(total);
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} {msg} [{bar:40}] {percent}% ({elapsed} spent, {eta} left)",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar
}
