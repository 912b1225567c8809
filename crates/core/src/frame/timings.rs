//! Milliseconds per named pass.
use std::time::Instant;

/// Milliseconds per named pass, in the order the passes first ran, summed when a pass runs
/// again.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timings(pub Vec<(&'static str, f64)>);

impl Timings {
    /// Runs `f`, adding its wall-clock time to `name`.
    pub fn time<T>(&mut self, name: &'static str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        self.add(name, start.elapsed().as_secs_f64() * 1e3);
        out
    }

    pub fn add(&mut self, name: &'static str, ms: f64) {
        match self.0.iter_mut().find(|(n, _)| *n == name) {
            Some((_, t)) => *t += ms,
            None => self.0.push((name, ms)),
        }
    }

    pub fn merge(&mut self, other: &Timings) {
        for &(n, t) in &other.0 {
            self.add(n, t);
        }
    }

    /// Milliseconds of the pass `name` (0 if it did not run).
    pub fn get(&self, name: &str) -> f64 {
        self.0
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(0.0, |(_, v)| *v)
    }

    /// The sum of every pass.
    pub fn total(&self) -> f64 {
        self.0.iter().map(|(_, t)| t).sum()
    }
}

/// Adds `more` into `into`, creating it on first use: GPU timestamp times, present only on
/// adapters that have trustworthy ones.
pub fn merge_optional(into: &mut Option<Timings>, more: Option<&Timings>) {
    if let Some(t) = more {
        into.get_or_insert_with(Timings::default).merge(t);
    }
}

/// One kind of GPU pass in a timestamp profile: the stage it ran in ("culling", "shading",
/// ...), its label ("tiled shade", "bounds", ...), the summed milliseconds of its passes and
/// how many passes there were.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTime {
    pub stage: &'static str,
    pub pass: &'static str,
    pub ms: f64,
    pub count: u32,
}
