//! The limits a device must allow for every pass to build ([`GpuContext::required_limits`]),
//! and the check that names each one a host's device falls short of
//! ([`GpuContext::check_limits`]) before any pass is built, instead of the first pipeline
//! that wgpu refuses.
use crate::device::context::{GpuContext, GpuError};

include!(concat!(env!("OUT_DIR"), "/kernels/limits.rs"));

impl GpuContext {
    /// The smallest limits on which every pass builds: WebGPU's defaults
    /// (`wgpu::Limits::default()`), with as many storage buffers per shader stage as the kernel
    /// that binds the most (12: VSGL building's emit, counted from the kernels by build.rs).
    /// A host that makes its own device for slc ([`Self::from_device`]) asks for at least
    /// these. Frames are held to the device's binding size: under these limits (128 MiB) as
    /// large as on lavapipe (`--rsm 1024`); a device with the adapter's own limits
    /// (`adapter.limits()`) runs the largest frames the adapter can.
    pub fn required_limits() -> wgpu::Limits {
        wgpu::Limits {
            max_storage_buffers_per_shader_stage: KERNEL_STORAGE_BUFFERS,
            ..wgpu::Limits::default()
        }
    }

    /// An error ([`GpuError::Limits`]) naming every limit of this device below
    /// [`Self::required_limits`], with the device's value and the one needed. The sizes of a
    /// storage binding and of a buffer are not checked here: they bound the frames, each
    /// refused by name where it needs more (`GpuError::BufferTooLarge`, and before any work
    /// by `GpuRenderer`'s frame-size check).
    pub fn check_limits(&self) -> Result<(), GpuError> {
        let needed = wgpu::Limits {
            max_storage_buffer_binding_size: self.limits.max_storage_buffer_binding_size,
            max_buffer_size: self.limits.max_buffer_size,
            ..Self::required_limits()
        };
        let mut short = Vec::new();
        needed.check_limits_with_fail_fn(&self.limits, false, |name, need, has| {
            short.push(format!("{name} is {has}, needs {need}"))
        });
        match short.is_empty() {
            true => Ok(()),
            false => Err(GpuError::Limits {
                adapter: self.adapter_name.clone(),
                short: short.join("; "),
            }),
        }
    }
}
