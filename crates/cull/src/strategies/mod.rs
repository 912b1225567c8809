//! The culling strategies: [`none::NoCulling`], and [`bounded::BoundedCuller`] for every
//! strategy that tests bounds (they share `tiled` and differ only in the bound of glossy VPLs
//! and the depth clustering).
pub mod bounded;
pub mod none;
