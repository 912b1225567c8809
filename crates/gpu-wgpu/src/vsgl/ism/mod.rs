//! Imperfect shadow maps (Ritschel et al. 2008, "Imperfect Shadow Maps for Efficient
//! Computation of Indirect Illumination") for the visibility `V(x_p, μ_v)` of VSGL eq. (3),
//! as Tokuyoshi 2015 section 5 uses them (there 64² per VSGL from 8192 points each): compute
//! only, no rasterization (`ism.wesl`, `ism_map.wesl`).
//!
//! * Caster points ([`caster_points`], on the CPU, deterministic): `points` samples over the
//!   scene's triangles (`slc_core::rng`, stream `ISM_CASTERS`), uniformly by area or, with
//!   `view`, denser near the eye (`crate::vsgl::ism::casters`), each a disc with the triangle's
//!   normal and the radius `footprint · sqrt(1 / (π M p(x)))`, `p` the points' density over the
//!   area (`1/A` when uniform) and M the points a map draws: `footprint` = 1 would tile the
//!   area exactly with M discs; the overlap closes the gaps a random point set leaves. Each map draws `points_per_map` of them, a run of the
//!   array from an offset of its own (a random subset, as the paper gives each VSGL, since the
//!   points are independent samples); with `points_per_map = points` all maps share them.
//! * Maps ([`IsmPass::render`]): per VSGL a full-sphere octahedral map of `resolution²`
//!   distances about `μ_v`; every point is projected into every map with `atomicMin` on the
//!   distance's f32 bits. A point writes its own texel with its distance and, within its disc's
//!   angular radius (at most `max_splat` texels away), each texel whose centre ray hits the
//!   disc with that ray's distance to it. Splats are clamped at the map border, not wrapped
//!   across the octahedral seams.
//! * Holes (`fill_levels` > 0): pull-push (Ritschel et al. 2008, section 3.3). A pyramid of
//!   levels 1..=fill_levels holds at each texel the mean depth of its 2×2 children where all
//!   but one of them are filled (a gap inside a surface; a silhouette against empty
//!   directions has fewer; at an odd map's border a parent has two children), and each empty
//!   texel of the map takes the depth of its nearest filled ancestor. Holes wider than
//!   2^fill_levels texels (open sky) stay empty.
//! * Lookup (`ism_visible` in `vsgl_shade.wesl`, used by
//!   [`crate::vsgl::shade::VsglShadePass`]'s visibility entry points): the receiver lifted by
//!   the tracer's epsilon along its geometric normal is visible when its distance to `μ_v` is
//!   at most the map's distance in its direction plus `lift + dist · (π/res) · (bias_constant +
//!   bias_slope · tan θ)` (θ the receiver's incidence, tan capped at 20).
//!
//! Imperfect by construction, so it differs from the CPU's shadow rays in known ways: light
//! leaks where the discs miss (thin or small occluders with few points, silhouettes, texels
//! no disc reaches); extra shadow where a disc overhangs its triangle's edge or one texel's
//! depth covers a whole texel's cone (contact regions, the bias); and the bias itself lets
//! occluders within it of the receiver cast no shadow. `tests/gpu/vsgl_visibility.rs`
//! measures the difference on the built-in scene.
pub mod casters;

use crate::device::buffers::{output, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::{ArgsPass, Count};
pub use crate::vsgl::ism::casters::caster_points;
use bytemuck::{Pod, Zeroable};
use core::f32::consts::PI;
use glam::Vec3;

/// The kernel of `ism.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("ism");

/// The kernel of `ism_fill.wesl`, linked with what it imports (build.rs).
const FILL_SOURCE: &str = kernel!("ism_fill");
const WORKGROUP: u32 = 64;

/// How the maps are built and read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IsmSettings {
    /// Caster points (the paper: 8192).
    pub points: u32,
    /// Texels per side of each octahedral map (the paper: 64).
    pub resolution: u32,
    /// Disc radius over `sqrt(1 / (π M p(x)))`, M = `points_per_map` and `p` the points'
    /// density over the area (`1/A` when uniform).
    pub footprint: f32,
    /// The widest splat, in texels from a point's own texel.
    pub max_splat: u32,
    /// The seed of the caster points.
    pub seed: u32,
    /// The tracer's surface offset (`Scene::ray_epsilon`).
    pub lift: f32,
    /// Depth bias in texel angles `π/res` times the receiver's distance, constant and times
    /// `tan θ` (see the module docs).
    pub bias_constant: f32,
    pub bias_slope: f32,
    /// The caster points each map draws (at most `points`; see the module docs). Set it with
    /// `points` when growing the pool: it does not follow it.
    pub points_per_map: u32,
    /// Pull-push levels of the hole filling (0: none; see the module docs).
    pub fill_levels: u32,
    /// The eye whose view the caster points adapt to (view-adaptive maps, Ritschel et al.
    /// 2011: density `∝ 1/max(d, near)²` at distance d from it, `crate::vsgl::ism::casters`); `None`:
    /// uniform by area.
    pub view: Option<Vec3>,
}

