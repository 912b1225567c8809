//! The guarantees of the culling strategies, on synthetic rooms, the built-in default scene
//! and Sponza: no contributing VPL is ever culled (for every strategy, interleaving factor,
//! δ and extreme input), and ellipsoids list far fewer false positives than spheres.
mod common;
mod extremes;
mod false_positives;
mod no_miss;
