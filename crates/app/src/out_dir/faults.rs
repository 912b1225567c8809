//! Fail points: every change an output folder makes to the file system is a numbered step, so
//! a test can make step k fail (an I/O error, as a full disk or a missing permission gives) or
//! stop the run there as `kill -9` would (nothing after it happens, no clean-up), and check
//! that no step leaves a torn result. Outside tests no step fails.
use std::io;

/// What a test injects.
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// Step k fails with "no space left on device"; the run goes on handling the error.
    Fail(usize),
    /// The run is killed at step k: it and every later step do nothing.
    Kill(usize),
}

/// The steps taken so far, and the fault planned.
#[derive(Debug, Default)]
pub struct Faults {
    steps: usize,
    #[cfg(test)]
    plan: Option<Fault>,
}

impl Faults {
    #[cfg(test)]
    pub fn planned(fault: Fault) -> Self {
        Self {
            steps: 0,
            plan: Some(fault),
        }
    }

    /// Counts one step; an error where the plan makes it fail.
    pub fn step(&mut self) -> io::Result<()> {
        let k = self.steps;
        self.steps += 1;
        self.injected(k)
    }

    #[cfg(test)]
    fn injected(&self, k: usize) -> io::Result<()> {
        match self.plan {
            // ENOSPC, as a full disk gives it.
            Some(Fault::Fail(n)) if n == k => Err(io::Error::from_raw_os_error(28)),
            Some(Fault::Kill(n)) if k >= n => Err(io::Error::other("killed")),
            _ => Ok(()),
        }
    }

    #[cfg(not(test))]
    fn injected(&self, _: usize) -> io::Result<()> {
        Ok(())
    }

    /// Steps taken so far.
    #[cfg(test)]
    pub fn steps(&self) -> usize {
        self.steps
    }
}
