//! The optional bidirectional importance of VSGL section 4.3: VSGLs generated on the camera's
//! G-buffer estimate how much each RSM texel's VPLs reach the image.
use super::emitter::Emitter;
use super::emitter_lanes::EmitterChunks;
use super::error::VsglError;
use super::importance::ImportanceMap;
use super::mip::MipRsm;
use super::sampling::{sample_points, FilteredSampler, Footprint, SampleSet};
use super::sums::ClusterSums;
use crate::rsm::{Rsm, RsmTexel};
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::sg::MeanMap;
use slc_bounds::SgSurface;
use slc_core::frame::DiffuseEmission;
use slc_core::{Camera, GBuffer};

/// The share of the flux importance `Φ(R_d + R_s)` (section 4.2) mixed into the estimated
/// one: every texel that reflects light keeps a positive probability, so the estimate stays
/// unbiased where the camera-side VSGLs see too little of a texel (the paper does not say how
/// it guards against this; a defensive mixture is the usual remedy).
pub const FLUX_SHARE: f64 = 0.1;

/// The G-buffer as a map of "camera VPLs" (section 4.3: the G-buffer gets the diffuse lobe,
/// specular lobe and position buffers of Fig. 4, weighted by reflectances only): one square
/// face of side `max(width, height)`, pixel `(x, y)` at texel `(x, y)`, each surface with flux
/// 1 and the view direction in the role of the photon's incoming direction (the BRDF is
/// reciprocal), so that its lobe is the pixel's response `ρ(ωo, ω) ⟨ω, n⟩` to light from `ω`.
/// A pixel's cross-section is the square `(2 tan(yfov/2) depth / height)²` of `camera`.
pub fn camera_rsm(gbuffer: &GBuffer, camera: &Camera) -> Rsm {
    let (w, h) = (gbuffer.width, gbuffer.height);
    let pixel_side = 2.0 * (0.5 * camera.yfov).tan() / h.max(1) as f32;
    let side = w.max(h).max(1);
    let mut texels = vec![None; (side * side) as usize];
    for y in 0..h {
        for x in 0..w {
            if let Some(g) = &gbuffer.samples[(y * w + x) as usize] {
                texels[(y * side + x) as usize] = Some(RsmTexel {
                    position: g.position,
                    normal: g.normal,
                    geometric_normal: g.geometric_normal,
                    normal_mapped: false,
                    omega_i: g.omega_o,
                    flux: Vec3::ONE,
                    cross_section: (pixel_side * g.depth).powi(2),
                    brdf: g.brdf,
                });
            }
        }
    }
    Rsm {
        resolution: side,
        faces: 1,
        texels,
    }
}

/// The importance of every texel of `maps` (section 4.3): `camera_vsgls` VSGLs are sampled
/// from the mipmapped [`camera_rsm`] of the G-buffer seen by `camera` by filtered importance
/// sampling (section 4.2, points of [`SampleSet::Camera`] from `seed`) and shade each texel as
/// if it were a receiver seen from its light (view direction `ω'_i`), without visibility, as
/// the paper does; the importance is the texel's flux times that radiance, summed over RGB. It is mixed with the flux
/// importance, [`FLUX_SHARE`] of the total probability. Fails for an invalid BRDF.
pub fn bidirectional_importance(
    gbuffer: &GBuffer,
    camera: &Camera,
    maps: &[Rsm],
    camera_vsgls: u32,
    seed: u32,
    sigma2_floor: f32,
    diffuse: DiffuseEmission,
) -> Result<Vec<ImportanceMap>, VsglError> {
    let camera_mip = MipRsm::build(&camera_rsm(gbuffer, camera), MeanMap::Toksvig)?;
    let camera_importance = [ImportanceMap::from_mip(&camera_mip)];
    let points = sample_points(camera_vsgls, seed, SampleSet::Camera);
    let vsgls = FilteredSampler::new(&camera_importance)
        .sample(&points, Footprint::Filtered)
        .iter()
        .map(|s| {
            let c = s.cluster;
            let v = camera_mip.vsgl(c.face, c.level, c.x, c.y, sigma2_floor)?;
            Emitter::new(&v.scaled(s.weight as f32), diffuse)
        })
        .collect::<Result<Vec<Emitter>, VsglError>>()?;
    let vsgls = EmitterChunks::new(&vsgls);
    // (view, flux) masses per texel of every map.
    let masses = maps
        .iter()
        .map(|rsm| {
            rsm.texels
                .par_iter()
                .map(|t| match t {
                    Some(t) => texel_masses(t, &vsgls),
                    None => Ok((0.0, 0.0)),
                })
                .collect::<Result<Vec<_>, VsglError>>()
        })
        .collect::<Result<Vec<_>, VsglError>>()?;
    let (view_total, flux_total) = masses
        .iter()
        .flatten()
        .fold((0.0, 0.0), |(v, f), m| (v + m.0, f + m.1));
    // Without any view importance (nothing seen), the flux importance alone.
    let flux_share = if view_total > 0.0 { FLUX_SHARE } else { 1.0 };
    let mix = |(view, flux): (f64, f64)| {
        let v = if view_total > 0.0 {
            (1.0 - FLUX_SHARE) * view / view_total
        } else {
            0.0
        };
        let f = if flux_total > 0.0 {
            flux_share * flux / flux_total
        } else {
            0.0
        };
        v + f
    };
    maps.iter()
        .zip(&masses)
        .map(|(rsm, m)| {
            let level0: Vec<f64> = m.iter().map(|&pair| mix(pair)).collect();
            ImportanceMap::from_texels(rsm.resolution, rsm.faces, &level0)
        })
        .collect()
}

/// The view importance (the texel's flux times the radiance the camera VSGLs send it, RGB
/// total) and the flux importance of one texel.
fn texel_masses(t: &RsmTexel, vsgls: &EmitterChunks) -> Result<(f64, f64), VsglError> {
    let flux = ClusterSums::from_texel(t, MeanMap::Toksvig)?.weight();
    let surface = SgSurface::new(t.normal, t.omega_i, &t.brdf)?;
    let mut radiance = Vec3::ZERO;
    vsgls.each_radiance(&surface, t.position, |_, c| radiance += c)?;
    let view = f64::from((t.flux * radiance).element_sum());
    Ok((view, flux))
}
