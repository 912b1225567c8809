//! VSGLs built on the GPU from the frame's RSMs where they lie (VSGL sections 4.1-4.3;
//! `vsgl_build.wesl`), the twin of `slc_cpu_ref::sampled_lights::sample_vsgls` with the
//! flux importance (`ImportanceMap::from_mip`) or the bidirectional one
//! (`slc_cpu_ref::vsgl::bidirectional_importance`). Nothing is read back: the VSGLs go to the
//! shading pass ([`crate::vsgl::shade`]) and the imperfect shadow maps
//! ([`crate::vsgl::ism::IsmPass::render_at`]) on the GPU, and the frame's faults and number of
//! lights come back with the shading's fault record.
//!
//! Three steps, named as the CPU's timings name them:
//! 1. [`VsglBuildPass::mip`] (`vsgl_mip`): each RSM texel's cluster sums (VSGL Fig. 4,
//!    `ClusterSums::from_texel`) at level 0 of one quadtree over the faces of every map, then
//!    each level from the one below (`Quadtree::fill_levels`), one dispatch per level. The
//!    positional buffers are kept as a weighted mean and a second moment about it, merged
//!    pairwise (Chan, Golub and LeVeque 1979): in f32 the CPU's plain sums would cancel.
//! 2. [`VsglBuildPass::bidirectional`] (`importance_map`, section 4.3 only): the G-buffer's
//!    own pyramid (`camera_rsm`), camera-side VSGLs sampled from it as in step 3, and each RSM
//!    texel's view mass (its flux times the radiance those VSGLs send it), summed up the tree.
//!    The flux importance needs nothing: it is the sums' positional weight.
//! 3. [`VsglBuildPass::sample`] (`light_sampling`): the CPU's stratified points warped down
//!    the tree of importance masses in parallel, one invocation per sample
//!    (`FilteredSampler::warp`, stopping where `N P(C) ≤ 1`); each tree texel counts the
//!    samples that reach it and keeps the first one's index; the first samples are numbered
//!    by a scan (`device::scan`) and each writes its cluster's VSGL (`Vsgl::from_sums`) scaled by
//!    `m / (N P(C))` at its number. The number of lights stays on the GPU ([`Count::Gpu`]):
//!    the shading and the imperfect shadow maps take it from there. The clusters and weights
//!    are the CPU's (up to the warp's f32 rounding at a branch's edge, and f32's points for
//!    more than about 2²³ samples); the lights are in the order of their first samples, where
//!    the CPU sorts them by cluster.
//!
//! The cluster sums are kept as five arrays of one field each, so that one storage binding
//! holds a fifth of the pyramid (16 bytes per tree texel): a point light's six faces at RSM
//! 512 fit lavapipe's 128 MiB per binding.
pub mod records;

