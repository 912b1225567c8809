//! The pipelines every list culler of a tile grid runs besides its own kernels (the tiled and
//! the clustered layout): per-VPL bounds, the subregions' VPLs, the scan of list offsets, the
//! tight refinement, and the room the lists of earlier frames needed.
use crate::cull::bounds::BoundsPass;
use crate::cull::partition::PartitionPass;
use crate::cull::room::ListRoom;
use crate::cull::tight::TightRefiner;
use crate::device::context::{GpuContext, GpuError};
use crate::device::scan::ScanPass;
use std::sync::Arc;

/// The passes a list culler shares with the other layouts.
pub struct ListPasses {
    pub bounds: BoundsPass,
    pub partition: PartitionPass,
    pub scan: ScanPass,
    pub tight: TightRefiner,
    /// What the lists of earlier frames needed.
    pub room: Arc<ListRoom>,
}

impl ListPasses {
    /// The pipelines, made within `ctx`'s error scope named `what`, with `own` (the layout's
    /// own pipelines) made in the same scope.
    pub fn new<T>(
        ctx: &GpuContext,
        what: &'static str,
        own: impl FnOnce() -> T,
    ) -> Result<(Self, T), GpuError> {
        let bounds = BoundsPass::new(ctx)?;
        ctx.scoped(what, || {
            Ok((
                Self {
                    bounds,
                    partition: PartitionPass::new(ctx),
                    scan: ScanPass::new(ctx),
                    tight: TightRefiner::new(ctx),
                    room: Arc::new(ListRoom::new()),
                },
                own(),
            ))
        })
    }

    /// Sets the room of the next frames' lists (`cull::room`), the refinement's too.
    pub fn set_list_room(&self, entries: u32) {
        self.room.set(entries);
        self.tight.set_list_room(entries);
    }
}
