//! Driving the GPU renderer on a device the host made, as an engine or a viewer would: the
//! example opens its own wgpu adapter and device, hands clones of them to
//! `GpuContext::from_device`, renders the built-in default scene with the stochastic estimate
//! and the ellipsoid culler, and keeps using its device afterwards.
//!
//! `cargo run --release -p slc-gpu-wgpu --example host_device`; `cargo test` runs it too
//! (it needs a GPU adapter: lavapipe on machines without a GPU).
use slc_core::frame::{LobeSelection, Method, RenderSettings, Stochastic};
use slc_core::{builtin, Strategy};
use slc_gpu_wgpu::{GpuContext, GpuRenderer};

/// The host's own device: the first adapter, with the limits slc's passes need (wgpu's
/// downlevel defaults raised to what the kernels use; `adapter.limits()` instead allows the
/// largest frames the adapter can run).
fn host_device(
) -> Result<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo), Box<dyn std::error::Error>> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("host"),
        required_limits: GpuContext::required_limits(),
        ..Default::default()
    }))?;
    Ok((device, queue, adapter.get_info()))
}

/// Renders the default scene on the host's device; returns the mean total radiance.
fn run() -> Result<glam::Vec3, Box<dyn std::error::Error>> {
    let (device, queue, info) = host_device()?;
    let renderer = GpuRenderer::from_context(GpuContext::from_device(
        device.clone(),
        queue.clone(),
        &info,
    ))?;
    let scene = builtin("default").ok_or("no built-in default scene")?;
    let settings = RenderSettings {
        width: 96,
        height: 96,
        rsm_resolution: 16,
        seed: 0,
        method: Method::Stochastic(Stochastic {
            delta: 1e-3,
            strategy: Strategy::Ellipsoid,
            interleave: 4,
            denoise: true,
            metrics: false,
        }),
        visibility: false,
        spp: 1,
        lobes: LobeSelection::Both,
    };
    let frame = slc_core::render(&renderer, &scene, &settings, &|_| {})?;
    let mean = frame.total().mean();
    println!(
        "{} on {}: {} VPLs, mean total radiance {mean:.4}",
        scene.name, info.name, frame.vpl_count
    );
    // The host's device is still its own: make and fill a buffer after the frame.
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("host buffer"),
        size: 16,
        usage: wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    queue.write_buffer(&buffer, 0, &[1u8; 16]);
    queue.submit([]);
    device.poll(wgpu::PollType::wait_indefinitely())?;
    Ok(mean)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run().map(|_| ())
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_example_renders_on_the_hosts_device() {
        if std::env::var_os("CI").is_none() && slc_gpu_wgpu::GpuContext::new().is_err() {
            eprintln!("notice: no GPU adapter, example skipped");
            return;
        }
        let mean = super::run().unwrap();
        assert!(mean.is_finite() && mean.min_element() > 0.0, "{mean}");
    }
}
