//! Reflective shadow maps by rasterization, GPU twin of `slc_cpu_ref::rsm::trace_rsm` with
//! `TexelSample::Centre` (Dachsbacher and Stamminger's RSM, the VPL source of the paper's
//! section 4): a point light gets six cube faces, a spot light one pinhole face whose
//! half-angle is the outer cone angle (six faces beyond 80°), a directional light one
//! orthographic map over the scene's bounding sphere; faces, axes, texel layout
//! (face-major, then row-major from the top) and fluxes as on the CPU. Per face the
//! visibility pass (`frame::raster::visibility`) picks each texel's nearest triangle and
//! `rsm.wesl` intersects the texel-centre ray with it.
//!
//! Each texel's solid angle is a 3 x 3 Gauss-Legendre quadrature in f32 of the exact
//! integral the CPU evaluates in closed form in f64 (see `solid_angle.wesl`). The map's
//! depth (the first surface of every texel's ray, either side) is kept as a shadow map for
//! `frame::light::direct`.
use crate::device::buffers::{output, read_back, uniform};
use crate::device::context::{GpuContext, GpuError};
use crate::frame::light::records::{
    gpu_spot, GpuRsmParams, GpuRsmTexel, GpuShadowTexel, RSM_DIRECTIONAL, RSM_POINT, RSM_SPOT,
};
use crate::frame::raster::scene::GpuScene;
use crate::frame::raster::visibility::{RasterView, Resolve, VisibilityPass, VisibilityTarget};
pub use slc_core::rsm::{RsmFace, RsmLayout, SPOT_SINGLE_FACE_MAX_ANGLE};
use slc_core::Light;

/// The kernel of `rsm.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("rsm");

/// The largest RSM resolution per face (`RenderSettings::validate`).
pub const MAX_RESOLUTION: u32 = 4096;

/// One light's reflective shadow map on the GPU.
pub struct GpuRsm {
    pub light: Light,
    pub layout: RsmLayout,
    /// Texels per face side.
    pub resolution: u32,
    /// [`GpuRsmTexel`] per texel, face-major then row-major (row 0 at the top).
    pub texels: wgpu::Buffer,
    /// [`GpuShadowTexel`] per texel, the same layout.
    pub shadow: wgpu::Buffer,
}

impl GpuRsm {
    /// Number of texels (faces x resolution²).
    pub fn texel_count(&self) -> usize {
        self.layout.faces.len() * (self.resolution as usize).pow(2)
    }

    /// The texels, read back.
    pub fn read_texels(&self, ctx: &GpuContext) -> Result<Vec<GpuRsmTexel>, GpuError> {
        read_back(ctx, "rsm texels", &self.texels, self.texel_count())
    }

    /// The shadow map, read back.
    pub fn read_shadow(&self, ctx: &GpuContext) -> Result<Vec<GpuShadowTexel>, GpuError> {
        read_back(ctx, "shadow map", &self.shadow, self.texel_count())
    }
}

/// The compiled RSM pipelines (visibility and resolve).
pub struct RsmPass {
    visibility: VisibilityPass,
    resolve: wgpu::ComputePipeline,
}

impl RsmPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let visibility = VisibilityPass::new(ctx)?;
        ctx.scoped("rsm pipeline", || {
            Ok(Self {
                visibility,
                resolve: ctx.compute_pipeline("rsm resolve", SOURCE),
            })
        })
    }

    /// Renders `light`'s map of `resolution`² texels per face. Errors on an invalid light
    /// (`Light::is_valid`), a resolution outside 1..=[`MAX_RESOLUTION`] or beyond the
    /// adapter's texture or storage limits, and on device faults.
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        light: &Light,
        resolution: u32,
    ) -> Result<GpuRsm, GpuError> {
        if !light.is_valid() {
            return Err(GpuError::Input(format!(
                "light {light:?} has a non-finite or negative value"
            )));
        }
        if !(1..=MAX_RESOLUTION).contains(&resolution) {
            return Err(GpuError::Input(format!(
                "RSM resolution {resolution} is outside 1..={MAX_RESOLUTION}"
            )));
        }
        let layout = RsmLayout::new(light, scene.bounds);
        let n = resolution;
        let count = layout.faces.len() * (n as usize).pow(2);
        let texels = output::<GpuRsmTexel>(ctx, "rsm texels", count)?;
        let shadow = output::<GpuShadowTexel>(ctx, "shadow map", count)?;
        let target = VisibilityTarget::new(ctx, n, n)?;
        ctx.scoped("rsm", || {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rsm") });
            for (f, face) in layout.faces.iter().enumerate() {
                let view = RasterView {
                    origin: layout.origin,
                    right: face.right,
                    up: face.up,
                    forward: face.forward,
                    extent: (face.extent, face.extent),
                    orthographic: layout.orthographic,
                    offset: (0.5, 0.5),
                };
                self.visibility
                    .encode(ctx, &mut encoder, scene, &view, &target);
                let params = uniform(
                    ctx,
                    "rsm params",
                    &face_params(light, &layout, face, n, f as u32 * n * n),
                );
                Resolve {
                    label: "rsm resolve",
                    pipeline: &self.resolve,
                    params: &params,
                    outputs: &[&texels, &shadow],
                    groups: (n.div_ceil(8), n.div_ceil(8)),
                }
                .encode(ctx, &mut encoder, scene, &target);
            }
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        Ok(GpuRsm {
            light: light.clone(),
            layout,
            resolution: n,
            texels,
            shadow,
        })
    }
}

/// The resolve parameters of one face (`trace_rsm`'s per-texel constants, computed as the
/// CPU computes them).
fn face_params(
    light: &Light,
    layout: &RsmLayout,
    face: &RsmFace,
    n: u32,
    first: u32,
) -> GpuRsmParams {
    let texel_size = 2.0 / n as f32;
    let e = face.extent;
    let (kind, radiometry) = match *light {
        Light::Point { intensity, .. } => (RSM_POINT, intensity),
        Light::Spot { intensity, .. } => (RSM_SPOT, intensity),
        Light::Directional { irradiance, .. } => {
            let area = (texel_size * e) * (texel_size * e);
            (RSM_DIRECTIONAL, irradiance * area)
        }
    };
    let (spot, falloff) = gpu_spot(light);
    GpuRsmParams {
        origin: layout.origin.extend(e).to_array(),
        forward: face.forward.extend(texel_size).to_array(),
        right: face.right.extend(0.0).to_array(),
        up: face.up.extend(0.0).to_array(),
        light: radiometry.extend(0.0).to_array(),
        spot,
        info: [kind, n, first, 0],
        falloff: [falloff, 0.0, 0.0, 0.0],
    }
}
