//! The headless wgpu device every pass runs on, and the errors of the GPU backend.
//!
//! Faults are errors, never panics or hangs:
//! - no adapter: [`GpuError::NoAdapter`], which suggests `--backend cpu`;
//! - device loss: wgpu's device-lost callback records the reason, and every wait
//!   ([`GpuContext::wait`]) is bounded by [`WAIT_TIMEOUT`] and checks the record, so a lost
//!   device gives [`GpuError::DeviceLost`] instead of a hang;
//! - validation and out-of-memory errors of a pass are caught in error scopes
//!   ([`GpuContext::scoped`]) and returned as [`GpuError::Wgpu`];
//! - a host's device below the limits the kernels need is refused before any pass is built,
//!   each limit named ([`GpuError::Limits`], `required_limits.rs`);
//! - buffers beyond `max_storage_buffer_binding_size` (128 MiB on lavapipe; or
//!   `max_buffer_size` where less, [`GpuContext::storage_limit`]) are refused before
//!   allocation ([`GpuError::BufferTooLarge`], see `buffers.rs`);
//! - more workgroups than one dispatch dimension allows are split into 2-D grids
//!   (`buffers::Grid`), and beyond 65535² workgroups refused ([`GpuError::TooManyWorkgroups`]).
use crate::device::buffers::{Grid, Workgroups};
use crate::device::profiler::Profiler;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The longest a wait for GPU work may take before it is reported as
/// [`GpuError::Timeout`]: a lost or wedged device must not hang the caller.
pub const WAIT_TIMEOUT: Duration = Duration::from_secs(120);

/// The most loop iterations one shader invocation runs, all its loops together, on Mesa's
/// llvmpipe (lavapipe): its JIT counts them against one limiter per invocation and, once it
/// runs out, ends every loop without an error (gallivm's `LP_MAX_TGSI_LOOP_ITERATIONS`).
/// Measured on the built-in scene with K = 1: lists of 65,701 unculled VPLs shaded within the
/// noise of the CPU's image, lists of 69,213 VPLs 2.2% dark, of 177,177 VPLs 22% dark.
pub const LLVMPIPE_LOOP_ITERATIONS: u64 = 65_535;

/// Everything that can go wrong in the GPU backend.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter found ({0}); install a Vulkan driver (on Debian: apt-get install \
         mesa-vulkan-drivers libvulkan1 for the software rasterizer lavapipe) or render with \
         --backend cpu"
    )]
    NoAdapter(String),
    #[error("the GPU adapter {adapter} refused the device: {reason}")]
    RequestDevice { adapter: String, reason: String },
    #[error(
        "the device on {adapter} allows less than slc's passes need ({short}); a host makes \
         its device with GpuContext::required_limits(), and where the adapter's own limits \
         are lower, render with --backend cpu"
    )]
    Limits { adapter: String, short: String },
    #[error("the GPU device was lost ({0}); results are unavailable, try --backend cpu")]
    DeviceLost(String),
    #[error("GPU work did not finish within {0:?} (device hung or lost)")]
    Timeout(Duration),
    #[error(
        "buffer {label:?} needs {size} bytes, more than the {limit} bytes one storage binding \
         allows on this adapter; lower the image size, --rsm or the light count, or render \
         with --backend cpu"
    )]
    BufferTooLarge {
        label: String,
        size: u64,
        limit: u64,
    },
    #[error(
        "{groups} workgroups exceed the {max} x {max} grid one dispatch allows; split the input"
    )]
    TooManyWorkgroups { groups: u64, max: u32 },
    #[error("wgpu error in {pass}: {message}")]
    Wgpu { pass: &'static str, message: String },
    #[error("reading back {label:?} failed: {message}")]
    Readback { label: String, message: String },
    #[error("invalid input to the GPU backend: {0}")]
    Input(String),
    #[error("light lists outgrew their buffer: {0}")]
    ListsOutgrown(String),
    #[error(
        "{what} would run up to {iterations} loop iterations in one shader invocation, more \
         than the {budget} after which the adapter {adapter} silently ends a shader's loops \
         (Mesa's llvmpipe); {remedy}, or render with --backend cpu"
    )]
    LoopBudget {
        what: String,
        iterations: u64,
        budget: u64,
        adapter: String,
        remedy: &'static str,
    },
}

