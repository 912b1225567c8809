//! Direct light with shadow maps (`direct.wesl`), the GPU twin of
//! `slc_cpu_ref::direct::shade_direct` with each shadow ray replaced by a lookup in the
//! light's RSM depth (`frame::light::rsm::GpuRsm::shadow`): per pixel of a G-buffer on the GPU,
//! `Σ f(ωl, ωo) E cos θl V` over the lights in scene order.
//!
//! Visibility, as chosen here (see `direct.wesl`): nearest texel, no filtering; the
//! occluder depth along the pixel's own light ray comes from the plane of the surface the
//! texel saw (its stored position and geometric normal), which removes self-shadowing of
//! flat receivers without a slope bias, falling back to the texel centre's depth where that
//! plane is nearly parallel to the ray; the bias is [`SHADOW_BIAS`] of the scene extent plus
//! [`SHADOW_BIAS_RELATIVE`] of the distance. What remains differs from the CPU's shadow rays
//! within about a texel of shadow boundaries (and where an occluder is thinner than a texel).
use crate::device::buffers::{output, read_back, uniform, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::frame::light::records::{
    gpu_spot, GpuDirectParams, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT,
};
use crate::frame::light::rsm::GpuRsm;
use crate::frame::raster::gbuffer::GpuGBuffer;
use crate::frame::raster::scene::GpuScene;
use glam::Vec3;
use slc_core::{Image, Light};

/// The kernel of `direct.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("direct");
const WORKGROUP: u32 = 64;

/// Absolute shadow bias relative to the scene extent (`GpuScene::extent`; the CPU lifts its
/// shadow rays by 2e-5 of it).
pub const SHADOW_BIAS: f32 = 1e-4;
/// Shadow bias relative to the distance from the light.
pub const SHADOW_BIAS_RELATIVE: f32 = 1e-4;

/// The compiled direct-light pipeline.
pub struct DirectPass {
    pipeline: wgpu::ComputePipeline,
}

impl DirectPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("direct pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("direct", SOURCE),
            })
        })
    }

    /// The direct light of `gbuffer` from the lights of `maps` (one RSM per light, in scene
    /// order, rendered from `scene`). Errors on an invalid light and on device faults.
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        gbuffer: &GpuGBuffer,
        maps: &[GpuRsm],
    ) -> Result<Image, GpuError> {
        let extent = scene.extent;
        let pixels = gbuffer.pixels();
        let out = output::<f32>(ctx, "direct image", 3 * pixels)?;
        let grid = Grid::for_items(ctx, pixels as u64, WORKGROUP)?;
        let params = maps
            .iter()
            .map(|map| light_params(map, pixels as u32, extent))
            .collect::<Result<Vec<_>, _>>()?;
        ctx.scoped("direct", || {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("direct"),
                });
            // The image starts at zero (wgpu zeroes new buffers); each light adds to it.
            for (p, map) in params.iter().zip(maps) {
                let p = uniform(ctx, "direct params", p);
                ctx.encode_dispatch(
                    &mut encoder,
                    "direct",
                    &self.pipeline,
                    &[
                        &p,
                        &gbuffer.samples,
                        &gbuffer.geometric_normals,
                        &map.shadow,
                        &out,
                        &gbuffer.positions,
                    ],
                    grid,
                );
            }
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let rgb: Vec<f32> = read_back(ctx, "direct image", &out, 3 * pixels)?;
        Ok(Image {
            width: gbuffer.width,
            height: gbuffer.height,
            pixels: rgb
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2]))
                .collect(),
        })
    }
}

fn light_params(map: &GpuRsm, pixels: u32, extent: f32) -> Result<GpuDirectParams, GpuError> {
    if !map.light.is_valid() {
        return Err(GpuError::Input(format!(
            "light {:?} has a non-finite or negative value",
            map.light
        )));
    }
    let (kind, light, radiometry) = match map.light {
        Light::Point {
            position,
            intensity,
        } => (LIGHT_POINT, position, intensity),
        Light::Spot {
            position,
            intensity,
            ..
        } => (LIGHT_SPOT, position, intensity),
        Light::Directional {
            direction,
            irradiance,
        } => (LIGHT_DIRECTIONAL, direction, irradiance),
    };
    let (spot, falloff) = gpu_spot(&map.light);
    let layout = &map.layout;
    let mut axes = [[0.0; 4]; 18];
    for (f, face) in layout.faces.iter().enumerate() {
        axes[3 * f] = face.forward.extend(0.0).to_array();
        axes[3 * f + 1] = face.right.extend(0.0).to_array();
        axes[3 * f + 2] = face.up.extend(0.0).to_array();
    }
    Ok(GpuDirectParams {
        light: light.extend(0.0).to_array(),
        spot,
        radiometry: radiometry.extend(falloff).to_array(),
        origin: layout.origin.extend(layout.faces[0].extent).to_array(),
        axes,
        info: [kind, layout.faces.len() as u32, map.resolution, pixels],
        shadow: [
            SHADOW_BIAS * extent,
            SHADOW_BIAS_RELATIVE,
            if layout.orthographic.is_some() {
                1.0
            } else {
                0.0
            },
            0.0,
        ],
    })
}
