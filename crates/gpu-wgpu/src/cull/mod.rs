//! One entry point for every culling strategy (`slc_core::Strategy`) on the GPU:
//! [`GpuCulling`] holds the pipelines of the passes that implement them (`cull::none`,
//! `cull::tiled`, `cull::clustered`, `cull::binned`) and runs the one of a strategy's layout with its
//! glossy bound; [`GpuCulling::culler`] binds one strategy as a `slc_core::Culler` whose lists
//! stay on the GPU for `shade::lists`.
pub mod binned;
pub mod bounds;
pub mod clustered;
pub mod frame;
pub mod list_passes;
pub mod lists;
pub mod none;
pub mod partition;
pub mod raster;
pub mod records;
pub mod room;
pub mod tight;
pub mod tiled;

use crate::cull::binned::BinnedCuller;
use crate::cull::clustered::ClusteredCuller;
use crate::cull::frame::CullFrame;
use crate::cull::list_passes::{PreparedTiles, TileLayout};
use crate::cull::lists::{no_lists, read_lists, GpuLightLists};
use crate::cull::none::NoneCuller;
use crate::cull::raster::clusters::{ClusterRasterizer, NodeFrame};
use crate::cull::raster::splat::Splatter;
use crate::cull::room::{settled, use_settled};
use crate::cull::tiled::TiledCuller;
use crate::device::context::{GpuContext, GpuError};
use slc_core::{CullInput, Culler, GlossyBound, Layout, LightLists, Strategy};
use std::cell::RefCell;

/// A culling pass that writes a frame's light lists on the GPU ([`ListCulling::cull_frame`]);
/// culling a CPU input comes with it, written once: uploaded and culled again where the lists
/// outgrew their buffer ([`ListCulling::cull_on_gpu`]), and read back ([`ListCulling::cull`]).
pub trait ListCulling {
    /// What picks the lists: a strategy, or a layout's glossy bound.
    type Choice: Copy;

    /// The lists of `frame` left on the GPU in the CSR layout the shading pass reads.
    fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        choice: Self::Choice,
    ) -> Result<GpuLightLists, GpuError>;

    /// [`ListCulling::cull_frame`] of `input` with its G-buffer uploaded, complete: culled
    /// again where the lists outgrew their buffer (their totals read).
    fn cull_on_gpu(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        choice: Self::Choice,
    ) -> Result<GpuLightLists, GpuError> {
        let frame = CullFrame::upload(ctx, input)?;
        settled(ctx, || self.cull_frame(ctx, &frame, choice))
    }

    /// The lists of `input`, read back. Errors on invalid input (as the CPU culler), on
    /// buffers beyond the device's limits and on device faults.
    fn cull(
        &self,
        ctx: &GpuContext,
        input: &CullInput,
        choice: Self::Choice,
    ) -> Result<LightLists, GpuError> {
        read_lists(ctx, &self.cull_on_gpu(ctx, input, choice)?)
    }
}

/// The pipelines of every strategy.
pub struct GpuCulling {
    none: NoneCuller,
    tiled: TiledCuller,
    clustered: ClusteredCuller,
    binned: BinnedCuller,
    splatter: Splatter,
    rasterizer: ClusterRasterizer,
}

impl GpuCulling {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Ok(Self {
            none: NoneCuller::new(ctx)?,
            tiled: TiledCuller::new(ctx)?,
            clustered: ClusteredCuller::new(ctx)?,
            binned: BinnedCuller::new(ctx)?,
            splatter: Splatter::new(ctx)?,
            rasterizer: ClusterRasterizer::new(ctx)?,
        })
    }

    /// `strategy` on `ctx` as a [`Culler`] of [`CullFrame`]s.
    pub fn culler<'a>(&'a self, ctx: &'a GpuContext, strategy: Strategy) -> StrategyCuller<'a> {
        StrategyCuller {
            passes: self,
            ctx,
            strategy,
        }
    }

    /// The splatting pipelines (its frames' shading).
    pub fn splatter(&self) -> &Splatter {
        &self.splatter
    }

    /// The rasterized clusters' pipelines (their frames' shading).
    pub fn rasterizer(&self) -> &ClusterRasterizer {
        &self.rasterizer
    }

    /// Runs `use_lists` on `lists` (of `strategy` for `frame`), then reads their culling's
    /// fault records; lists that outgrew their buffer are culled again, now with room for
    /// them, and used again ([`use_settled`]). Returns what the last use gave; `lists` then
    /// holds the lists it used, complete, their records read (using them again reads
    /// nothing).
    pub fn use_lists<T>(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        strategy: Strategy,
        lists: &RefCell<GpuLightLists>,
        use_lists: impl FnMut(&GpuLightLists) -> Result<T, GpuError>,
    ) -> Result<T, GpuError> {
        let recull = || self.cull_frame(ctx, frame, strategy);
        let first = lists.borrow().clone();
        let (out, complete) = use_settled(ctx, first, recull, use_lists)?;
        *lists.borrow_mut() = complete;
        Ok(out)
    }

    /// Sets the room the list cullers (tiled lists, clustered, the tight refinement, binned) and
    /// the raster baselines' node buffers leave for the next frames' lists, which grows
    /// again where a frame needs more (`cull::room`): to preallocate for a known scene, or to
    /// exercise culling again.
    pub fn set_list_room(&self, entries: u32) {
        self.tiled.set_list_room(entries);
        self.clustered.set_list_room(entries);
        self.binned.set_list_room(entries);
        self.rasterizer.set_list_room(entries);
        self.splatter.set_list_room(entries);
    }
}