impl IsmSettings {
    /// The paper's sizes (8192 points, 64²) with the footprint and bias measured on the
    /// built-in scene (`tests/gpu/vsgl_visibility.rs`, `ism_settings_sweep`), for a scene
    /// whose tracer offset is `lift`. Every map shares the points, no hole is filled and the
    /// points are uniform: measured there against the CPU's shadow rays (mean / 99th percentile
    /// of the per-pixel error, commit 376466e's shading), the discs already close the surfaces
    /// (0.0738 / 0.498), pull-push adds false shadow where it fills open directions (one
    /// level: 0.0744 / 0.498), and per-map subsets of a 262,144-point pool change little
    /// (0.0742 / 0.516) for 32 times the points to sample. With the paper's one-texel points
    /// instead of discs, pull-push pays (65,536 pooled, 8192 per map: 0.0882 / 0.758 without,
    /// 0.0869 / 0.702 with two levels) but stays behind the discs. View-adaptive points
    /// ([`IsmSettings::view`]) do not pay there nor on Sponza (0.0743 / 0.524 and 0.328 / 2.46
    /// against 0.0738 / 0.498 and 0.298 / 2.57 uniform).
    pub fn paper(lift: f32) -> Self {
        Self {
            points: 8192,
            resolution: 64,
            footprint: 1.5,
            max_splat: 4,
            seed: 0,
            lift,
            bias_constant: 1.0,
            bias_slope: 1.0,
            points_per_map: 8192,
            fill_levels: 0,
            view: None,
        }
    }

    fn params(&self, point_count: u32, map_count: u32) -> GpuIsmParams {
        GpuIsmParams {
            point_count,
            map_count,
            resolution: self.resolution,
            max_splat: self.max_splat,
            texel_angle: PI / self.resolution as f32,
            lift: self.lift,
            bias_constant: self.bias_constant,
            bias_slope: self.bias_slope,
            points_per_map: self.points_per_map.min(point_count),
            fill_levels: self.fill_levels,
            pad: [0; 2],
        }
    }
}

/// Twin of `IsmParams` in `ism_map.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuIsmParams {
    pub point_count: u32,
    pub map_count: u32,
    pub resolution: u32,
    pub max_splat: u32,
    pub texel_angle: f32,
    pub lift: f32,
    pub bias_constant: f32,
    pub bias_slope: f32,
    pub points_per_map: u32,
    pub fill_levels: u32,
    pub pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuIsmParams>() == 48);

/// Twin of `Caster` in `ism.wesl`: a disc.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuCaster {
    /// Position (xyz), disc radius (w).
    pub position_radius: [f32; 4],
    /// Unit normal (xyz).
    pub normal: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuCaster>() == 32);

/// Imperfect shadow maps on the GPU: one per VSGL, in VSGL order.
pub struct ImperfectShadowMaps {
    /// `map_count · resolution²` f32 distances (bits; +inf: empty), map-major, rows of the
    /// octahedral map's v.
    pub depth: wgpu::Buffer,
    pub params: GpuIsmParams,
}

impl ImperfectShadowMaps {
    /// The maps' parameters as a uniform buffer (what the shading pass binds).
    pub(crate) fn params_buffer(&self, ctx: &GpuContext) -> wgpu::Buffer {
        uniform(ctx, "ism params", &self.params)
    }

    /// Reads the distances back (tests, debugging).
    pub fn read_back(&self, ctx: &GpuContext) -> Result<Vec<f32>, GpuError> {
        let n = self.params.map_count as usize * (self.params.resolution as usize).pow(2);
        crate::device::buffers::read_back(ctx, "ism depth", &self.depth, n)
    }
}

/// The compiled clear, splat and pull-push pipelines.
pub struct IsmPass {
    clear: wgpu::ComputePipeline,
    splat: wgpu::ComputePipeline,
    pull: wgpu::ComputePipeline,
    fill: wgpu::ComputePipeline,
    args: ArgsPass,
}

