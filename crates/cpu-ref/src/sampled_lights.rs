//! N lights sampled from a prepared frame's reflective shadow maps by importance (VSGL section
//! 4.2): virtual spherical Gaussian lights, or, for comparison at equal count, VPLs.
//!
//! Both estimators warp the same stratified points ([`sample_points`]) through the same
//! importance ([`Importance`]); they differ only in where the warp stops. VSGLs stop at the
//! filtered mip level of section 4.2 and shade the cluster's VSGL analytically (eq. 2-5); VPLs
//! go down to single texels and shade that texel's diffuse and glossy VPLs exactly (eq. 4 of the
//! culling paper), as Ritschel et al. 2011 resample VPLs from an RSM. Each sample weighs
//! `1/(N P)`, so the VPL estimate is unbiased against every VPL with p = 1 and the VSGL
//! estimate carries the total flux unbiased; "N lights" means N samples, each one VSGL with
//! its two lobes or one texel with its (up to) two VPLs.
use crate::prepare::CpuPrepared;
use crate::tracer::Tracer;
use crate::vpl_shading::{shade_vpls, VplEstimator};
use crate::vsgl::{
    bidirectional_importance, sample_points, shade_vsgls, FilteredSampler, Footprint,
    ImportanceMap, MipRsm, SampleSet, Vsgl, VsglError, WeightedCluster,
};
use slc_bounds::sg::MeanMap;
use slc_core::frame::{Importance, LightSampling, Shaded, Timings};
use slc_core::{Progress, Vpl};

/// The floor of a VSGL's positional variance `σ_v²` (a single VPL has none, where eq. 1 and
/// 4 diverge): the square of the tracer's ray offset, the length below which the renderer
/// treats points as coincident. Level-0 VSGLs are then point lights up to the SG fits.
pub fn sigma2_floor(tracer: &Tracer) -> f32 {
    tracer.epsilon() * tracer.epsilon()
}

/// Indirect light from `s.count` VSGLs (sections 3-4): the mipmapped RSMs (section 4.1), the
/// importance, filtered importance sampling of clusters (4.2, points from `seed`) and the
/// analytic shading of eq. (2)-(5), with a shadow ray to each `μ_v` if `visibility`.
pub fn shade_vsgl(
    p: &CpuPrepared,
    s: &LightSampling,
    seed: u32,
    visibility: bool,
    progress: Progress,
) -> Result<Shaded, VsglError> {
    let mut timings = Timings::default();
    let floor = sigma2_floor(&p.tracer);
    let mips = timings.time("vsgl_mip", || {
        p.maps
            .iter()
            .map(|rsm| MipRsm::build(rsm, MeanMap::Toksvig))
            .collect::<Result<Vec<_>, _>>()
    })?;
    let importance = timings.time("importance_map", || match s.importance {
        Importance::Flux => Ok(mips.iter().map(ImportanceMap::from_mip).collect()),
        Importance::Bidirectional { camera_vsgls } => bidirectional_importance(
            &p.gbuffer,
            &p.camera,
            &p.maps,
            camera_vsgls,
            seed,
            floor,
            s.diffuse,
        ),
    })?;
    let vsgls = timings.time("light_sampling", || {
        sample_vsgls(&mips, &importance, s.count, seed, floor)
    })?;
    let indirect = timings.time("light_shading", || {
        shade_vsgls(
            &p.tracer, &p.gbuffer, &vsgls, s.diffuse, visibility, progress,
        )
    })?;
    Ok(Shaded {
        sampled_lights: Some(vsgls.len()),
        listed_pairs: None,
        ..Shaded::new(indirect, timings)
    })
}

/// `count` VSGLs by filtered importance sampling (section 4.2) of `importance` over the
/// mipmapped RSMs `mips` with the points of `seed`: each sampled cluster's VSGL (section 3.1,
/// `σ_v²` floored at `sigma2_floor`) scaled by its weight `1/(N P)`.
pub fn sample_vsgls(
    mips: &[MipRsm],
    importance: &[ImportanceMap],
    count: u32,
    seed: u32,
    sigma2_floor: f32,
) -> Result<Vec<Vsgl>, VsglError> {
    sample(importance, count, seed, Footprint::Filtered)
        .iter()
        .map(|w| {
            let c = w.cluster;
            let v = mips[c.map as usize].vsgl(c.face, c.level, c.x, c.y, sigma2_floor)?;
            Ok(v.scaled(w.weight as f32))
        })
        .collect()
}

/// Indirect light from `s.count` texels' VPLs sampled with the same importance and points as
/// [`shade_vsgl`] but down to single texels ([`Footprint::Texel`]), each VPL's flux times its
/// weight `1/(N P)`, shaded exactly (with shadow rays if `visibility`): unbiased against
/// every VPL with p = 1.
pub fn shade_sampled_vpls(
    p: &CpuPrepared,
    s: &LightSampling,
    seed: u32,
    visibility: bool,
    progress: Progress,
) -> Result<Shaded, VsglError> {
    let mut timings = Timings::default();
    let importance = timings.time("importance_map", || match s.importance {
        Importance::Flux => p.maps.iter().map(ImportanceMap::flux).collect(),
        Importance::Bidirectional { camera_vsgls } => bidirectional_importance(
            &p.gbuffer,
            &p.camera,
            &p.maps,
            camera_vsgls,
            seed,
            sigma2_floor(&p.tracer),
            s.diffuse,
        ),
    })?;
    let vpls = timings.time("light_sampling", || {
        texel_vpls(p, &sample(&importance, s.count, seed, Footprint::Texel))
    });
    let indirect = timings.time("light_shading", || {
        shade_vpls(
            &p.tracer,
            &p.gbuffer,
            &vpls,
            VplEstimator::Exact,
            visibility,
            progress,
        )
    })?;
    Ok(Shaded {
        sampled_lights: Some(vpls.len()),
        listed_pairs: None,
        ..Shaded::new(indirect, timings)
    })
}

/// The clusters `count` points of [`SampleSet::Lights`] warp to.
fn sample(
    importance: &[ImportanceMap],
    count: u32,
    seed: u32,
    footprint: Footprint,
) -> Vec<WeightedCluster> {
    let points = sample_points(count, seed, SampleSet::Lights);
    FilteredSampler::new(importance).sample(&points, footprint)
}

/// The VPLs of sampled level-0 texels, fluxes times the samples' weights. Texel `(x, y)` of
/// face `f` of map `m` is texel `k = Σ_{m' < m} |texels of m'| + (f N + y) N + x` of the
/// concatenated maps, whose VPLs have ids `2k` and `2k + 1` (`crate::vpls::generate_vpls`).
fn texel_vpls(p: &CpuPrepared, samples: &[WeightedCluster]) -> Vec<Vpl> {
    let mut bases = Vec::with_capacity(p.maps.len());
    let mut base = 0u32;
    for rsm in &p.maps {
        bases.push(base);
        base += rsm.texels.len() as u32;
    }
    let mut vpls = Vec::with_capacity(2 * samples.len());
    for s in samples {
        let c = s.cluster;
        let n = p.maps[c.map as usize].resolution;
        let k = bases[c.map as usize] + (c.face * n + c.y) * n + c.x;
        for id in [2 * k, 2 * k + 1] {
            if let Ok(i) = p.vpls.binary_search_by_key(&id, |v| v.id) {
                let mut vpl = p.vpls[i];
                vpl.flux *= s.weight as f32;
                vpls.push(vpl);
            }
        }
    }
    vpls
}
