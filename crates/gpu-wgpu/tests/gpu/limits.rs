//! The limits a host's device must allow (`GpuContext::required_limits`): every pass builds and
//! every strategy and VSGLs render on a device with exactly those limits (wgpu's downlevel
//! defaults, below WebGPU's in the limits the kernels do not need, raised where they need
//! more), a frame beyond its textures is refused by name, and a device below what the
//! kernels need is refused before any pass is built, each limit it falls short of named; a
//! scene whose RSMs and VPLs outgrow the bindings is refused before the frame's first pass,
//! with the largest `--rsm` that fits.
use crate::common::{device_with_limits, gpu, small_frame};
use slc_core::frame::{DiffuseEmission, Importance, LightSampling, Method, RenderSettings};
use slc_core::render::render;
use slc_core::{builtin, Strategy};
use slc_gpu_wgpu::{GpuContext, GpuError, GpuRenderer};

#[test]
fn every_pass_runs_within_the_required_limits() {
    let Some(shared) = gpu() else { return };
    let required = GpuContext::required_limits();
    if !required.check_limits(&shared.limits) {
        eprintln!("notice: the adapter allows less than GpuContext::required_limits()");
        return;
    }
    let ctx = device_with_limits(&shared, |_| required);
    // The docs name it: VSGL building's emit binds 12.
    assert_eq!(ctx.limits.max_storage_buffers_per_shader_stage, 12);
    // Below WebGPU's defaults (8192 and 64), which the kernels do not need.
    assert_eq!(ctx.limits.max_texture_dimension_2d, 2048);
    assert!(ctx.limits.max_inter_stage_shader_variables < 16);
    let renderer = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    let frames = (Strategy::ALL.into_iter().chain(Strategy::RASTER))
        .map(|s| small_frame(s, true))
        .chain([RenderSettings {
            method: Method::Vsgl(LightSampling {
                count: 256,
                importance: Importance::Bidirectional { camera_vsgls: 32 },
                diffuse: DiffuseEmission::ClampedCosine,
            }),
            ..small_frame(Strategy::None, true)
        }]);
    for settings in frames {
        let what = format!("{:?}", settings.method);
        let raster = matches!(&settings.method, Method::Stochastic(s) if s.strategy.is_raster());
        match render(&renderer, &scene, &settings, &|_| {}) {
            Ok(frame) => assert!(
                frame.indirect.pixels.iter().any(|p| p.max_element() > 0.0),
                "{what}: black"
            ),
            // An adapter without f32 blending refuses the raster baselines by capability.
            Err(e) if raster => assert!(e.to_string().contains("blend"), "{what}: {e}"),
            Err(e) => panic!("{what}: {e}"),
        }
    }
    // An image wider than the device's 2-D textures: refused before any work, by name.
    let wide = RenderSettings {
        width: 2049,
        height: 8,
        ..small_frame(Strategy::Ellipsoid, false)
    };
    let e = render(&renderer, &scene, &wide, &|_| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("2049x8 with RSM 16²: more than the 2048 texels a side"),
        "{e}"
    );
}

#[test]
fn a_device_below_the_required_limits_is_refused_naming_each() {
    let Some(shared) = gpu() else { return };
    // WebGPU's defaults allow 8 storage buffers per stage; one pass binds 12. Less workgroup
    // memory than a kernel declares is a second shortfall.
    let ctx = device_with_limits(&shared, |_| wgpu::Limits {
        max_compute_workgroup_storage_size: 8192,
        ..wgpu::Limits::default()
    });
    match GpuRenderer::from_context(ctx) {
        Err(e @ GpuError::Limits { .. }) => {
            let text = e.to_string();
            for named in [
                "max_storage_buffers_per_shader_stage is 8, needs 12",
                "max_compute_workgroup_storage_size is 8192, needs ",
                "GpuContext::required_limits()",
            ] {
                assert!(text.contains(named), "{text}");
            }
            assert_eq!(text.matches(" needs ").count(), 2, "{text}");
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("a device of 8 storage buffers per stage built every pass"),
    }
}

/// The built-in scene's spot light (1 face) and point light (a cube, 6 faces) on bindings of
/// 1 MiB: at RSM 64 their VPLs (7 x 64² x 2 records of 128 bytes, 7.3 MB) outgrow two bindings,
/// refused before the first pass with the largest RSM whose texels (6 x 34² per light) and
/// records (7 x 34² x 2 in two bindings of 8,192) fit; at RSM 16 it renders.
#[test]
fn a_scene_beyond_the_bindings_is_refused_before_its_first_pass() {
    let Some(shared) = gpu() else { return };
    let ctx = device_with_limits(&shared, |adapter| wgpu::Limits {
        max_storage_buffer_binding_size: 1 << 20,
        ..adapter
    });
    let renderer = GpuRenderer::from_context(ctx).unwrap();
    let scene = builtin("default").unwrap();
    let frame = |rsm_resolution| RenderSettings {
        width: 32,
        height: 24,
        rsm_resolution,
        ..small_frame(Strategy::Ellipsoid, false)
    };
    let e = render(&renderer, &scene, &frame(64), &|_| {})
        .unwrap_err()
        .to_string();
    for part in ["RSM 64² over 7 faces of 2 lights", "at most --rsm 34 here"] {
        assert!(e.contains(part), "{e}");
    }
    // No pass ran: the RSM pass would have refused its texels by buffer name.
    assert!(!e.contains("rsm texels"), "{e}");
    let frame = render(&renderer, &scene, &frame(16), &|_| {}).unwrap();
    assert!(frame.vpl_count > 2000, "{}", frame.vpl_count);
}
