//! Clustered shading by conservative rasterization of bounding meshes \[OP16\], the paper's
//! Table 2 baseline (`--culling clustered-raster`): the clustered culler's bounds (written as
//! shapes too), partition and depth slices
//! ([`ClusteredCuller::prepare`](crate::cull::clustered::ClusteredCuller::prepare): 32
//! exponential slices of the G-buffer's depth range per 16 x 16 tile of each subregion), then
//! - the shell pass (`cluster_shell.wesl`): each VPL's 20-triangle mesh rasterized at
//!   tile resolution into its subregion's viewport, conservatively (in hardware where the
//!   adapter has `Features::CONSERVATIVE_RASTERIZATION`, else each triangle drawn as the
//!   cells around it; either way a cell is kept where the triangle meets it: lavapipe has
//!   only the software form), marking per VPL and tile the slices its surface spans;
//! - the fill pass (`cluster_fill.wesl`): each VPL joins the linked list of every
//!   occupied slice between its nearest and farthest mark, in a node buffer (`cull::raster::nodes`);
//! - shading (`node_shade.wesl`): each pixel walks its cluster's list.
//!
//! The node buffer's size is a guess (`cull::room`: the largest count seen so far); the count
//! is read with the frame's fault record after shading, and a frame whose nodes did not fit is
//! filled and shaded again with a buffer of that size. Sums follow the lists' order, which
//! the GPU's scheduling sets: images equal the list shading's up to f32 rounding.
use crate::cull::clustered::records::CLUSTER_SLICES;
use crate::cull::clustered::{ClusteredCuller, PreparedClusters};
use crate::cull::frame::{read_status, CullFrame};
use crate::cull::list_passes::TileLayout;
use crate::cull::lists::GpuLightLists;
use crate::cull::raster::mesh::BoundMesh;
use crate::cull::raster::nodes::NodeLists;
use crate::cull::raster::records::GpuRasterParams;
use crate::cull::raster::{atlas, bind, render_pipeline, Rasterization, SubregionDraws};
use crate::cull::room::ListRoom;
use crate::device::buffers::{output, read_back, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::ArgsPass;
use crate::shade::records::GpuShadeParams;
use slc_core::TILE_SIZE;
use slc_cull::GlossyBound;
use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};

/// The kernel of `cluster_shell.wesl`, linked with what it imports (build.rs).
pub(crate) const SHELL_SOURCE: &str = kernel!("cluster_shell");

/// The kernel of `cluster_fill.wesl`, linked with what it imports (build.rs).
pub(crate) const FILL_SOURCE: &str = kernel!("cluster_fill");

/// The kernel of `node_shade.wesl`, linked with what it imports (build.rs).
pub(crate) const SHADE_SOURCE: &str = kernel!("node_shade");

/// The shell pass's target: only its size matters (the fragments write storage).
const SHELL_TARGET: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// The byte offset of the VPL count in [`GpuRasterParams`].
const VPL_COUNT_AT: usize = std::mem::offset_of!(GpuRasterParams, vpl_count);

/// Vertices each mesh triangle is drawn with (its cover: two triangles).
const COVER_VERTICES: u32 = 6;

/// The rasterized clusters' pipelines.
pub struct ClusterRasterizer {
    mesh: wgpu::Buffer,
    mesh_triangles: u32,
    draws: SubregionDraws,
    /// The shell pass with conservative rasterization in software (`vs_main`).
    shell: wgpu::RenderPipeline,
    /// The shell pass with the adapter's conservative rasterization (`vs_conservative`),
    /// where it has it.
    hardware_shell: Option<wgpu::RenderPipeline>,
    /// Whether the shell pass draws with `hardware_shell`.
    hardware: AtomicBool,
    fill: wgpu::ComputePipeline,
    shade: wgpu::ComputePipeline,
    /// The largest node count seen: the next frame's buffer.
    room: ListRoom,
    args: ArgsPass,
}

/// A frame's rasterized clusters: the clustered culler's frusta and the lists in their
/// node buffer (replaced when a refill needs a larger one).
pub struct NodeFrame {
    pub clusters: PreparedClusters,
    /// Per VPL slot and tile, the slices its mesh reached (the shell pass's output).
    pub cells: wgpu::Buffer,
    pub params: GpuRasterParams,
    pub lists: RefCell<NodeLists>,
}

