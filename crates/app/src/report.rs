//! `report.json`: what was rendered, how long each pass took and what was measured.
//! Unknown values are `null`, never made up.
use crate::out_dir::OutDir;
use crate::provenance::Provenance;
use crate::repeat::Spread;
use serde::Serialize;
use slc_core::frame::{Importance, Method, RenderSettings, Timings};
use slc_core::{BackendInfo, CullMetrics, Image, Scene};
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Serialize, Debug)]
pub struct Report {
    /// The build, command, machine and scene files this result comes from.
    pub provenance: Provenance,
    pub scene: String,
    pub backend: &'static str,
    /// The device that rendered: the CPU backend names its thread count, the GPU backend its
    /// wgpu adapter.
    pub adapter: String,
    /// Where each pass ran and how it was timed, when the backend is not all one device
    /// (empty for the CPU).
    pub notes: Vec<String>,
    pub width: u32,
    pub height: u32,
    pub vpl_count: usize,
    /// δ of eq. (2); `null` for the references, which use every VPL with p = 1 or none.
    pub delta: Option<f32>,
    pub seed: u32,
    /// The culling strategy; `null` for the references.
    pub culling: Option<&'static str>,
    /// `vsgl` for virtual spherical Gaussian lights, `vpl` otherwise.
    pub shader: &'static str,
    /// N, the number of sampled lights (VSGLs, or VPLs sampled by the same importance at equal
    /// count); `null` for the other methods.
    pub light_samples: Option<u32>,
    /// The importance the lights were sampled with, `flux` or `bidirectional`; `null` for the
    /// other methods.
    pub importance: Option<&'static str>,
    /// VSGLs generated on the G-buffer for the bidirectional importance; `null` otherwise.
    pub camera_vsgls: Option<u32>,
    /// The form of the VSGLs' diffuse intensity, `clamped` or `sg` (the paper's); `null` for
    /// the other methods.
    pub vsgl_diffuse: Option<&'static str>,
    /// Distinct lights shaded (samples of the same cluster merged; a sampled texel gives up to
    /// two VPLs); `null` for the other methods.
    pub sampled_lights: Option<usize>,
    /// K of K x K interleaved sampling; `null` for the references.
    pub interleave: Option<u32>,
    /// Whether the cross bilateral filter ran; `null` for the references.
    pub denoise: Option<bool>,
    /// `vpl` or `path` for reference renders, `null` for the stochastic estimate.
    pub reference: Option<&'static str>,
    pub visibility: bool,
    pub spp: u32,
    pub rsm: u32,
    /// Milliseconds per pass: the median over `timing_runs` runs.
    pub timings_ms: BTreeMap<String, f64>,
    /// Measured runs (`--repeat`; more than one after a warm-up).
    pub timing_runs: usize,
    /// Median, min and max per pass over the runs; `null` for one run.
    pub timings_spread_ms: Option<BTreeMap<String, Spread>>,
    /// GPU execution time per pass from timestamp queries (the GPU backend on an adapter that
    /// has them, `total` included); `null` otherwise, with a note saying why.
    pub gpu_timings_ms: Option<BTreeMap<String, f64>>,
    /// Bytes the frame read back from the GPU (its preparation and its shading, the metrics'
    /// reads included), by what was read; `null` on the CPU backend.
    pub gpu_readback: Option<Readback>,
    pub metrics: Metrics,
    /// Mean RGB of each written image.
    pub image_means: BTreeMap<&'static str, [f32; 3]>,
    pub skipped_triangles: usize,
    /// The removed triangles by defect.
    pub skipped_by_defect: Skipped,
    pub warnings: Vec<String>,
    pub memory: Memory,
    /// Features of the scene slc does not model (emission, alpha blending, glTF extensions
    /// such as `KHR_materials_clearcoat`, OBJ bump maps), each with the materials using it.
    pub ignored: BTreeMap<String, Vec<String>>,
}

/// Culling metrics (measured by brute force over all pixel-VPL pairs of each subregion).
#[derive(Serialize, Debug, Default)]
pub struct Metrics {
    pub lights_per_pixel_mean: Option<f64>,
    pub true_positive_pairs: Option<u64>,
    pub false_positive_pairs: Option<u64>,
    pub false_discovery_rate: Option<f64>,
    pub missed_pairs: Option<u64>,
}

impl From<Option<&CullMetrics>> for Metrics {
    fn from(m: Option<&CullMetrics>) -> Self {
        m.map_or_else(Metrics::default, |m| Metrics {
            lights_per_pixel_mean: Some(m.lights_per_pixel_mean),
            true_positive_pairs: Some(m.true_positive_pairs),
            false_positive_pairs: Some(m.false_positive_pairs),
            false_discovery_rate: Some(m.false_discovery_rate),
            missed_pairs: Some(m.missed_pairs),
        })
    }
}

/// What a frame was, for its report.
pub struct FrameFacts<'a> {
    pub device: &'a BackendInfo,
    pub scene: &'a Scene,
    /// The frame's size, RSM, seed and visibility (its method is `method`).
    pub settings: &'a RenderSettings,
    pub method: Method,
    pub spp: u32,
    pub vpl_count: usize,
    /// Wall-clock times of each measured run (one, or `--repeat` runs).
    pub timings: &'a [Timings],
    /// The GPU's timestamp times of its passes, where it has them.
    pub gpu_timings: Option<&'a Timings>,
    pub metrics: Option<&'a CullMetrics>,
    /// Distinct sampled lights, for the VSGL and sampled-VPL methods.
    pub sampled_lights: Option<usize>,
    pub images: &'a [(&'static str, &'a Image)],
    /// Bytes read back from the device, by what was read (GPU backend).
    pub readback_bytes: Option<&'a BTreeMap<String, u64>>,
}

