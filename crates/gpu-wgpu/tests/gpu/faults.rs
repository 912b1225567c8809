//! Limits and faults: clear errors, no panics.
use crate::common::{gpu, own_gpu};
use slc_gpu_wgpu::device::buffers::{check_storage_size, output};
use slc_gpu_wgpu::vpl::records::RngSample;
use slc_gpu_wgpu::vpl::rng::{RngPass, RngQuery};
use slc_gpu_wgpu::GpuError;

#[test]
fn buffers_beyond_the_binding_limit_are_refused() {
    let Some(ctx) = gpu() else { return };
    let limit = ctx.storage_limit();
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

/// Mesa's llvmpipe ends a shader invocation's loops after 65,535 iterations in all
/// (`LLVMPIPE_LOOP_ITERATIONS`): a tile walks every VPL of its subregion and an unculled list
/// holds them all, so beyond that the lists and the image came out short without an error
/// (unculled lists of 69,213 VPLs shaded 2.2% dark). There every list strategy refuses a
/// subregion of that many VPLs with the typed error naming the limit and what to raise;
/// elsewhere it culls them. With K = 2 (about 17,300 VPLs per subregion) each culls, and
/// misses no pair.
#[test]
fn subregions_beyond_the_adapters_loop_budget_are_refused() {
    use crate::common::cull_input;
    use crate::tiled::frame;
    use slc_core::{builtin, Strategy};
    use slc_cull::metrics::measure;
    use slc_gpu_wgpu::cull::{GpuCulling, ListCulling};
    let Some(ctx) = gpu() else { return };
    let culler = GpuCulling::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let (gbuffer, vpls) = frame(&scene, &camera, (16, 12), 80);
    assert!(vpls.len() > 68_000, "{}", vpls.len());
    for strategy in [Strategy::None, Strategy::Ellipsoid, Strategy::Binned] {
        let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (1, 0));
        match (culler.cull(&ctx, &input, strategy), ctx.loop_budget) {
            (Err(e @ GpuError::LoopBudget { .. }), Some(_)) => {
                let text = e.to_string();
                assert!(
                    text.contains(&vpls.len().to_string())
                        && text.contains("--interleave")
                        && text.contains("--backend cpu"),
                    "{text}"
                );
            }
            (Ok(_), None) => {}
            (got, budget) => panic!("{strategy:?} with a loop budget {budget:?}: {got:?}"),
        }
        let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (2, 0));
        let lists = culler.cull(&ctx, &input, strategy).unwrap();
        assert_eq!(
            measure(&input, &lists).unwrap().missed_pairs,
            0,
            "{strategy:?}"
        );
    }
}