use crate::cull::records::GpuCullStatus;
use crate::device::buffers::{output, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::{Count, GpuCount};
use crate::device::scan::ScanPass;
use crate::frame::light::rsm::GpuRsm;
use crate::frame::raster::gbuffer::GpuGBuffer;
use crate::vsgl::build::records::{GpuBuildParams, GpuTree, CLAMPED_DIFFUSE, COUNT_LIGHTS};
use crate::vsgl::shade::records::{GpuVsgl, GpuVsglStatus};
use crate::vsgl::shade::specular_table;
use crate::vsgl::shade::GpuVsgls;
use crate::vsgl::shade::ITERATIONS_PER_VSGL;
use slc_core::frame::DiffuseEmission;
use slc_core::vsgl::{point_shift, SampleSet};

/// The kernel of `vsgl_build.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("vsgl_build");
const WORKGROUP: u32 = 64;

/// The binding numbers of `vsgl_build.wesl` (each entry point binds those it uses).
const PARAMS: u32 = 0;
const STATUS: u32 = 1;
/// The first of the five arrays of cluster sums (2 to 6).
const SUMS: u32 = 2;
const VIEW: u32 = 7;
const MARKS: u32 = 8;
const HIT_NODE: u32 = 9;
const VSGLS: u32 = 10;
const CENTRES: u32 = 11;
const RSM_TEXELS: u32 = 12;
const SAMPLES: u32 = 13;
const POSITIONS: u32 = 14;
const NORMALS: u32 = 15;
const CAMERA_VSGLS: u32 = 16;
const SLOTS: u32 = 17;
/// The specular lobe's fit (`crate::vsgl::shade::specular_table`), bound by the entries that make SG
/// surfaces (texels, camera_texels, view).
const SPECULAR_TABLE: u32 = specular_table::BINDING;

/// The cluster sums of a tree, one array of `[f32; 4]` per field of
/// [`crate::vsgl::build::records::GpuSums`] (in its order), one element per tree texel.
pub type SumsBuffers = [wgpu::Buffer; 5];

/// Zeroed sums for `tree`.
fn sums_buffers(ctx: &GpuContext, tree: GpuTree) -> Result<SumsBuffers, GpuError> {
    let one = || output::<[f32; 4]>(ctx, "vsgl sums", tree.len());
    Ok([one()?, one()?, one()?, one()?, one()?])
}

/// The sums' bindings.
fn sums_bindings(sums: &SumsBuffers) -> [(u32, &wgpu::Buffer); 5] {
    let [a, b, c, d, e] = sums;
    [
        (SUMS, a),
        (SUMS + 1, b),
        (SUMS + 2, c),
        (SUMS + 3, d),
        (SUMS + 4, e),
    ]
}

/// The mipmapped RSMs of a frame on the GPU (VSGL section 4.1): the cluster sums of every
/// texel of one quadtree over the faces of all maps, map by map, and the frame's fault
/// record, which the later steps and the shading add to.
pub struct GpuMipRsm {
    /// The quadtree (the maps' resolution, their faces in order).
    pub tree: GpuTree,
    /// The cluster sums per tree texel.
    pub sums: SumsBuffers,
    /// The view mass per tree texel (section 4.3), once [`VsglBuildPass::bidirectional`] ran.
    pub view: Option<wgpu::Buffer>,
    /// The frame's [`GpuVsglStatus`].
    pub status: wgpu::Buffer,
}

/// How lights are sampled from a pyramid: `count` samples of the points of `seed`, `σ_v²`
/// floored at `sigma2_floor` (`slc_cpu_ref::sampled_lights::sigma2_floor`), the diffuse lobe
/// emitting as `diffuse` says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglSampling {
    pub count: u32,
    pub seed: u32,
    pub sigma2_floor: f32,
    pub diffuse: DiffuseEmission,
}

/// The compiled entry points of `vsgl_build.wesl`.
pub struct VsglBuildPass {
    texels: wgpu::ComputePipeline,
    camera_texels: wgpu::ComputePipeline,
    reduce_sums: wgpu::ComputePipeline,
    reduce_view: wgpu::ComputePipeline,
    view: wgpu::ComputePipeline,
    sample: wgpu::ComputePipeline,
    own: wgpu::ComputePipeline,
    emit: wgpu::ComputePipeline,
    scan: ScanPass,
    specular_table: wgpu::Buffer,
}

/// One step's commands (wgpu keeps the buffers they use alive until they ran).
struct Commands<'a> {
    ctx: &'a GpuContext,
    encoder: &'a mut wgpu::CommandEncoder,
}

impl Commands<'_> {
    /// One dispatch of `items` invocations of `pipeline` with `params` and `buffers` at their
    /// binding numbers.
    fn dispatch(
        &mut self,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        params: GpuBuildParams,
        buffers: &[(u32, &wgpu::Buffer)],
    ) -> Result<(), GpuError> {
        self.dispatch_counted(label, pipeline, params, buffers, None)
    }

    /// [`Self::dispatch`] whose `params.count` is `count` (one left on the GPU is copied in).
    fn dispatch_counted(
        &mut self,
        label: &'static str,
        pipeline: &wgpu::ComputePipeline,
        params: GpuBuildParams,
        buffers: &[(u32, &wgpu::Buffer)],
        count: Option<&Count>,
    ) -> Result<(), GpuError> {
        let grid = Grid::for_items(self.ctx, u64::from(params.items), WORKGROUP)?;
        let p = match count {
            Some(count) => count.uniform(
                self.ctx,
                self.encoder,
                label,
                &params,
                std::mem::offset_of!(GpuBuildParams, count),
            ),
            None => uniform(self.ctx, label, &params),
        };
        let mut bound = vec![(PARAMS, &p)];
        bound.extend_from_slice(buffers);
        self.ctx
            .encode_dispatch_at(self.encoder, label, pipeline, &bound, grid);
        Ok(())
    }
}

