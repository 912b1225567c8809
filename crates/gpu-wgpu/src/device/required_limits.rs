//! The limits a device must allow for every pass to build ([`GpuContext::required_limits`]),
//! and the check that names each one a host's device falls short of
//! ([`GpuContext::check_limits`]) before any pass is built, instead of the first pipeline
//! that wgpu refuses.
use crate::device::context::{GpuContext, GpuError};

include!(concat!(env!("OUT_DIR"), "/kernels/limits.rs"));

impl GpuContext {
    /// The limits to ask of a device made for slc ([`Self::from_device`]): wgpu's downlevel
    /// defaults (`wgpu::Limits::downlevel_defaults()`, which nearly every adapter allows), each
    /// limit the kernels need more of raised to their need (build.rs counts it from every
    /// entry point: 12 storage buffers per shader stage for VSGL building's emit, workgroups of
    /// 256 invocations, ...). Frames are held to the device's storage binding and texture
    /// sizes, and refused by name beyond them: under these limits (128 MiB, 2048 texels) up to
    /// RSM 1024 and images of 2048 x 2048; a device with the adapter's own limits
    /// (`adapter.limits()`) runs the largest frames the adapter can.
    pub fn required_limits() -> wgpu::Limits {
        let mut limits = wgpu::Limits::downlevel_defaults();
        for (field, (_, need)) in kernel_fields(&mut limits).into_iter().zip(KERNEL_NEEDS) {
            *field = (*field).max(need);
        }
        limits
    }

    /// An error ([`GpuError::Limits`]) naming every limit of this device below what the
    /// kernels need (those [`Self::required_limits`] raises), with the device's value and the
    /// one needed. The other limits bound the frames, each refused by name where it needs more
    /// (`GpuError::BufferTooLarge`, and before any work `GpuRenderer`'s frame-size check).
    pub fn check_limits(&self) -> Result<(), GpuError> {
        let mut limits = self.limits.clone();
        let short: Vec<String> = (kernel_fields(&mut limits).into_iter().zip(KERNEL_NEEDS))
            .filter(|(has, (_, need))| **has < *need)
            .map(|(has, (name, need))| format!("{name} is {has}, needs {need}"))
            .collect();
        match short.is_empty() {
            true => Ok(()),
            false => Err(GpuError::Limits {
                adapter: self.adapter_name.clone(),
                short: short.join("; "),
            }),
        }
    }
}