/// A headless device and its queue, with what the passes need to know about the adapter.
pub struct GpuContext {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// The adapter's name, backend and driver ([`adapter_label`]).
    pub adapter_name: String,
    /// Whether the device was created with timestamp queries (for per-pass timings).
    pub timestamps: bool,
    /// Whether the device has subgroup operations (`Features::SUBGROUP`; the one-pass tiled
    /// kernel combines a subgroup's hits with them, `shade::tiled`).
    pub subgroups: bool,
    /// Whether the device rasterizes conservatively in hardware
    /// (`Features::CONSERVATIVE_RASTERIZATION`; the shell pass of `clustered-raster` draws
    /// its triangles with it, `cull::raster::clusters`).
    pub conservative_raster: bool,
    /// Whether those timestamps measure execution: false on CPU adapters, where lavapipe's
    /// stop bracketing the work of compute passes once a render pass has run (measured: 0.09
    /// ms of timestamp time for 1.1 s of compute, `tests/gpu/profile.rs`). Callers report
    /// wall clock instead.
    pub timestamps_trusted: bool,
    /// Whether the adapter rasterizes on the CPU ([`is_software_adapter`]).
    pub software: bool,
    /// The most loop iterations one shader invocation may run, where the adapter ends its
    /// loops after that many ([`LLVMPIPE_LOOP_ITERATIONS`] on Mesa's llvmpipe); `None`
    /// elsewhere.
    pub loop_budget: Option<u64>,
    /// The device's limits (storage binding size, workgroups per dimension, ...).
    pub limits: wgpu::Limits,
    lost: Arc<Mutex<Option<String>>>,
    /// The running timestamp profile, if any (`profiler.rs`).
    pub(crate) profiler: Mutex<Option<Profiler>>,
    /// Bytes read back from the device so far, by what was read ([`Self::readback_bytes`]).
    readback: Mutex<BTreeMap<String, u64>>,
}

impl GpuContext {
    /// The most bytes one storage buffer may hold and bind on this device: the storage
    /// binding size, or the buffer size where a host's device allows less of that
    /// (`max_buffer_size`). Every size check of the passes and of the frame is against it.
    pub fn storage_limit(&self) -> u64 {
        self.limits
            .max_storage_buffer_binding_size
            .min(self.limits.max_buffer_size)
    }

    /// Bytes read back from the device since the context was made, by the label of what was
    /// read (`buffers::read_back`): what a frame costs the bus beyond its passes.
    pub fn readback_bytes(&self) -> BTreeMap<String, u64> {
        self.readback.lock().map(|m| m.clone()).unwrap_or_default()
    }

    /// Counts `bytes` read back as `label`.
    pub(crate) fn count_readback(&self, label: &str, bytes: u64) {
        if let Ok(mut m) = self.readback.lock() {
            *m.entry(label.to_owned()).or_default() += bytes;
        }
    }

    /// An error ([`GpuError::LoopBudget`]) where one invocation of `what` may run
    /// `iterations` loop iterations and this adapter ends loops before that; `remedy` says
    /// what input to lower.
    pub fn check_loop_budget(
        &self,
        what: impl FnOnce() -> String,
        iterations: u64,
        remedy: &'static str,
    ) -> Result<(), GpuError> {
        match self.loop_budget {
            Some(budget) if iterations > budget => Err(GpuError::LoopBudget {
                what: what(),
                iterations,
                budget,
                adapter: self.adapter_name.clone(),
                remedy,
            }),
            _ => Ok(()),
        }
    }

    /// The warning every front end prints on a software adapter (None on a GPU): its times
    /// say nothing about a GPU.
    pub fn software_warning(&self) -> Option<String> {
        self.software.then(|| {
            format!(
                "the GPU adapter {} is a software rasterizer running on the CPU: GPU runs are \
                 slow here and their times say nothing about a GPU (the CPU backend is faster)",
                self.adapter_name
            )
        })
    }

