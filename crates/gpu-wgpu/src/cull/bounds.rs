//! Per-VPL bounds in compute (`bounds.wesl`): for each VPL the bound the culling
//! strategies test, in the culling view of `slc_cull::view`, as `slc_cull`'s
//! `vpl_bounds.rs` computes it on the CPU: the sphere of section 6 for diffuse VPLs, and for
//! glossy VPLs the sphere r/α around q, the sphere r_u around c (section 7), or the GGX
//! spheroid of eq. (12)-(15) as its test space BS, BS·c (eq. 16-17), all grown by
//! `BOUND_SLACK`. The CPU validates the VPLs (as `slc_cull` does) before upload; the GPU
//! computes in f32 (the CPU in f64 where `slc_bounds` does), which the conformance test
//! bounds at relative 1e-5. [`BoundsPass::run_with_locals`] writes each sphere or spheroid
//! once more in world axes relative to its VPL ([`GpuLocalBound`], for `cull::binned`).
use crate::cull::frame::FrameVpls;
use crate::cull::raster::records::GpuBoundShape;
use crate::cull::records::{
    GpuBound, GpuView, BOUND_OVERFLOW, BOUND_SLACK, GLOSSY_ELLIPSOID, GLOSSY_ENCLOSING_SPHERE,
    GLOSSY_SPHERE, MAX_K,
};
use crate::cull::records::{GpuBoxBound, GpuLocalBound};
use crate::device::buffers::{output, per_binding, read_back};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::{ArgsPass, Count};
use crate::device::split_buffers::SplitBuffers;
use crate::vpl::buffers::VplBuffers;
use crate::vpl::records::vec4;
use slc_core::{Camera, Interleaving, Vpl};
use slc_cull::CullView;
use slc_cull::GlossyBound;

/// The binding numbers of the low and the high buffer of the bounds over boxes in
/// `box_bound_buffers.wesl`, past every other binding of `bounds.wesl` and `tight_cull.wesl`
/// but the VPLs' (`crate::vpl::buffers::VPL_BINDINGS`).
pub const BOX_BOUND_BINDINGS: [u32; 2] = [12, 13];

/// The kernel of `bounds.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("bounds");
const WORKGROUP: u32 = 64;

/// What the bounds depend on besides the VPLs: the camera and image size of the culling
/// view, δ of eq. (2) and the glossy bound.
#[derive(Clone, Copy, Debug)]
pub struct BoundsSettings<'a> {
    pub camera: &'a Camera,
    pub width: u32,
    pub height: u32,
    pub delta: f32,
    pub glossy: GlossyBound,
    /// The interleaved sampling of section 6: each bound records its VPL's subregion.
    pub interleaving: Interleaving,
    /// Whether each bound is written as a [`GpuBoundShape`] too (the raster baselines draw
    /// meshes around them).
    pub shapes: bool,
}

/// The bounds of a set of VPLs on the GPU, one [`GpuBound`] per VPL in input order, and for
/// [`GlossyBound::Tight`] one [`GpuBoxBound`] (what the tight refinement tests) per VPL,
/// with [`BoundsSettings::shapes`] one [`GpuBoundShape`] per VPL, from
/// [`BoundsPass::run_with_locals`] one [`GpuLocalBound`] per VPL.
pub struct GpuBounds {
    pub buffer: wgpu::Buffer,
    /// Over two bindings: Sponza's 1.6M VPLs of a 1024² RSM need 184 MB of them.
    pub box_bounds: SplitBuffers<GpuBoxBound>,
    pub shapes: wgpu::Buffer,
    pub locals: wgpu::Buffer,
    /// The VPLs as uploaded (`GpuVpl`), for the passes that shade them.
    pub vpls: VplBuffers,
    /// How many there are (the buffers hold its capacity).
    pub count: Count,
}

impl GpuBounds {
    /// The bounds buffer with the count of bounds it holds (what `cull::partition` reads).
    pub fn counted(&self) -> (&wgpu::Buffer, &Count) {
        (&self.buffer, &self.count)
    }
}

/// The compiled bounds pipeline.
pub struct BoundsPass {
    pipeline: wgpu::ComputePipeline,
    args: ArgsPass,
}

