//! The progress bar of long commands.
use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `total` pixel-passes with a message.
pub fn bar(total: u64, message: String) -> ProgressBar {
    let bar = ProgressBar::new(total);
    if let Ok(style) =
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent}% ({eta} left)")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar
}
