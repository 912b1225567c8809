//! The device shared by the tests and the no-adapter policy, and the small stochastic frame
//! the renderer tests compare strategies on.
use glam::Vec3;
use slc_bounds::Fresnel;
use slc_core::frame::{LobeSelection, Method, RenderSettings, Stochastic};
use slc_core::Strategy;
use slc_core::{Camera, CullInput, GBuffer, Image, Interleaving, Vpl};
use slc_gpu_wgpu::cull::frame::FrameVpls;
use slc_gpu_wgpu::cull::lists::GpuLightLists;
use slc_gpu_wgpu::frame::raster::gbuffer::GpuGBuffer;
use slc_gpu_wgpu::shade::lists::{read_image, ShadePass, ShadedGBuffer};
use slc_gpu_wgpu::{GpuContext, GpuError};
use std::sync::OnceLock;

/// The device of this test binary, opened once: every test shares it (the suite runs with
/// as many test threads as cores; a device per test hung a GPU driver with 16 threads).
static DEVICE: OnceLock<Result<Option<GpuContext>, String>> = OnceLock::new();

/// A context for one test on the binary's shared device ([`GpuContext::share`]: its own
/// timestamp profile and readback counts). No adapter: with `CI` set the test fails (CI
/// installs lavapipe, so a missing adapter is a broken setup); otherwise a notice is printed
/// and `None` returned, and the test passes without checking anything. Any other device
/// error fails the test. (lavapipe warns when `XDG_RUNTIME_DIR` is unset; harmless, `.ci/run`
/// sets it.)
pub fn gpu() -> Option<GpuContext> {
    let shared = DEVICE.get_or_init(|| opened(GpuContext::new()).map_err(|e| e.to_string()));
    match shared {
        Ok(Some(ctx)) => Some(ctx.share()),
        Ok(None) => None,
        Err(e) => panic!("GPU device could not be created: {e}"),
    }
}

/// A device of its own, for a test that breaks it (device loss): the same policy as
/// [`gpu`].
pub fn own_gpu() -> Option<GpuContext> {
    opened(GpuContext::new()).unwrap_or_else(|e| panic!("GPU device could not be created: {e}"))
}

/// A device of the shared one's adapter (and its features) with the limits `limits` makes of
/// the adapter's own.
pub fn device_with_limits(
    shared: &GpuContext,
    limits: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
) -> GpuContext {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
    .expect("the shared device's adapter");
    let info = adapter.get_info();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("limits of a test's own"),
        required_features: adapter.features() & shared.device.features(),
        required_limits: limits(adapter.limits()),
        ..Default::default()
    }))
    .expect("a device with the test's limits");
    GpuContext::from_device(device, queue, &info)
}

/// The no-adapter policy of [`gpu`] applied to an opened device.
fn opened(ctx: Result<GpuContext, GpuError>) -> Result<Option<GpuContext>, GpuError> {
    match ctx {
        Ok(ctx) => Ok(Some(ctx)),
        Err(e @ GpuError::NoAdapter(_)) => {
            if std::env::var_os("CI").is_some() {
                panic!("CI is set but no GPU adapter was found: {e}");
            }
            eprintln!("notice: GPU test skipped, no adapter ({e})");
            Ok(None)
        }
        Err(e) => Err(e),
    }
}

/// The culling input of `gbuffer` seen from `camera` with `vpls`, δ of eq. (2) and the
/// interleaving `(k, seed)`.
pub fn cull_input<'a>(
    gbuffer: &'a GBuffer,
    camera: &'a Camera,
    vpls: &'a [Vpl],
    delta: f32,
    (k, seed): (u32, u32),
) -> CullInput<'a> {
    CullInput {
        gbuffer,
        camera,
        vpls,
        delta,
        interleaving: Interleaving { k, seed },
    }
}

/// A 64x48 frame of `strategy` (RSM 16², δ 1e-3, K 4, with metrics), denoised or not.
pub fn small_frame(strategy: Strategy, denoise: bool) -> RenderSettings {
    RenderSettings {
        width: 64,
        height: 48,
        rsm_resolution: 16,
        seed: 2,
        method: Method::Stochastic(Stochastic {
            delta: 1e-3,
            strategy,
            interleave: 4,
            denoise,
            metrics: true,
        }),
        visibility: false,
        spp: 1,
        lobes: LobeSelection::Both,
    }
}

/// `ShadePass::shade_on_gpu` of a G-buffer rendered on the GPU, read back.
pub fn shade_gpu_gbuffer<'a>(
    ctx: &GpuContext,
    shader: &ShadePass,
    gbuffer: &GpuGBuffer,
    vpls: impl Into<FrameVpls<'a>>,
    delta: f32,
    interleaving: Interleaving,
    lists: &GpuLightLists,
) -> Result<Image, GpuError> {
    let rgb = shader.shade_on_gpu(
        ctx,
        ShadedGBuffer::Gpu(gbuffer),
        vpls,
        delta,
        interleaving,
        lists,
    )?;
    read_image(ctx, &rgb, gbuffer.width, gbuffer.height)
}

/// The Fresnel of a crafted G-buffer's sample: Schlick with a coloured F0, or glass (η 1.5).
pub fn crafted_fresnel(schlick: bool) -> Fresnel {
    if schlick {
        Fresnel::Schlick(Vec3::new(0.04, 0.5, 0.95))
    } else {
        Fresnel::Dielectric(1.5)
    }
}

/// The diffuse colour of a crafted G-buffer's sample: black or an orange.
pub fn crafted_kd(black: bool) -> Vec3 {
    if black {
        Vec3::ZERO
    } else {
        Vec3::new(0.6, 0.4, 0.2)
    }
}