    /// Opens the first adapter wgpu finds (any backend; `WGPU_BACKEND` and `WGPU_ADAPTER_NAME`
    /// choose one), with the adapter's own limits and, where available, timestamp queries.
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<Self, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                ..Default::default()
            })
            .await
            .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        // Timestamps for the profiles; f32 blending for splatting's sums (`cull::raster::splat`);
        // subgroup operations for the one-pass tiled kernel (`shade::tiled`);
        // conservative rasterization for clustered-raster's shell pass
        // (`cull::raster::clusters`).
        let required_features = adapter.features()
            & (wgpu::Features::TIMESTAMP_QUERY
                | wgpu::Features::FLOAT32_BLENDABLE
                | wgpu::Features::SUBGROUP
                | wgpu::Features::CONSERVATIVE_RASTERIZATION);
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("slc"),
                required_features,
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|e| GpuError::RequestDevice {
                adapter: adapter_label(&info),
                reason: e.to_string(),
            })?;
        let lost = Arc::new(Mutex::new(None));
        let record = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut slot) = record.lock() {
                *slot = Some(format!("{reason:?}: {message}"));
            }
        });
        Ok(Self {
            lost,
            ..Self::from_device(device, queue, &info)
        })
    }

    /// Runs on a device and queue the host already owns (an engine's, a viewer's), from the
    /// adapter `info` it was made on. The device must allow what the kernels need (ask for
    /// [`Self::required_limits`], or the adapter's own, `adapter.limits()`, where they are
    /// higher; `GpuRenderer::from_context` refuses a device below them by name,
    /// [`Self::check_limits`]) and, for per-pass GPU times,
    /// `Features::TIMESTAMP_QUERY`, for the one-pass tiled kernel's subgroup operations
    /// `Features::SUBGROUP`, for clustered-raster's hardware conservative rasterization
    /// `Features::CONSERVATIVE_RASTERIZATION`. The host keeps its device-lost callback: a lost device
    /// shows here as errors of the passes and waits, not through [`GpuError::DeviceLost`].
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, info: &wgpu::AdapterInfo) -> Self {
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Self {
            limits: device.limits(),
            subgroups: device.features().contains(wgpu::Features::SUBGROUP),
            conservative_raster: device
                .features()
                .contains(wgpu::Features::CONSERVATIVE_RASTERIZATION),
            device,
            queue,
            adapter_name: adapter_label(info),
            timestamps,
            timestamps_trusted: timestamps && info.device_type != wgpu::DeviceType::Cpu,
            software: is_software_adapter(info),
            loop_budget: is_llvmpipe(info).then_some(LLVMPIPE_LOOP_ITERATIONS),
            lost: Arc::new(Mutex::new(None)),
            profiler: Mutex::new(None),
            readback: Mutex::new(BTreeMap::new()),
        }
    }

    /// A second context on the same device and queue: its own timestamp profile
    /// ([`Self::start_profiling`]) and readback counts ([`Self::readback_bytes`]), the same
    /// device-lost record. Threads that each hold one share a device without sharing that
    /// state (the GPU tests of one binary do; wgpu's error scopes are per thread).
    pub fn share(&self) -> Self {
        Self {
            device: self.device.clone(),
            queue: self.queue.clone(),
            adapter_name: self.adapter_name.clone(),
            timestamps: self.timestamps,
            subgroups: self.subgroups,
            conservative_raster: self.conservative_raster,
            timestamps_trusted: self.timestamps_trusted,
            software: self.software,
            loop_budget: self.loop_budget,
            limits: self.limits.clone(),
            lost: Arc::clone(&self.lost),
            profiler: Mutex::new(None),
            readback: Mutex::new(BTreeMap::new()),
        }
    }

    /// [`GpuError::DeviceLost`] if the device-lost callback has fired.
    pub fn check_lost(&self) -> Result<(), GpuError> {
        match self.lost.lock().ok().and_then(|slot| slot.clone()) {
            Some(reason) => Err(GpuError::DeviceLost(reason)),
            None => Ok(()),
        }
    }

    /// Waits for all submitted work, at most [`WAIT_TIMEOUT`]; a lost device or a timeout
    /// is an error.
    pub fn wait(&self) -> Result<(), GpuError> {
        self.check_lost()?;
        let polled = self.device.poll(wgpu::PollType::Wait {
            submission_index: None,
            timeout: Some(WAIT_TIMEOUT),
        });
        self.check_lost()?;
        match polled {
            Ok(_) => Ok(()),
            Err(wgpu::PollError::Timeout) => Err(GpuError::Timeout(WAIT_TIMEOUT)),
            Err(e) => Err(GpuError::Wgpu {
                pass: "poll",
                message: e.to_string(),
            }),
        }
    }

    /// Runs `f` (pipeline creation, encoding, submission) inside validation and
    /// out-of-memory error scopes: a wgpu error raised there becomes [`GpuError::Wgpu`]
    /// naming `pass` instead of a panic in wgpu's default handler.
    pub fn scoped<T>(
        &self,
        pass: &'static str,
        f: impl FnOnce() -> Result<T, GpuError>,
    ) -> Result<T, GpuError> {
        self.check_lost()?;
        let memory = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let out = f();
        let errors = [
            pollster::block_on(validation.pop()),
            pollster::block_on(memory.pop()),
        ];
        if let Some(e) = errors.into_iter().flatten().next() {
            // A lost device makes every later call invalid: report the loss, not the symptom.
            // Polling (non-blocking) delivers a pending device-lost callback.
            let _ = self.device.poll(wgpu::PollType::Poll);
            self.check_lost()?;
            return Err(GpuError::Wgpu {
                pass,
                message: e.to_string(),
            });
        }
        self.check_lost()?;
        out
    }
}

impl GpuContext {
    /// A compute pipeline from WGSL `source` with entry point `main` and the layout naga
    /// derives from the shader (everything in bind group 0).
    pub fn compute_pipeline(&self, label: &'static str, source: &str) -> wgpu::ComputePipeline {
        self.compute_pipeline_entry(label, source, "main")
    }