impl IsmPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let args = ArgsPass::new(ctx)?;
        ctx.scoped("ism pipelines", || {
            Ok(Self {
                clear: ctx.compute_pipeline_entry("ism_clear", SOURCE, "clear"),
                splat: ctx.compute_pipeline("ism_splat", SOURCE),
                pull: ctx.compute_pipeline_entry("ism_pull", FILL_SOURCE, "pull"),
                fill: ctx.compute_pipeline_entry("ism_fill", FILL_SOURCE, "fill"),
                args,
            })
        })
    }

    /// One map per centre `μ_v` of `centres` from `casters` (see [`caster_points`]).
    pub fn render(
        &self,
        ctx: &GpuContext,
        casters: &[GpuCaster],
        centres: &[Vec3],
        settings: &IsmSettings,
    ) -> Result<ImperfectShadowMaps, GpuError> {
        let maps = u32::try_from(centres.len())
            .map_err(|_| GpuError::Input(format!("{} ISMs exceed u32", centres.len())))?;
        let centres: Vec<[f32; 4]> = centres.iter().map(|c| c.extend(1.0).to_array()).collect();
        let centres = upload(ctx, "ism centres", &centres)?;
        self.render_at(ctx, casters, &centres, &Count::Host(maps), settings)
    }

    /// [`Self::render`] for `maps` centres already on the GPU (`[μ_v, ·]` per map, e.g.
    /// [`crate::vsgl::shade::GpuVsgls::centres`]), their number possibly left there too:
    /// the maps are allocated for its capacity and drawn for the count.
    pub fn render_at(
        &self,
        ctx: &GpuContext,
        casters: &[GpuCaster],
        centres: &wgpu::Buffer,
        maps: &Count,
        settings: &IsmSettings,
    ) -> Result<ImperfectShadowMaps, GpuError> {
        if !(1..=4096).contains(&settings.resolution) {
            return Err(GpuError::Input(format!(
                "ISM resolution {} outside 1..=4096",
                settings.resolution
            )));
        }
        if settings.fill_levels > 12 || settings.points_per_map == 0 {
            return Err(GpuError::Input(format!(
                "ISM fill levels {} above 12 or no points per map",
                settings.fill_levels
            )));
        }
        if !(settings.lift >= 0.0
            && settings.lift.is_finite()
            && settings.footprint >= 0.0
            && settings.footprint.is_finite()
            && settings.bias_constant.is_finite()
            && settings.bias_slope.is_finite())
        {
            return Err(GpuError::Input(format!(
                "ISM settings {settings:?} not finite"
            )));
        }
        // A point's splat walks the (2k + 1)² texels of its disc, k <= max_splat.
        let k = u64::from(settings.max_splat);
        ctx.check_loop_budget(
            || format!("splatting discs up to {k} texels wide into the ISMs"),
            (2 * k + 1).pow(2) + 2 * k + 64,
            "lower the ISM's max_splat",
        )?;
        let points = u32::try_from(casters.len())
            .map_err(|_| GpuError::Input(format!("{} caster points exceed u32", casters.len())))?;
        let capacity = maps.capacity();
        let per_map = settings.points_per_map.min(points);
        let texels = u64::from(capacity) * u64::from(settings.resolution).pow(2);
        let items = u64::from(capacity) * u64::from(per_map);
        if texels > u64::from(u32::MAX) || items > u64::from(u32::MAX) {
            return Err(GpuError::Input(format!(
                "{capacity} ISMs of {}² texels and {points} points exceed u32 indices",
                settings.resolution
            )));
        }
        let depth = output::<u32>(ctx, "ism depth", texels as usize)?;
        let params = settings.params(points, capacity);
        let out = ImperfectShadowMaps { depth, params };
        if texels == 0 {
            return Ok(out);
        }
        let caster_buf = upload(ctx, "ism casters", casters)?;
        let clear_grid = Grid::for_items(ctx, texels, WORKGROUP)?;
        ctx.submit("ism", |encoder| {
            // The passes bound their work by the map count, the GPU's where it lies there.
            let at = std::mem::offset_of!(GpuIsmParams, map_count);
            let params_buf = maps.uniform(ctx, encoder, "ism params", &params, at);
            ctx.encode_dispatch(
                encoder,
                "ism_clear",
                &self.clear,
                &[&params_buf, &out.depth],
                clear_grid,
            );
            if items > 0 {
                let splats = maps.workgroups(ctx, encoder, &self.args, per_map, WORKGROUP)?;
                ctx.encode_dispatch(
                    encoder,
                    "ism_splat",
                    &self.splat,
                    &[&params_buf, &out.depth, &caster_buf, centres],
                    splats,
                );
                self.pull_push(ctx, encoder, &out, &params_buf)?;
            }
            Ok(())
        })?;
        Ok(out)
    }
}

impl IsmPass {
    /// Encodes the pull-push hole filling of `maps` (nothing with `fill_levels` = 0): one pull
    /// per pyramid level, then the fill of the maps' empty texels.
    fn pull_push(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        maps: &ImperfectShadowMaps,
        params_buf: &wgpu::Buffer,
    ) -> Result<(), GpuError> {
        let p = maps.params;
        if p.fill_levels == 0 {
            return Ok(());
        }
        let size = |l: u32| u64::from(p.resolution.div_ceil(1 << l));
        let level_texels = |l: u32| u64::from(p.map_count) * size(l) * size(l);
        let pyramid_len: u64 = (1..=p.fill_levels).map(level_texels).sum();
        let pyramid = output::<f32>(ctx, "ism pyramid", pyramid_len.max(1) as usize)?;
        for l in 1..=p.fill_levels {
            let level = uniform(ctx, "ism pull level", &[l, 0, 0, 0]);
            ctx.encode_dispatch(
                encoder,
                "ism_pull",
                &self.pull,
                &[params_buf, &maps.depth, &pyramid, &level],
                Grid::for_items(ctx, level_texels(l), WORKGROUP)?,
            );
        }
        ctx.encode_dispatch(
            encoder,
            "ism_fill",
            &self.fill,
            &[params_buf, &maps.depth, &pyramid],
            Grid::for_items(ctx, level_texels(0), WORKGROUP)?,
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        SOURCE => {
            GpuIsmParams as "IsmParams",
            GpuCaster as "Caster",
        }
    }
}
