//! The culling strategies, one per file; all bound-based ones share `tiled` and differ only
//! in the bound of glossy VPLs and the depth clustering.
pub mod clustered;
pub mod ellipsoid;
pub mod enclosing_sphere;
pub mod none;
pub mod sphere;