impl VsglBuildPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let entry = |label, name| ctx.compute_pipeline_entry(label, SOURCE, name);
        ctx.scoped("vsgl build pipelines", || {
            Ok(Self {
                texels: entry("vsgl_texels", "texels"),
                camera_texels: entry("vsgl_camera_texels", "camera_texels"),
                reduce_sums: entry("vsgl_reduce_sums", "reduce_sums"),
                reduce_view: entry("vsgl_reduce_view", "reduce_view"),
                view: entry("vsgl_view", "view"),
                sample: entry("vsgl_sample", "sample"),
                own: entry("vsgl_own", "own"),
                emit: entry("vsgl_emit", "emit"),
                scan: ScanPass::new(ctx),
                specular_table: specular_table::buffer(ctx),
            })
        })
    }

    /// Runs `f`'s dispatches in one command buffer (`label` for errors).
    fn submit<T>(
        &self,
        ctx: &GpuContext,
        label: &'static str,
        f: impl FnOnce(&mut Commands) -> Result<T, GpuError>,
    ) -> Result<T, GpuError> {
        ctx.submit(label, |encoder| f(&mut Commands { ctx, encoder }))
    }

    /// Step 1, the mipmapped RSMs (`MipRsm::build` of every map, Toksvig's mean map): level 0
    /// from the texels, then every level of the quadtree. The maps must share one resolution
    /// (a frame's do).
    pub fn mip(&self, ctx: &GpuContext, maps: &[GpuRsm]) -> Result<GpuMipRsm, GpuError> {
        let n = maps.first().map_or(1, |m| m.resolution);
        if let Some(m) = maps.iter().find(|m| m.resolution != n) {
            return Err(GpuError::Input(format!(
                "RSMs of resolutions {n} and {} in one frame",
                m.resolution
            )));
        }
        let faces: u32 = maps.iter().map(|m| m.layout.faces.len() as u32).sum();
        let tree = GpuTree::new(n, faces);
        let sums = sums_buffers(ctx, tree)?;
        let status = upload(ctx, "vsgl status", &[GpuVsglStatus::clear(0)])?;
        self.submit(ctx, "vsgl_mip", |c| {
            for (m, first_face, first_texel) in map_offsets(maps) {
                let params = map_params(tree, m, first_face, first_texel);
                let mut buffers = vec![
                    (STATUS, &status),
                    (RSM_TEXELS, &m.texels),
                    (SPECULAR_TABLE, &self.specular_table),
                ];
                buffers.extend(sums_bindings(&sums));
                c.dispatch("vsgl_texels", &self.texels, params, &buffers)?;
            }
            self.reduce(c, tree, &self.reduce_sums, &sums_bindings(&sums))
        })?;
        Ok(GpuMipRsm {
            tree,
            sums,
            view: None,
            status,
        })
    }

    /// Every level above 0 of `tree` from the one below, by `pipeline` on `pyramid`.
    fn reduce(
        &self,
        c: &mut Commands,
        tree: GpuTree,
        pipeline: &wgpu::ComputePipeline,
        pyramid: &[(u32, &wgpu::Buffer)],
    ) -> Result<(), GpuError> {
        for level in 1..tree.levels {
            let params = GpuBuildParams {
                tree,
                level,
                items: tree.faces * tree.size(level).pow(2),
                ..Default::default()
            };
            c.dispatch("vsgl_reduce", pipeline, params, pyramid)?;
        }
        Ok(())
    }

    /// Step 2 for the bidirectional importance (VSGL section 4.3,
    /// `bidirectional_importance`): `camera_vsgls` VSGLs sampled from the pyramid of
    /// `gbuffer` (`camera_rsm`: one square face, each pixel a surface of flux 1 lit from the
    /// camera) with the points of [`SampleSet::Camera`], then each texel of `maps` (those `mip`
    /// was built from) shaded by them from its light: its view mass, summed up the tree. The
    /// sampling of step 3 then mixes it with the flux importance
    /// (`slc_cpu_ref::vsgl::FLUX_SHARE`).
    pub fn bidirectional(
        &self,
        ctx: &GpuContext,
        mip: &mut GpuMipRsm,
        maps: &[GpuRsm],
        gbuffer: &GpuGBuffer,
        camera_vsgls: u32,
        sampling: &VsglSampling,
    ) -> Result<(), GpuError> {
        // Each RSM texel sums the light of every camera VSGL as a pixel sums the VSGLs.
        ctx.check_loop_budget(
            || format!("weighing the RSM texels by {camera_vsgls} camera VSGLs"),
            ITERATIONS_PER_VSGL * u64::from(camera_vsgls) + 64,
            "lower --camera-vsgls",
        )?;
        let (w, h) = (gbuffer.width, gbuffer.height);
        let camera_tree = GpuTree::new(w.max(h).max(1), 1);
        let camera_sums = sums_buffers(ctx, camera_tree)?;
        let view = output::<f32>(ctx, "vsgl view masses", mip.tree.len())?;
        let camera = &gbuffer.camera;
        let pixel_side = 2.0 * (0.5 * camera.yfov).tan() / h.max(1) as f32;
        let camera_sampling = VsglSampling {
            count: camera_vsgls,
            ..*sampling
        };
        let no_view = output::<f32>(ctx, "no view masses", 0)?;
        let status = &mip.status;
        let tree = mip.tree;
        self.submit(ctx, "vsgl_importance", |c| {
            let params = GpuBuildParams {
                tree: camera_tree,
                origin: camera.position.extend(pixel_side).to_array(),
                forward: camera.forward.extend(0.0).to_array(),
                items: w * h,
                width: w,
                ..Default::default()
            };
            let mut buffers = vec![
                (STATUS, status),
                (SAMPLES, &gbuffer.samples),
                (POSITIONS, &gbuffer.positions),
                (NORMALS, &gbuffer.geometric_normals),
                (SPECULAR_TABLE, &self.specular_table),
            ];
            buffers.extend(sums_bindings(&camera_sums));
            c.dispatch("vsgl_camera_texels", &self.camera_texels, params, &buffers)?;
            self.reduce(
                c,
                camera_tree,
                &self.reduce_sums,
                &sums_bindings(&camera_sums),
            )?;
            let pyramid = Pyramid {
                tree: camera_tree,
                sums: &camera_sums,
                view: None,
                status,
            };
            let (camera_lights, _, camera_count) = self.encode_sampling(
                c,
                &pyramid,
                &camera_sampling,
                SampleSet::Camera,
                0,
                &no_view,
            )?;
            for (m, first_face, first_texel) in map_offsets(maps) {
                let params = GpuBuildParams {
                    count: camera_vsgls,
                    ..map_params(tree, m, first_face, first_texel)
                };
                let buffers = [
                    (STATUS, status),
                    (VIEW, &view),
                    (RSM_TEXELS, &m.texels),
                    (CAMERA_VSGLS, &camera_lights),
                    (SPECULAR_TABLE, &self.specular_table),
                ];
                let count = Some(&camera_count);
                c.dispatch_counted("vsgl_view", &self.view, params, &buffers, count)?;
            }
            self.reduce(c, tree, &self.reduce_view, &[(VIEW, &view)])
        })?;
        mip.view = Some(view);
        Ok(())
    }

    /// Step 3, the lights: `sampling.count` samples of [`SampleSet::Lights`] warped down the
    /// importance of `mip` (its view masses mixed in where step 2 ran), each cluster reached
    /// once a VSGL, packed in the order of their first samples; their number stays on the
    /// GPU.
    pub fn sample(
        &self,
        ctx: &GpuContext,
        mip: GpuMipRsm,
        sampling: &VsglSampling,
    ) -> Result<GpuVsgls, GpuError> {
        let no_view = output::<f32>(ctx, "no view masses", 0)?;
        let (buffer, centres, count) = self.submit(ctx, "vsgl_sampling", |c| {
            let pyramid = Pyramid {
                tree: mip.tree,
                sums: &mip.sums,
                view: mip.view.as_ref(),
                status: &mip.status,
            };
            self.encode_sampling(
                c,
                &pyramid,
                sampling,
                SampleSet::Lights,
                COUNT_LIGHTS,
                &no_view,
            )
        })?;
        Ok(GpuVsgls {
            buffer,
            count,
            centres,
            status: mip.status,
        })
    }

    /// The sample, own, scan and emit dispatches of `sampling` over `pyramid`: the lights, their
    /// centres and their number. `no_view` stands in for the view masses of the flux
    /// importance.
    fn encode_sampling(
        &self,
        c: &mut Commands,
        pyramid: &Pyramid,
        sampling: &VsglSampling,
        set: SampleSet,
        flags: u32,
        no_view: &wgpu::Buffer,
    ) -> Result<(wgpu::Buffer, wgpu::Buffer, Count), GpuError> {
        let ctx = c.ctx;
        let count = sampling.count as usize;
        let vsgls = output::<GpuVsgl>(ctx, "vsgls", count)?;
        let centres = output::<[f32; 4]>(ctx, "vsgl centres", count)?;
        if count == 0 {
            return Ok((vsgls, centres, Count::Host(0)));
        }
        // Each light's draw sums the faces' masses (twice with the view) and descends the
        // tree from a face's root, a few iterations per face and level.
        let tree = pyramid.tree;
        ctx.check_loop_budget(
            || format!("sampling VSGLs over {} RSM faces", tree.faces),
            u64::from(tree.faces) * (3 + 4 * u64::from(tree.levels)) + 64,
            "use fewer lights",
        )?;
        let marks = output::<u32>(ctx, "vsgl sample marks", 2 * pyramid.tree.len())?;
        let hit_node = output::<u32>(ctx, "vsgl sample texels", count)?;
        let slots = output::<u32>(ctx, "vsgl light slots", count + 1)?;
        let scanned = upload(ctx, "vsgl light scan", &[GpuCullStatus::CLEAR])?;
        let clamped = match sampling.diffuse {
            DiffuseEmission::ClampedCosine => CLAMPED_DIFFUSE,
            DiffuseEmission::Sg => 0,
        };
        let params = GpuBuildParams {
            tree: pyramid.tree,
            items: sampling.count,
            count: sampling.count,
            bidirectional: u32::from(pyramid.view.is_some()),
            shift: point_shift(sampling.seed, set),
            sigma2_floor: sampling.sigma2_floor,
            flags: flags | clamped,
            ..Default::default()
        };
        let view = pyramid.view.unwrap_or(no_view);
        // The warp reads only the sums' positional weights (`flux_mass`).
        let weights = (SUMS + 1, &pyramid.sums[1]);
        let warp = [
            weights,
            (VIEW, view),
            (MARKS, &marks),
            (HIT_NODE, &hit_node),
        ];
        c.dispatch("vsgl_sample", &self.sample, params, &warp)?;
        let own = [(MARKS, &marks), (HIT_NODE, &hit_node), (SLOTS, &slots)];
        c.dispatch("vsgl_own", &self.own, params, &own)?;
        self.scan
            .encode(ctx, c.encoder, &slots, sampling.count, &scanned)?;
        let mut emit = vec![
            (STATUS, pyramid.status),
            (VIEW, view),
            (MARKS, &marks),
            (HIT_NODE, &hit_node),
            (VSGLS, &vsgls),
            (CENTRES, &centres),
            (SLOTS, &slots),
        ];
        emit.extend(sums_bindings(pyramid.sums));
        c.dispatch("vsgl_emit", &self.emit, params, &emit)?;
        // The scan appends the number of first samples, the lights, after the flags.
        let lights = Count::Gpu(GpuCount {
            buffer: slots,
            offset: 4 * count as u64,
            capacity: sampling.count,
        });
        Ok((vsgls, centres, lights))
    }
}

/// A pyramid the sampling reads: its tree, sums, view masses (bidirectional importance) and
/// the fault record it writes to.
struct Pyramid<'a> {
    tree: GpuTree,
    sums: &'a SumsBuffers,
    view: Option<&'a wgpu::Buffer>,
    status: &'a wgpu::Buffer,
}

/// Each map with its first face in the tree and its first texel over all maps.
fn map_offsets(maps: &[GpuRsm]) -> impl Iterator<Item = (&GpuRsm, u32, u32)> {
    maps.iter().scan((0u32, 0u32), |(face, texel), m| {
        let out = (m, *face, *texel);
        *face += m.layout.faces.len() as u32;
        *texel += m.texel_count() as u32;
        Some(out)
    })
}

/// The parameters of a per-texel dispatch over map `m`.
fn map_params(tree: GpuTree, m: &GpuRsm, first_face: u32, first_texel: u32) -> GpuBuildParams {
    let extent = m.layout.faces.first().map_or(1.0, |f| f.extent);
    GpuBuildParams {
        tree,
        origin: m.layout.origin.extend(extent).to_array(),
        items: m.texel_count() as u32,
        first_face,
        first_texel,
        orthographic: u32::from(m.layout.orthographic.is_some()),
        ..Default::default()
    }
}