    /// [`GpuContext::compute_pipeline`] with entry point `entry`.
    pub fn compute_pipeline_entry(
        &self,
        label: &'static str,
        source: &str,
        entry: &str,
    ) -> wgpu::ComputePipeline {
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        self.device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
    }

    /// Records one compute pass of `pipeline` over `workgroups` (a [`Grid`], or indirect
    /// arguments written on the GPU), with `buffers` bound at 0, 1, ... of group 0 (see
    /// [`GpuContext::bind_group`]); timed while profiling (`profiler.rs`).
    pub fn encode_dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[&wgpu::Buffer],
        workgroups: impl Into<Workgroups>,
    ) {
        let numbered: Vec<_> = (0u32..).zip(buffers.iter().copied()).collect();
        self.encode_dispatch_at(encoder, label, pipeline, &numbered, workgroups);
    }

    /// [`GpuContext::encode_dispatch`] with each buffer at the binding number given: for an
    /// entry point that uses some of a module's bindings (the layout naga derives holds only
    /// those).
    pub fn encode_dispatch_at(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[(u32, &wgpu::Buffer)],
        workgroups: impl Into<Workgroups>,
    ) {
        let bind = self.bind_group_at(label, pipeline, buffers);
        let timed = self.compute_timestamps(label);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: timed
                .as_ref()
                .map(crate::device::profiler::compute_pass_writes),
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind, &[]);
        match workgroups.into() {
            Workgroups::Grid(grid) => grid.dispatch(&mut pass),
            Workgroups::Indirect(args) => pass.dispatch_workgroups_indirect(&args, 0),
        }
    }

    /// The passes `f` records in one command buffer, submitted at once, checked as the pass
    /// `label` ([`GpuContext::scoped`]).
    pub fn submit<T>(
        &self,
        label: &'static str,
        f: impl FnOnce(&mut wgpu::CommandEncoder) -> Result<T, GpuError>,
    ) -> Result<T, GpuError> {
        self.scoped(label, || {
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
            let out = f(&mut encoder)?;
            self.queue.submit([encoder.finish()]);
            Ok(out)
        })
    }

    /// [`GpuContext::encode_dispatch`] in a command buffer of its own, submitted at once.
    pub fn dispatch(
        &self,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[&wgpu::Buffer],
        grid: Grid,
    ) {
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        self.encode_dispatch(&mut encoder, label, pipeline, buffers, grid);
        self.queue.submit([encoder.finish()]);
    }

    /// A bind group for group 0 of `pipeline` with `buffers` at bindings 0, 1, ...
    pub fn bind_group(
        &self,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[&wgpu::Buffer],
    ) -> wgpu::BindGroup {
        let numbered: Vec<_> = (0u32..).zip(buffers.iter().copied()).collect();
        self.bind_group_at(label, pipeline, &numbered)
    }

    /// A bind group for group 0 of `pipeline` with each buffer at the binding number given.
    pub fn bind_group_at(
        &self,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[(u32, &wgpu::Buffer)],
    ) -> wgpu::BindGroup {
        let entries: Vec<_> = buffers
            .iter()
            .map(|&(binding, b)| (binding, b.as_entire_binding()))
            .collect();
        crate::cull::raster::bind(self, label, &pipeline.get_bind_group_layout(0), &entries)
    }
}

/// The adapter as reports name it: its name, graphics API and driver (with the driver's
/// version where it gives one), e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, driver llvmpipe
/// Mesa 22.3.6)`.
pub fn adapter_label(info: &wgpu::AdapterInfo) -> String {
    let driver = [info.driver.as_str(), info.driver_info.as_str()]
        .into_iter()
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join(" ");
    if driver.is_empty() {
        format!("{} ({:?})", info.name, info.backend)
    } else {
        format!("{} ({:?}, driver {driver})", info.name, info.backend)
    }
}

/// Whether an adapter is Mesa's llvmpipe (lavapipe on Vulkan), whose loops end after
/// [`LLVMPIPE_LOOP_ITERATIONS`] per invocation.
pub fn is_llvmpipe(info: &wgpu::AdapterInfo) -> bool {
    let name = info.name.to_ascii_lowercase();
    name.contains("llvmpipe") || name.contains("lavapipe")
}

/// Whether an adapter rasterizes on the CPU: its type says so, or its name is one of the
/// software rasterizers (Mesa's llvmpipe/lavapipe and softpipe, Microsoft's WARP, SwiftShader).
pub fn is_software_adapter(info: &wgpu::AdapterInfo) -> bool {
    let name = info.name.to_ascii_lowercase();
    info.device_type == wgpu::DeviceType::Cpu
        || is_llvmpipe(info)
        || ["softpipe", "warp", "swiftshader"]
            .iter()
            .any(|s| name.contains(s))
}
