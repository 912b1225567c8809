//! VPLs and the tight strategies' bounds over boxes over two storage bindings
//! (`device::split_buffers`): on a device whose bindings hold fewer VPL records, and fewer
//! bounds over boxes, than a frame makes, the frame renders the same images bit for bit (but for
//! clustered-raster's order of sums, which no two runs share) and counts
//! the same VPLs as on one whose bindings hold them all; records uploaded over two bindings
//! read back as they went in; VPLs beyond two bindings are refused by name.
use crate::common::{device_with_limits, gpu, small_frame};
use glam::Vec3;
use slc_core::frame::{Method, RenderSettings};
use slc_core::render::render;
use slc_core::{builtin, Strategy, Vpl, VplLobe};
use slc_gpu_wgpu::device::buffers::per_binding;
use slc_gpu_wgpu::vpl::buffers::VplBuffers;
use slc_gpu_wgpu::vpl::records::GpuVpl;
use slc_gpu_wgpu::{GpuContext, GpuError, GpuRenderer};

/// A device of the shared one's adapter whose storage bindings hold `bytes` at most.
fn narrow_gpu(shared: &GpuContext, bytes: u64) -> GpuContext {
    device_with_limits(shared, |adapter| wgpu::Limits {
        max_storage_buffer_binding_size: bytes,
        ..adapter
    })
}

/// Bindings of 256 KiB hold 2,048 VPL records: the built-in scene at RSM 16 makes some
/// 2,770 VPLs of both lobes (2,766 on lavapipe; room for 3,584), so some 700 lie in the
/// second buffer. Bounds of 80 bytes for the 3,584 would not fit one binding (287 KB), so the
/// count is read back and they are sized by it (`GpuVpls::fit_capacity`, 221 KB). The tight
/// strategies' bounds over boxes (112 bytes, 310 KB for 2,766) lie over two bindings of
/// 2,340 each. The G-buffer and the lists fit one binding at 32x24 (at 64x48 `binned`'s lists
/// needed 711 KB).
const NARROW: u64 = 256 * 1024;

#[test]
fn vpls_over_two_bindings_render_as_over_one() {
    let Some(wide) = gpu() else { return };
    let narrow = narrow_gpu(&wide, NARROW);
    assert_eq!(per_binding::<GpuVpl>(&narrow), 2048);
    let scene = builtin("default").unwrap();
    let strategies = Strategy::ALL.into_iter().chain(Strategy::RASTER);
    let (wide, narrow) = (
        GpuRenderer::from_context(wide).unwrap(),
        GpuRenderer::from_context(narrow).unwrap(),
    );
    for strategy in strategies {
        let mut settings = RenderSettings {
            width: 32,
            height: 24,
            ..small_frame(strategy, true)
        };
        // No metrics: splatting's lists for them would outgrow these bindings.
        if let Method::Stochastic(s) = &mut settings.method {
            s.metrics = false;
        }
        let (a, b) = (
            render(&wide, &scene, &settings, &|_| {}),
            render(&narrow, &scene, &settings, &|_| {}),
        );
        if strategy.is_raster() && a.is_err() {
            // An adapter without f32 blending refuses the raster baselines on both devices.
            assert!(b.is_err(), "{strategy}");
            continue;
        }
        let (a, b) = (a.unwrap(), b.unwrap_or_else(|e| panic!("{strategy}: {e}")));
        // More than the first buffer holds.
        assert!(a.vpl_count > 2048, "{strategy}: {} VPLs", a.vpl_count);
        assert_eq!(b.vpl_count, a.vpl_count, "{strategy}");
        // The count is read once: on the narrow device where it sized the bounds, and not
        // again for the frame's report.
        for frame in [&a, &b] {
            let count = frame
                .readback_bytes
                .as_ref()
                .and_then(|r| r.get("vpl count"));
            assert_eq!(count, Some(&12), "{strategy}");
        }
        let bits = |i: &slc_core::Image| {
            i.pixels
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert!(
            bits(&a.direct) == bits(&b.direct),
            "{strategy}: direct images differ"
        );
        if strategy == Strategy::ClusteredRaster {
            // Its nodes are ordered by atomics, differently from run to run on one device
            // too: the sums agree to their rounding.
            let worst = (a.indirect.pixels.iter().zip(&b.indirect.pixels))
                .map(|(x, y)| (*x - *y).abs().max_element() / y.abs().max_element().max(1e-6))
                .fold(0.0f32, f32::max);
            assert!(worst <= 1e-5, "{strategy}: {worst}");
        } else {
            assert!(
                bits(&a.indirect) == bits(&b.indirect),
                "{strategy}: indirect images differ"
            );
        }
        assert!(
            a.indirect.pixels.iter().any(|p| p.max_element() > 0.0),
            "{strategy}: black"
        );
    }
}

/// Records uploaded over two bindings, and generated into them, read back as they were; a
/// count beyond two bindings is refused, naming the buffer.
#[test]
fn records_over_two_bindings_read_back_whole() {
    let Some(wide) = gpu() else { return };
    let narrow = narrow_gpu(&wide, NARROW);
    let vpl = |i: usize| Vpl {
        position: Vec3::new(i as f32, 1.0, -2.0),
        normal: Vec3::Y,
        geometric_normal: Vec3::Y,
        omega_i: Vec3::Y,
        flux: Vec3::splat(0.5),
        brdf: slc_bounds::Brdf {
            kd: Vec3::splat(0.5),
            fresnel: slc_bounds::Fresnel::Schlick(Vec3::splat(0.04)),
            alpha: 0.3,
            anisotropy: None,
        },
        lobe: VplLobe::Diffuse,
        id: i as u32,
        xi: 0.5,
    };
    for count in [0, 1, 2047, 2048, 2049, 4096] {
        let records: Vec<GpuVpl> = (0..count)
            .map(|i| GpuVpl::new(&vpl(i), i, 1e-3).unwrap())
            .collect();
        let buffers = VplBuffers::upload(&narrow, "vpls", &records).unwrap();
        let back = buffers.read_back(&narrow, count).unwrap();
        assert!(back == records, "{count} records");
    }
    let records: Vec<GpuVpl> = (0..4097)
        .map(|i| GpuVpl::new(&vpl(i), i, 1e-3).unwrap())
        .collect();
    match VplBuffers::upload(&narrow, "vpls", &records) {
        Err(GpuError::BufferTooLarge { label, limit, .. }) => {
            assert!(label.contains("vpls") && limit == NARROW, "{label} {limit}")
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("4,097 records in two bindings of 2,048"),
    }
}
