//! Per-pass GPU times from timestamp queries (`wgpu::Features::TIMESTAMP_QUERY`).
//!
//! While profiling is on ([`GpuContext::start_profiling`]), every compute pass recorded with
//! [`GpuContext::encode_dispatch`] and every render pass that asks for
//! [`GpuContext::render_timestamps`] writes a timestamp at its beginning and end. Each pass is
//! attributed to the stage named by the last [`GpuContext::set_stage`] call ("culling",
//! "shading", ...). [`GpuContext::finish_profiling`] resolves the queries and returns, per
//! stage, the sum of its passes' durations: the time the GPU spent executing that stage's
//! passes, without uploads, readbacks or the gaps between submissions.
//!
//! Adapters without timestamp queries (`GpuContext::timestamps == false`) record nothing and
//! report no stages; callers say so (the app's report does).
use crate::device::context::{GpuContext, GpuError};

/// At most this many timed passes per profile (two queries each; wgpu allows 4096 queries
/// per set). Passes beyond it run untimed and are counted in [`GpuProfile::untimed`].
pub const MAX_TIMED_PASSES: u32 = 2048;

/// The queries of one profile and what each pair of them belongs to.
pub(crate) struct Profiler {
    query_set: wgpu::QuerySet,
    stage: &'static str,
    /// (stage, pass label) of timed pass `i`, whose queries are `2i` and `2i + 1`.
    passes: Vec<(&'static str, &'static str)>,
    untimed: u32,
}

/// The resolved times of one profile.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GpuProfile {
    /// Per stage, in order of first use: the summed duration of its passes, in milliseconds.
    pub stages: Vec<(&'static str, f64)>,
    /// Per pass label, in order of first use: (stage, label, summed ms, number of passes).
    pub passes: Vec<(&'static str, &'static str, f64, u32)>,
    /// Passes that ran untimed because the profile was full ([`MAX_TIMED_PASSES`]).
    pub untimed: u32,
}

impl Profiler {
    fn new(ctx: &GpuContext) -> Self {
        let query_set = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("slc timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * MAX_TIMED_PASSES,
        });
        Self {
            query_set,
            stage: "gpu",
            passes: Vec::new(),
            untimed: 0,
        }
    }

    /// The query set and the index of the first of the two queries for a pass `label`, or
    /// `None` when the profile is full.
    fn allocate(&mut self, label: &'static str) -> Option<(wgpu::QuerySet, u32)> {
        if self.passes.len() as u32 >= MAX_TIMED_PASSES {
            self.untimed += 1;
            return None;
        }
        self.passes.push((self.stage, label));
        Some((self.query_set.clone(), 2 * (self.passes.len() as u32 - 1)))
    }
}

impl GpuContext {
    /// Starts timing passes (see the module documentation); returns whether this adapter has
    /// timestamp queries. A profile already running is discarded.
    pub fn start_profiling(&self) -> bool {
        let mut slot = self.profiler_slot();
        *slot = self.timestamps.then(|| Profiler::new(self));
        slot.is_some()
    }

    /// Attributes the passes recorded from now on to `stage`.
    pub fn set_stage(&self, stage: &'static str) {
        if let Some(p) = self.profiler_slot().as_mut() {
            p.stage = stage;
        }
    }

    /// Timestamp writes for a compute pass named `label`, while profiling.
    pub(crate) fn compute_timestamps(&self, label: &'static str) -> Option<(wgpu::QuerySet, u32)> {
        self.profiler_slot().as_mut()?.allocate(label)
    }

    /// Timestamp writes for a render pass named `label` while profiling (`None` otherwise):
    /// pass the query set and index to [`render_pass_writes`].
    pub fn render_timestamps(&self, label: &'static str) -> Option<(wgpu::QuerySet, u32)> {
        self.profiler_slot().as_mut()?.allocate(label)
    }

    /// Ends the profile: waits for the GPU, resolves the timestamps and sums them per stage
    /// and per pass. Without a running profile (no timestamp queries) the result is empty.
    pub fn finish_profiling(&self) -> Result<GpuProfile, GpuError> {
        let Some(profiler) = self.profiler_slot().take() else {
            return Ok(GpuProfile::default());
        };
        let count = 2 * profiler.passes.len() as u32;
        if count == 0 {
            return Ok(GpuProfile {
                untimed: profiler.untimed,
                ..Default::default()
            });
        }
        let ticks = self.resolve(&profiler.query_set, count)?;
        let period_ns = f64::from(self.queue.get_timestamp_period());
        let mut profile = GpuProfile {
            untimed: profiler.untimed,
            ..Default::default()
        };
        for (i, &(stage, label)) in profiler.passes.iter().enumerate() {
            let (begin, end) = (ticks[2 * i], ticks[2 * i + 1]);
            let ms = end.saturating_sub(begin) as f64 * period_ns * 1e-6;
            match profile.stages.iter_mut().find(|(s, _)| *s == stage) {
                Some((_, total)) => *total += ms,
                None => profile.stages.push((stage, ms)),
            }
            match profile
                .passes
                .iter_mut()
                .find(|(s, l, _, _)| *s == stage && *l == label)
            {
                Some((_, _, total, n)) => {
                    *total += ms;
                    *n += 1;
                }
                None => profile.passes.push((stage, label, ms, 1)),
            }
        }
        Ok(profile)
    }

    /// Resolves the first `count` queries of `set` and reads them back as ticks.
    fn resolve(&self, set: &wgpu::QuerySet, count: u32) -> Result<Vec<u64>, GpuError> {
        let size = u64::from(count) * 8;
        self.scoped("timestamp resolve", || {
            let resolved = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps resolved"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("timestamp resolve"),
                });
            encoder.resolve_query_set(set, 0..count, &resolved, 0);
            self.queue.submit([encoder.finish()]);
            crate::device::buffers::read_back::<u64>(self, "timestamps", &resolved, count as usize)
        })
    }

    fn profiler_slot(&self) -> std::sync::MutexGuard<'_, Option<Profiler>> {
        // A poisoned lock only means a panic elsewhere while profiling: keep the data.
        self.profiler
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

/// The render-pass form of a `(query set, first index)` pair from
/// [`GpuContext::render_timestamps`].
pub fn render_pass_writes(
    (set, index): &(wgpu::QuerySet, u32),
) -> wgpu::RenderPassTimestampWrites<'_> {
    wgpu::RenderPassTimestampWrites {
        query_set: set,
        beginning_of_pass_write_index: Some(*index),
        end_of_pass_write_index: Some(index + 1),
    }
}

/// The compute-pass form of a `(query set, first index)` pair.
pub(crate) fn compute_pass_writes(
    (set, index): &(wgpu::QuerySet, u32),
) -> wgpu::ComputePassTimestampWrites<'_> {
    wgpu::ComputePassTimestampWrites {
        query_set: set,
        beginning_of_pass_write_index: Some(*index),
        end_of_pass_write_index: Some(index + 1),
    }
}
