//! Work that behaves as Python expects of a long call: it runs on a worker thread without the
//! GIL while the calling thread checks for signals and forwards progress. Ctrl-C (or any
//! signal whose handler raises) raises the [`Cancel`] flag the work watches between its tiles
//! and passes, waits for the work to stop, and raises the handler's exception
//! (`KeyboardInterrupt`); an exception raised by the progress callback stops the work the same
//! way and is raised in its place.
use crate::error;
use pyo3::prelude::*;
use slc_core::{Cancel, Progress};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc;
use std::time::Duration;

/// How often the calling thread checks for signals and reports progress.
const POLL: Duration = Duration::from_millis(40);

/// Where progress goes: `progress(done, total)`, called on the calling thread.
pub struct Reporter<'a> {
    pub callback: Option<&'a Py<PyAny>>,
    /// The pixel-passes the whole call does (a job may set it once it knows).
    pub total: &'a AtomicU64,
}

/// Runs `work` on a worker thread, given a monitor that counts its pixel-passes and is
/// cancelled by Ctrl-C; returns its result, or raises the exception that stopped it, or
/// `SlcError` with the library's message.
pub fn watched<T: Send>(
    py: Python<'_>,
    reporter: Reporter<'_>,
    work: impl FnOnce(Progress) -> Result<T, String> + Send,
) -> PyResult<T> {
    let cancel = Cancel::new();
    let done = AtomicU64::new(0);
    let count = |n| {
        done.fetch_add(n, Ordering::Relaxed);
    };
    let monitor = cancel.reporting(&count);
    let mut stopped_by: Option<PyErr> = None;
    let result = py.detach(|| {
        std::thread::scope(|s| {
            let (send, receive) = mpsc::channel();
            s.spawn(move || {
                // The receiver waits for this until the scope ends.
                let _ = send.send(work(&monitor));
            });
            let mut reported = None;
            loop {
                match receive.recv_timeout(POLL) {
                    Ok(result) => break Some(result),
                    Err(mpsc::RecvTimeoutError::Disconnected) => break None,
                    Err(mpsc::RecvTimeoutError::Timeout) => {}
                }
                if stopped_by.is_some() {
                    continue;
                }
                let now = done.load(Ordering::Relaxed);
                let checked = Python::attach(|py| {
                    py.check_signals()?;
                    report(py, &reporter, now, &mut reported)
                });
                if let Err(e) = checked {
                    cancel.cancel();
                    stopped_by = Some(e);
                }
            }
        })
    });
    if let Some(e) = stopped_by {
        return Err(e);
    }
    match result {
        Some(Ok(out)) => {
            let mut reported = None;
            report(py, &reporter, done.load(Ordering::Relaxed), &mut reported)?;
            Ok(out)
        }
        Some(Err(e)) => Err(error(e)),
        None => Err(error("the worker thread stopped without a result")),
    }
}

/// Calls the callback with `done` of the total, when it changed since `reported`.
fn report(
    py: Python<'_>,
    reporter: &Reporter,
    done: u64,
    reported: &mut Option<u64>,
) -> PyResult<()> {
    let Some(callback) = reporter.callback else {
        return Ok(());
    };
    if *reported == Some(done) {
        return Ok(());
    }
    *reported = Some(done);
    let total = reporter.total.load(Ordering::Relaxed);
    callback.call1(py, (done.min(total), total))?;
    Ok(())
}