impl BoundsPass {
    /// The most VPLs whose bounds `ctx` holds: each per-VPL buffer of [`Self::run_with_locals`]
    /// in one binding (the bounds, shapes and local bounds), the bounds over boxes in two.
    pub fn most_vpls(ctx: &GpuContext) -> usize {
        per_binding::<GpuBound>(ctx)
            .min(per_binding::<GpuBoundShape>(ctx))
            .min(per_binding::<GpuLocalBound>(ctx))
            .min(2 * per_binding::<GpuBoxBound>(ctx))
    }

    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let args = ArgsPass::new(ctx)?;
        ctx.scoped("bounds pipeline", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("bounds", SOURCE),
                args,
            })
        })
    }

    /// The bounds of `vpls` (left on the GPU); VPLs on the CPU are validated and uploaded
    /// first ([`FrameVpls::records`]). VPLs generated on the GPU are bounded as many as they
    /// are, by an indirect dispatch sized there.
    pub fn run(
        &self,
        ctx: &GpuContext,
        vpls: FrameVpls,
        settings: &BoundsSettings,
    ) -> Result<GpuBounds, GpuError> {
        self.run_for(ctx, vpls, settings, false)
    }

    /// [`Self::run`], each VPL's sphere or spheroid written as a [`GpuLocalBound`] too.
    pub fn run_with_locals(
        &self,
        ctx: &GpuContext,
        vpls: FrameVpls,
        settings: &BoundsSettings,
    ) -> Result<GpuBounds, GpuError> {
        self.run_for(ctx, vpls, settings, true)
    }

    fn run_for(
        &self,
        ctx: &GpuContext,
        vpls: FrameVpls,
        settings: &BoundsSettings,
        locals: bool,
    ) -> Result<GpuBounds, GpuError> {
        let capacity = vpls.capacity();
        let count = u32::try_from(capacity)
            .map_err(|_| GpuError::Input(format!("{capacity} VPLs exceed u32 indices")))?;
        let vpl_buffer = vpls.records(ctx, settings.delta)?;
        let view = GpuView {
            locals: u32::from(locals),
            ..GpuView::new(settings, count)?
        };
        let bounds = output::<GpuBound>(ctx, "bounds", capacity)?;
        // Only the tight strategies' refinement reads the box bounds.
        let box_count = if settings.glossy == GlossyBound::Tight {
            capacity
        } else {
            1
        };
        let box_bounds = SplitBuffers::<GpuBoxBound>::output(ctx, "box bounds", box_count)?;
        let shape_count = if settings.shapes { capacity } else { 1 };
        let shapes = output::<GpuBoundShape>(ctx, "bound shapes", shape_count)?;
        let local_count = if locals { capacity } else { 1 };
        let local_bounds = output::<GpuLocalBound>(ctx, "local bounds", local_count)?;
        let vpl_count = vpls.count();
        ctx.submit("bounds", |encoder| {
            let at = std::mem::offset_of!(GpuView, count);
            let view_buffer = vpl_count.uniform(ctx, encoder, "bounds view", &view, at);
            let workgroups = vpl_count.workgroups(ctx, encoder, &self.args, 1, WORKGROUP)?;
            let mut buffers = vpl_buffer.with(&[&view_buffer, &bounds, &shapes, &local_bounds]);
            buffers.extend(box_bounds.at(BOX_BOUND_BINDINGS));
            ctx.encode_dispatch_at(encoder, "bounds", &self.pipeline, &buffers, workgroups);
            Ok(())
        })?;
        Ok(GpuBounds {
            buffer: bounds,
            box_bounds,
            shapes,
            locals: local_bounds,
            vpls: vpl_buffer,
            count: vpl_count,
        })
    }

    /// [`Self::run`] and read the bounds back; a bound that does not fit in f32 is an
    /// error, as on the CPU (`BoundsError::Overflow`).
    pub fn compute(
        &self,
        ctx: &GpuContext,
        vpls: &[Vpl],
        settings: &BoundsSettings,
    ) -> Result<Vec<GpuBound>, GpuError> {
        let gpu = self.run(ctx, FrameVpls::Cpu(vpls), settings)?;
        let bounds: Vec<GpuBound> = read_back(ctx, "bounds", &gpu.buffer, vpls.len())?;
        if let Some(b) = bounds.iter().find(|b| b.kind == BOUND_OVERFLOW) {
            return Err(GpuError::Input(format!(
                "the bound of VPL {} does not fit in f32 (extreme flux, delta or xi)",
                b.index
            )));
        }
        Ok(bounds)
    }
}

impl GpuView {
    /// The view of `settings` for `count` VPLs (the camera validated by [`CullView::new`]).
    pub fn new(settings: &BoundsSettings, count: u32) -> Result<Self, GpuError> {
        if !(1..=MAX_K).contains(&settings.interleaving.k) {
            return Err(GpuError::Input(format!(
                "interleaving factor K = {} must lie in 1..={MAX_K}",
                settings.interleaving.k
            )));
        }
        let view = CullView::new(settings.camera, settings.width, settings.height)
            .map_err(|e| GpuError::Input(e.to_string()))?;
        let r = view.rotation();
        Ok(Self {
            rotation: [
                vec4(r.x_axis, 0.0),
                vec4(r.y_axis, 0.0),
                vec4(r.z_axis, 0.0),
            ],
            eye: vec4(settings.camera.position, 0.0),
            delta: settings.delta,
            glossy: match settings.glossy {
                GlossyBound::Sphere => GLOSSY_SPHERE,
                GlossyBound::EnclosingSphere => GLOSSY_ENCLOSING_SPHERE,
                // The tight strategies cull with the spheroid first (`cull::tight`).
                GlossyBound::Ellipsoid | GlossyBound::Tight => GLOSSY_ELLIPSOID,
            },
            count,
            slack: BOUND_SLACK,
            k: settings.interleaving.k,
            seed: settings.interleaving.seed,
            box_bounds: u32::from(settings.glossy == GlossyBound::Tight),
            shapes: u32::from(settings.shapes),
            locals: 0,
            pad: [0; 3],
        })
    }
}