impl ClusterRasterizer {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let mesh = BoundMesh::icosphere(0);
        let args = ArgsPass::new(ctx)?;
        let shell = |label, raster| {
            let target = wgpu::ColorTargetState {
                format: SHELL_TARGET,
                blend: None,
                write_mask: wgpu::ColorWrites::empty(),
            };
            render_pipeline(ctx, label, SHELL_SOURCE, "fs_main", target, raster)
        };
        ctx.scoped("cluster raster pipelines", || {
            Ok(Self {
                mesh: mesh.upload(ctx)?,
                mesh_triangles: mesh.triangle_count(),
                draws: SubregionDraws::new(ctx),
                shell: shell("cluster shell", Rasterization::PLAIN),
                hardware_shell: ctx.conservative_raster.then(|| {
                    shell(
                        "cluster shell (hardware conservative)",
                        Rasterization {
                            vertex: "vs_conservative",
                            conservative: true,
                            ..Rasterization::PLAIN
                        },
                    )
                }),
                hardware: AtomicBool::new(ctx.conservative_raster),
                fill: ctx.compute_pipeline("cluster fill", FILL_SOURCE),
                shade: ctx.compute_pipeline("node shade", SHADE_SOURCE),
                room: ListRoom::new(),
                args,
            })
        })
    }

    /// Whether the shell pass rasterizes conservatively in hardware: by default where the
    /// adapter can (`GpuContext::conservative_raster`). Same cells either way (the fragment
    /// keeps the cells its triangle meets); `false` measures the software form on such an
    /// adapter.
    pub fn hardware(&self) -> bool {
        self.hardware.load(Ordering::Relaxed)
    }

    /// Chooses the hardware form (`true`, where the adapter has it; returns whether it is
    /// used) or the software form (`false`) for the next frames.
    pub fn set_hardware(&self, hardware: bool) -> bool {
        let on = hardware && self.hardware_shell.is_some();
        self.hardware.store(on, Ordering::Relaxed);
        on
    }

    /// The culling step of a frame: depth slices, shell and fill passes, encoded and
    /// submitted; `None` for a frame without pixels.
    pub fn prepare(
        &self,
        ctx: &GpuContext,
        clustered: &ClusteredCuller,
        frame: &CullFrame,
    ) -> Result<Option<NodeFrame>, GpuError> {
        let Some(clusters) = clustered.prepare(ctx, frame, GlossyBound::Ellipsoid, true)? else {
            return Ok(None);
        };
        let p = &clusters.tiles.params;
        let k = p.k;
        let params = GpuRasterParams {
            image: p.image,
            shift: [0.0, 0.0],
            cell: (TILE_SIZE * k) as f32,
            delta: frame.delta,
            width: frame.width,
            height: frame.height,
            k,
            mesh_vertices: COVER_VERTICES * self.mesh_triangles,
            view_w: p.tiles_x,
            view_h: p.tiles_y,
            capacity: self.room.entries::<[u32; 2]>(
                ctx,
                frame,
                u64::from(CLUSTER_SLICES) * u64::from(p.tiles_x) * u64::from(p.tiles_y),
            ),
            scale: frame.interleaving.scale(),
            tiles_x: p.tiles_x,
            tiles_y: p.tiles_y,
            vpl_count: clusters.tiles.bounds.count.capacity(),
            pad: 0,
        };
        let per_sub = u64::from(p.tiles_x) * u64::from(p.tiles_y);
        let cell_count = per_sub * u64::from(clusters.tiles.bounds.count.capacity());
        let cells = output::<u32>(ctx, "cluster cells", cell_count as usize)?;
        let target = atlas(
            ctx,
            "cluster shell atlas",
            (k * p.tiles_x, k * p.tiles_y),
            SHELL_TARGET,
        )?;
        let count = &clusters.tiles.bounds.count;
        let shell = match &self.hardware_shell {
            Some(hardware) if self.hardware() => hardware,
            _ => &self.shell,
        };
        ctx.submit("cluster shell", |encoder| {
            let params_buffer =
                count.uniform(ctx, encoder, "cluster shell params", &params, VPL_COUNT_AT);
            let group = bind(
                ctx,
                "cluster shell",
                &shell.get_bind_group_layout(0),
                &[
                    (0, params_buffer.as_entire_binding()),
                    (1, self.mesh.as_entire_binding()),
                    (2, clusters.tiles.bounds.shapes.as_entire_binding()),
                    (3, clusters.tiles.partition.sub_offsets.as_entire_binding()),
                    (4, clusters.tiles.partition.order.as_entire_binding()),
                    (5, clusters.depth_range.as_entire_binding()),
                    (6, cells.as_entire_binding()),
                ],
            );
            let (tx, ty) = (p.tiles_x, p.tiles_y);
            self.draws.encode(
                ctx,
                encoder,
                "cluster shell",
                (&params, &params_buffer),
                &clusters.tiles.partition.sub_offsets,
                (shell, &group),
                &target,
                |_, _| [tx, ty],
            )
        })?;
        let lists = self.fill(ctx, &clusters, &cells, &params)?;
        Ok(Some(NodeFrame {
            clusters,
            cells,
            params,
            lists: RefCell::new(lists),
        }))
    }

    /// The fill pass into fresh lists of `params.capacity` nodes.
    fn fill(
        &self,
        ctx: &GpuContext,
        clusters: &PreparedClusters,
        cells: &wgpu::Buffer,
        params: &GpuRasterParams,
    ) -> Result<NodeLists, GpuError> {
        let list_count = CLUSTER_SLICES * clusters.tiles.params.tile_count;
        let lists = NodeLists::new(ctx, list_count, params.capacity)?;
        // The node count restarts (GpuCullStatus.total); the faults stay.
        ctx.queue
            .write_buffer(&clusters.tiles.status, 8, bytemuck::bytes_of(&0u32));
        let per_sub = params.tiles_x * params.tiles_y;
        let count = &clusters.tiles.bounds.count;
        ctx.submit("cluster fill", |encoder| {
            let params_buffer =
                count.uniform(ctx, encoder, "cluster fill params", params, VPL_COUNT_AT);
            let workgroups = count.workgroups(ctx, encoder, &self.args, per_sub, 64)?;
            ctx.encode_dispatch(
                encoder,
                "cluster fill",
                &self.fill,
                &[
                    &params_buffer,
                    cells,
                    &clusters.tiles.partition.order,
                    &clusters.tiles.bounds.buffer,
                    &clusters.tiles.frusta,
                    &lists.heads,
                    &lists.nodes,
                    &clusters.tiles.status,
                ],
                workgroups,
            );
            Ok(())
        })?;
        Ok(lists)
    }

    /// The indirect image of `frame` (its `GpuSample`s in `samples`) from the rasterized
    /// clusters: RGB, 3 f32 per pixel row-major, left on the GPU. The fault record and node
    /// count are read afterwards (16 bytes); nodes that did not fit are filled again into a
    /// buffer of their count and the frame shaded again.
    pub fn shade(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        samples: &wgpu::Buffer,
        nodes: &NodeFrame,
    ) -> Result<wgpu::Buffer, GpuError> {
        let clusters = &nodes.clusters;
        let image = output::<f32>(ctx, "indirect image", 3 * clusters.tiles.pixels as usize)?;
        let params = GpuShadeParams {
            width: frame.width,
            height: frame.height,
            pixel_count: clusters.tiles.pixels,
            vpl_count: nodes.params.vpl_count,
            list_count: CLUSTER_SLICES * clusters.tiles.params.tile_count,
            delta: frame.delta,
            scale: frame.interleaving.scale(),
            pad: 0,
        };
        let grid = Grid::for_items(ctx, u64::from(clusters.tiles.pixels), 64)?;
        loop {
            {
                let lists = nodes.lists.borrow();
                ctx.submit("node shade", |encoder| {
                    let params = clusters.tiles.bounds.count.uniform(
                        ctx,
                        encoder,
                        "node shade params",
                        &params,
                        std::mem::offset_of!(GpuShadeParams, vpl_count),
                    );
                    ctx.encode_dispatch_at(
                        encoder,
                        "node shade",
                        &self.shade,
                        &clusters.tiles.bounds.vpls.with(&[
                            &params,
                            samples,
                            &frame.positions,
                            &clusters.tiles.pixel_list,
                            &lists.heads,
                            &lists.nodes,
                            &image,
                        ]),
                        grid,
                    );
                    Ok(())
                })?;
            }
            let count = read_status(ctx, &clusters.tiles.status, frame.width)?;
            if count <= nodes.lists.borrow().capacity {
                return Ok(image);
            }
            self.refill(ctx, nodes, count)?;
        }
    }

    /// The frame's lists in the CSR layout (for the metrics): each cluster's nodes read
    /// back, ascending, uploaded (filled again first if they did not fit).
    pub fn lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        nodes: &NodeFrame,
    ) -> Result<GpuLightLists, GpuError> {
        let clusters = &nodes.clusters;
        let count = loop {
            let count = read_status(ctx, &clusters.tiles.status, frame.width)?;
            if count <= nodes.lists.borrow().capacity {
                break count;
            }
            self.refill(ctx, nodes, count)?;
        };
        let pixel_list: Vec<u32> = read_back(
            ctx,
            "pixel lists",
            &clusters.tiles.pixel_list,
            clusters.tiles.pixels as usize,
        )?;
        let lists = nodes.lists.borrow().read(ctx, count, &pixel_list)?;
        let vpls = clusters.tiles.bounds.count.capacity() as usize;
        GpuLightLists::upload(ctx, &lists, clusters.tiles.pixels as usize, vpls)
    }

    /// Sets the room of the next frames' node buffers (`cull::room`).
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
    }

    /// The fill pass again into a node buffer of `count` nodes (the count it needed).
    fn refill(&self, ctx: &GpuContext, nodes: &NodeFrame, count: u32) -> Result<(), GpuError> {
        self.room.learn(count);
        let params = GpuRasterParams {
            capacity: count,
            ..nodes.params
        };
        *nodes.lists.borrow_mut() = self.fill(ctx, &nodes.clusters, &nodes.cells, &params)?;
        Ok(())
    }
}