/// Culls by `strategy`: [`ListCulling::cull`] gives lists equal to the CPU
/// strategy's per pixel (up to f32-versus-f64 decisions at bound and slice boundaries;
/// the tight strategies' f32 bound keeps up to 1% more entries, `binned`'s f32 per-pixel test
/// a few percent more with the sharpest lobes, `cull::binned`). Splatting takes the
/// uploaded samples to lie on the pixel centres' rays ([`CullFrame::upload`]): a G-buffer
/// jittered per pixel would be splatted along other rays.
impl ListCulling for GpuCulling {
    type Choice = Strategy;

    /// The lists of `strategy` for `frame` (a G-buffer on the GPU, uploaded or rasterized),
    /// left on the GPU. The raster baselines, which shade without these lists, give what
    /// they evaluate: the pixels each splat covers, the rasterized clusters' lists. The
    /// lists' totals are read after their use ([`GpuLightLists::outgrown`],
    /// [`Self::use_lists`]).
    fn cull_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        strategy: Strategy,
    ) -> Result<GpuLightLists, GpuError> {
        match strategy.parts() {
            (Layout::Unculled, _) => self.none.cull_frame(ctx, frame),
            (Layout::Tiled, glossy) => self.tiled.cull_frame(ctx, frame, glossy),
            (Layout::Clustered, glossy) => self.clustered.cull_frame(ctx, frame, glossy),
            (Layout::Splatting | Layout::ClusteredRaster, _) => {
                let lists = self.prepare_frame(ctx, frame, strategy)?;
                self.frame_lists(ctx, frame, &lists)
            }
            (Layout::Binned, _) => self.binned.cull_frame(ctx, frame),
        }
    }
}

/// What a frame's culling step leaves for its shading step (`GpuRenderer`): the frusta of a
/// tiled strategy, culled and shaded in one pass (`shade::tiled`, the paper's Fig. 2),
/// the bounds splatting draws (`cull::raster::splat`), the rasterized clusters (`cull::raster::clusters`),
/// or the lists of the others (clustered, tight, binned, unculled) and their strategy, shaded by
/// `shade::lists` (replaced by complete ones where they outgrew their buffer,
/// [`GpuCulling::use_lists`]).
pub enum Culled {
    Tiles(Box<PreparedTiles>),
    Splats(Box<PreparedTiles>),
    Nodes(Box<NodeFrame>),
    Lists(RefCell<GpuLightLists>, Strategy),
}

impl GpuCulling {
    /// Whether a frame of `strategy` is culled and shaded in one pass: the tiled strategies
    /// but the tight one.
    pub fn one_pass(strategy: Strategy) -> bool {
        matches!(strategy.parts(), (Layout::Tiled, glossy) if glossy != GlossyBound::Tight)
    }

    /// The culling step of a frame: [`Culled::Tiles`] where [`Self::one_pass`], the
    /// raster baselines' own steps, else [`ListCulling::cull_frame`]'s lists.
    pub fn prepare_frame(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        strategy: Strategy,
    ) -> Result<Culled, GpuError> {
        let no_pixels = || Ok(Culled::Lists(RefCell::new(no_lists(ctx)?), strategy));
        match strategy.parts().0 {
            Layout::Splatting => {
                return match self
                    .tiled
                    .prepare(ctx, frame, GlossyBound::Ellipsoid, true)?
                {
                    Some(tiles) => Ok(Culled::Splats(Box::new(tiles))),
                    None => no_pixels(),
                };
            }
            Layout::ClusteredRaster => {
                return match self.rasterizer.prepare(ctx, &self.clustered, frame)? {
                    Some(nodes) => Ok(Culled::Nodes(Box::new(nodes))),
                    None => no_pixels(),
                };
            }
            _ => {}
        }
        if !Self::one_pass(strategy) {
            let lists = self.cull_frame(ctx, frame, strategy)?;
            return Ok(Culled::Lists(RefCell::new(lists), strategy));
        }
        match self.tiled.prepare(ctx, frame, strategy.parts().1, false)? {
            Some(tiles) => Ok(Culled::Tiles(Box::new(tiles))),
            None => no_pixels(),
        }
    }

    /// The lists of a culling step, built from the frusta where it kept only those (for the
    /// metrics), complete (culled again where they outgrew their buffer).
    pub fn frame_lists(
        &self,
        ctx: &GpuContext,
        frame: &CullFrame,
        lists: &Culled,
    ) -> Result<GpuLightLists, GpuError> {
        match lists {
            Culled::Tiles(tiles) => settled(ctx, || self.tiled.lists(ctx, frame, tiles)),
            Culled::Splats(tiles) => self.splatter.lists(ctx, frame, tiles),
            Culled::Nodes(nodes) => self.rasterizer.lists(ctx, frame, nodes),
            Culled::Lists(lists, strategy) => {
                self.use_lists(ctx, frame, *strategy, lists, |_| Ok(()))?;
                Ok(lists.borrow().clone())
            }
        }
    }
}

/// One strategy of a [`GpuCulling`] on one device.
pub struct StrategyCuller<'a> {
    passes: &'a GpuCulling,
    ctx: &'a GpuContext,
    strategy: Strategy,
}

impl Culler<CullFrame<'_>> for StrategyCuller<'_> {
    type Lists = GpuLightLists;
    type Error = GpuError;

    fn strategy(&self) -> Strategy {
        self.strategy
    }

    fn cull(&self, frame: &CullFrame) -> Result<GpuLightLists, GpuError> {
        self.passes.cull_frame(self.ctx, frame, self.strategy)
    }
}
