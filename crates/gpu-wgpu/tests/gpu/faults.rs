//! Limits and faults: clear errors, no panics.
use crate::common::{gpu, own_gpu};
use slc_gpu_wgpu::device::buffers::{check_storage_size, output};
use slc_gpu_wgpu::vpl::records::RngSample;
use slc_gpu_wgpu::vpl::rng::{RngPass, RngQuery};
use slc_gpu_wgpu::GpuError;

#[test]
fn buffers_beyond_the_binding_limit_are_refused() {
    let Some(ctx) = gpu() else { return };
    let limit = ctx.limits.max_storage_buffer_binding_size;
    assert!(check_storage_size(&ctx, "ok", limit).is_ok());
    let e = output::<RngSample>(&ctx, "huge", (limit / 16 + 1) as usize).unwrap_err();
    assert!(matches!(e, GpuError::BufferTooLarge { size, .. } if size == limit + 16 - limit % 16));
    let text = e.to_string();
    assert!(
        text.contains("huge") && text.contains(&limit.to_string()),
        "{text}"
    );
    // A pass asked for too much output refuses before allocating.
    let pass = RngPass::new(&ctx).unwrap();
    let q = RngQuery {
        seed: 0,
        stream: 0,
        counter: 0,
        k: 1,
    };
    let too_many = u32::try_from(limit / 16 + 1).unwrap_or(u32::MAX);
    assert!(matches!(
        pass.run(&ctx, q, too_many),
        Err(GpuError::BufferTooLarge { .. })
    ));
    assert!(matches!(
        pass.run(&ctx, RngQuery { k: 0, ..q }, 4),
        Err(GpuError::Input(_))
    ));
}

#[test]
fn adapter_is_named_and_device_is_alive() {
    let Some(ctx) = gpu() else { return };
    assert!(!ctx.adapter_name.is_empty());
    ctx.check_lost().unwrap();
    ctx.wait().unwrap();
    eprintln!(
        "adapter: {}, timestamps: {}",
        ctx.adapter_name, ctx.timestamps
    );
}

/// A destroyed device reports itself lost: later work is an error, not a hang.
#[test]
fn device_loss_is_an_error() {
    // Its own device: the binary's shared one must survive.
    let Some(ctx) = own_gpu() else { return };
    ctx.device.destroy();
    let pass = RngPass::new(&ctx);
    let run = pass.and_then(|p| {
        p.run(
            &ctx,
            RngQuery {
                seed: 0,
                stream: 0,
                counter: 0,
                k: 1,
            },
            64,
        )
    });
    match run {
        Err(e @ GpuError::DeviceLost(_)) => {
            assert!(e.to_string().contains("--backend cpu"), "{e}");
        }
        other => panic!("expected a device-lost error, got {other:?}"),
    }
}

#[test]
fn no_adapter_message_suggests_the_cpu_backend() {
    let e = GpuError::NoAdapter("none".into());
    assert!(e.to_string().contains("--backend cpu"));
}
