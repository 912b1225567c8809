//! `report.json`: what was rendered, how long each pass took and what was measured.
//! Unknown values are `null`, never made up.
use serde::Serialize;
use std::collections::BTreeMap;

#[derive(Serialize, Debug)]
pub struct Report {
    pub scene: String,
    pub backend: &'static str,
    /// The device that rendered: the CPU backend names its thread count.
    pub adapter: String,
    pub width: u32,
    pub height: u32,
    pub vpl_count: usize,
    /// δ of eq. (2); `null` when every VPL is used with p = 1 (the VPL reference) or no VPLs are used.
    pub delta: Option<f32>,
    pub seed: u32,
    pub culling: &'static str,
    pub shader: &'static str,
    /// `vpl` or `path` for reference renders, `null` for the stochastic estimate.
    pub reference: Option<&'static str>,
    pub visibility: bool,
    pub spp: u32,
    pub rsm: u32,
    pub timings_ms: BTreeMap<String, f64>,
    pub metrics: Metrics,
    /// Mean RGB of each written image.
    pub image_means: BTreeMap<&'static str, [f32; 3]>,
    pub skipped_triangles: usize,
    pub warnings: Vec<String>,
}

#[derive(Serialize, Debug, Default)]
pub struct Metrics {
    pub lights_per_pixel_mean: Option<f64>,
    pub true_positive_pairs: Option<u64>,
    pub false_positive_pairs: Option<u64>,
    pub false_discovery_rate: Option<f64>,
    pub missed_pairs: Option<u64>,
}
