//! What both backends' virtual spherical Gaussian lights (Tokuyoshi 2015) share: the layout
//! of the mip pyramids over the RSM faces ([`Quadtree`]) and the sample points warped down
//! them ([`sample_points`]). The VSGLs themselves are built by each backend.
mod points;
mod quadtree;

pub use points::{point_shift, sample_points, SampleSet, ONE_BELOW};
pub use quadtree::Quadtree;