/// What a frame read back from the GPU.
#[derive(Clone, Debug, Serialize)]
pub struct Readback {
    pub total_bytes: u64,
    pub by_label: BTreeMap<String, u64>,
}

impl Readback {
    fn of(by_label: &BTreeMap<String, u64>) -> Self {
        Self {
            total_bytes: by_label.values().sum(),
            by_label: by_label.clone(),
        }
    }
}

/// Milliseconds per pass and their `total`, the medians over the runs.
fn medians(runs: &[Timings]) -> BTreeMap<String, f64> {
    spread_per_pass(runs)
        .into_iter()
        .map(|(k, s)| (k, s.median))
        .collect()
}

/// Each pass (and the `total`) over the runs.
fn spread_per_pass(runs: &[Timings]) -> BTreeMap<String, Spread> {
    let mut out: BTreeMap<String, Spread> = runs[0]
        .0
        .iter()
        .map(|(k, _)| (k.to_string(), Spread::of_passes(runs, &[k])))
        .collect();
    out.insert("total".into(), Spread::of_totals(runs));
    out
}

impl Report {
    pub fn new(f: &FrameFacts) -> Self {
        let stochastic = match f.method {
            Method::Stochastic(s) => Some(s),
            _ => None,
        };
        let sampling = match f.method {
            Method::Vsgl(l) | Method::SampledVpls(l) => Some(l),
            _ => None,
        };
        Report {
            provenance: Provenance::new(f.scene),
            scene: f.scene.name.clone(),
            backend: f.device.backend,
            adapter: f.device.adapter.clone(),
            notes: f.device.notes.clone(),
            width: f.settings.width,
            height: f.settings.height,
            vpl_count: f.vpl_count,
            delta: stochastic.map(|s| s.delta),
            seed: f.settings.seed,
            culling: stochastic.map(|s| s.strategy.name()),
            shader: match f.method {
                Method::Vsgl(_) => "vsgl",
                _ => "vpl",
            },
            light_samples: sampling.map(|l| l.count),
            importance: sampling.map(|l| l.importance.name()),
            camera_vsgls: sampling.and_then(|l| match l.importance {
                Importance::Bidirectional { camera_vsgls } => Some(camera_vsgls),
                Importance::Flux => None,
            }),
            vsgl_diffuse: match f.method {
                Method::Vsgl(l) => Some(l.diffuse.name()),
                _ => None,
            },
            sampled_lights: f.sampled_lights,
            interleave: stochastic.map(|s| s.interleave),
            denoise: stochastic.map(|s| s.denoise),
            reference: match f.method {
                Method::VplReference => Some("vpl"),
                Method::Path => Some("path"),
                Method::Stochastic(_) | Method::Vsgl(_) | Method::SampledVpls(_) => None,
            },
            visibility: f.settings.visibility || f.method == Method::Path,
            spp: f.spp,
            rsm: f.settings.rsm_resolution,
            timings_ms: medians(f.timings),
            timing_runs: f.timings.len(),
            timings_spread_ms: (f.timings.len() > 1).then(|| spread_per_pass(f.timings)),
            gpu_timings_ms: f.gpu_timings.map(|t| medians(std::slice::from_ref(t))),
            gpu_readback: f.readback_bytes.map(Readback::of),
            metrics: f.metrics.into(),
            image_means: f
                .images
                .iter()
                .map(|(n, i)| (*n, i.mean().to_array()))
                .collect(),
            skipped_triangles: f.scene.report.skipped.total(),
            skipped_by_defect: Skipped::from(f.scene.report.skipped),
            warnings: f.scene.report.warnings.clone(),
            memory: Memory {
                estimate_bytes: f.settings.memory_estimate(f.scene).total(),
                peak_rss_bytes: crate::limits::peak_rss(),
            },
            ignored: f.scene.report.ignored.clone(),
        }
    }

    /// Stages the report as `dir/report.json` in `out` (empty `dir`: the top).
    pub fn write(&self, out: &mut OutDir, dir: &str) -> Result<(), String> {
        let json = serde_json::to_string_pretty(self).map_err(|e| e.to_string())?;
        out.write(Path::new(dir).join("report.json"), (json + "\n").as_bytes())
    }
}

/// What the run was estimated to need before any work ([`RenderSettings::memory_estimate`],
/// what the memory check compares with the memory available) and what the process held at
/// most by the time the report was made (`null` where the OS does not say).
#[derive(Serialize, Debug)]
pub struct Memory {
    pub estimate_bytes: u64,
    pub peak_rss_bytes: Option<u64>,
}

/// Triangles the loader removed, by defect.
#[derive(Serialize, Debug)]
pub struct Skipped {
    pub non_finite_vertex: usize,
    pub index_out_of_range: usize,
    /// A coordinate beyond ±1e18 (`slc_core::mesh::MAX_COORDINATE`).
    pub coordinate_out_of_range: usize,
    pub zero_area: usize,
}

impl From<slc_core::mesh::DefectCounts> for Skipped {
    fn from(d: slc_core::mesh::DefectCounts) -> Self {
        Self {
            non_finite_vertex: d.non_finite,
            index_out_of_range: d.index_out_of_range,
            coordinate_out_of_range: d.out_of_range,
            zero_area: d.degenerate,
        }
    }
}
