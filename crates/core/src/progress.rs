//! What a long step reports and obeys while it works: how many pixel-passes it finished, and
//! whether it should stop. Every step of the renderer API that takes a [`Progress`] reports
//! to it and checks it between its tiles (or rows); the frame loop ([`crate::render()`]) and
//! the shaders check it between passes. A cancelled step returns
//! [`RenderError::Cancelled`].
//!
//! A closure `&|n| ...` is a monitor that never cancels; [`Cancel`] is a flag another thread
//! (a Ctrl-C handler, a user interface) raises, and [`Cancel::reporting`] pairs it with a
//! closure. `slc_core::render(&renderer, &scene, &settings, &cancel)` renders until the flag
//! is raised. A step of one's own checks the monitor the same way:
//!
//! ```
//! use slc_core::frame::RenderError;
//! use slc_core::progress::{Cancel, Progress};
//!
//! /// Rows of work, the monitor checked between them.
//! fn rows(progress: Progress) -> Result<(), RenderError> {
//!     for _row in 0..100 {
//!         progress.check()?;
//!         // ... one row of 64 pixels ...
//!         progress.advance(64);
//!     }
//!     Ok(())
//! }
//!
//! let cancel = Cancel::new();
//! assert!(rows(&cancel).is_ok());
//! cancel.clone().cancel(); // e.g. in a Ctrl-C handler on another thread
//! let report = |n| eprintln!("{n} more pixels");
//! let stopped = rows(&cancel.reporting(&report));
//! assert!(matches!(stopped, Err(RenderError::Cancelled)));
//! ```
use crate::frame::RenderError;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// What a step reports its work to and asks whether to go on.
pub trait Monitor: Sync {
    /// `done` more pixel-passes are finished.
    fn advance(&self, done: u64);

    /// Whether the work should stop (checked between tiles and passes).
    fn cancelled(&self) -> bool {
        false
    }

    /// [`RenderError::Cancelled`] when [`Monitor::cancelled`].
    fn check(&self) -> Result<(), RenderError> {
        if self.cancelled() {
            Err(RenderError::Cancelled)
        } else {
            Ok(())
        }
    }
}

/// A function of the pixel-passes finished is a monitor that never cancels.
impl<F: Fn(u64) + Sync> Monitor for F {
    fn advance(&self, done: u64) {
        self(done)
    }
}

/// What the steps of the renderer API take: `&|n| ...`, `&cancel`, or
/// `&cancel.reporting(&|n| ...)`.
pub type Progress<'a> = &'a dyn Monitor;

/// A cancellation flag shared by its clones: any of them raises it ([`Cancel::cancel`]), work
/// given any of them as its monitor stops at its next check. It stays raised until
/// [`Cancel::reset`].
#[derive(Clone, Debug, Default)]
pub struct Cancel {
    raised: Arc<AtomicBool>,
}

impl Cancel {
    /// A flag not raised.
    pub fn new() -> Self {
        Self::default()
    }

    /// Raises the flag: work watching it stops at its next check.
    pub fn cancel(&self) {
        self.raised.store(true, Ordering::Relaxed);
    }

    /// Whether the flag is raised.
    pub fn is_cancelled(&self) -> bool {
        self.raised.load(Ordering::Relaxed)
    }

    /// Lowers the flag, for the next piece of work.
    pub fn reset(&self) {
        self.raised.store(false, Ordering::Relaxed);
    }

    /// A monitor that reports to `report` and stops when this flag is raised.
    pub fn reporting<'a>(&'a self, report: &'a (dyn Fn(u64) + Sync)) -> Reporting<'a> {
        Reporting {
            cancel: self,
            report,
        }
    }
}

/// The flag alone: no reports, stops when raised.
impl Monitor for Cancel {
    fn advance(&self, _done: u64) {}

    fn cancelled(&self) -> bool {
        self.is_cancelled()
    }
}

/// A [`Cancel`] flag with a function the finished pixel-passes are reported to
/// ([`Cancel::reporting`]).
#[derive(Clone, Copy)]
pub struct Reporting<'a> {
    cancel: &'a Cancel,
    report: &'a (dyn Fn(u64) + Sync),
}

impl Monitor for Reporting<'_> {
    fn advance(&self, done: u64) {
        (self.report)(done)
    }

    fn cancelled(&self) -> bool {
        self.cancel.is_cancelled()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;

    #[test]
    fn a_closure_reports_and_never_cancels() {
        let done = AtomicU64::new(0);
        let progress: Progress = &|n| {
            done.fetch_add(n, Ordering::Relaxed);
        };
        progress.advance(3);
        progress.advance(4);
        assert_eq!(done.load(Ordering::Relaxed), 7);
        assert!(!progress.cancelled() && progress.check().is_ok());
    }

    #[test]
    fn a_clone_raises_the_flag_for_every_watcher_until_reset() {
        let cancel = Cancel::new();
        let done = AtomicU64::new(0);
        let report = |n| {
            done.fetch_add(n, Ordering::Relaxed);
        };
        let watching = cancel.reporting(&report);
        let progress: Progress = &watching;
        assert!(progress.check().is_ok());
        let other = cancel.clone();
        std::thread::scope(|s| {
            s.spawn(|| other.cancel());
        });
        assert!(cancel.is_cancelled() && progress.cancelled());
        assert!(matches!(progress.check(), Err(RenderError::Cancelled)));
        progress.advance(5);
        assert_eq!(
            done.load(Ordering::Relaxed),
            5,
            "reports go on after a cancel"
        );
        cancel.reset();
        assert!(!other.is_cancelled() && progress.check().is_ok());
    }
}
