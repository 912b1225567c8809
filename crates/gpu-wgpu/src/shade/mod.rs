//! Stochastic VPL shading (eq. 2-4 and 6-8 with the K² weight of section 6): from light lists
//! ([`lists`], `shade.wesl`) or culled and shaded in one pass, the paper's Fig. 2
//! ([`tiled`], `tiled_shade.wesl`), both evaluating one VPL's contribution the same way
//! (`vpl_eval.wesl`, on the BRDF of `material/brdf.wesl`), with their records ([`records`]).
pub mod lists;
pub mod records;
pub mod tiled;
