//! Shading by VSGLs (VSGL section 3.2): the incoming radiance of a VSGL as one spherical
//! Gaussian (eq. 3-5) integrated against the receiver's diffuse + GGX lobe (eq. 2).
use super::emitter::Emitter;
use super::emitter_lanes::EmitterChunks;
use super::error::VsglError;
use super::light::Vsgl;
use crate::frame_images::shade_rows;
use crate::tracer::Tracer;
use glam::Vec3;
use slc_bounds::SgSurface;
use slc_core::frame::DiffuseEmission;
use slc_core::{GBuffer, Image, Progress};

/// The radiance reflected towards the receiver's view by one VSGL (eq. 2), without visibility:
/// for each lobe `c_v G(ω; ξ_v, λ_v)` of the VSGL's radiant intensity, the incoming radiance of
/// eq. (5),
///
/// `L_in(ω) ≈ c_v/(2πσ_v²) G(ω; −ξ_v, λ_v) G(ω; ξ_μ, λ_σ)`, `ξ_μ = (μ_v − x_p)/|μ_v − x_p|`,
/// `λ_σ = |μ_v − x_p|²/σ_v²` (eq. 4),
///
/// a product of two SGs and so one SG, shaded in closed form by `surface` ([`SgSurface`]: the
/// SG's irradiance for the diffuse term, the fitted GGX lobe for the specular one); the
/// diffuse lobe as `diffuse` says, a specular lobe of sharpness 3 or more as the three SGs of
/// GGX's profile ([`slc_bounds::sg::ggx_mixture`], each shaded so). A receiver at `μ_v` itself sees the constant `λ_σ = 0` (and
/// the clamped diffuse intensity averaged over all directions, `Σ Φ R_d/(4π)`). Fails for a
/// `σ_v²` that is not positive and finite, or when a lobe leaves the `f32` range.
pub fn vsgl_radiance(
    surface: &SgSurface,
    x_p: Vec3,
    vsgl: &Vsgl,
    diffuse: DiffuseEmission,
) -> Result<Vec3, VsglError> {
    Emitter::new(vsgl, diffuse)?.radiance(surface, x_p)
}

/// Indirect radiance at every pixel of `gbuffer` from every VSGL of `vsgls` (their weights
/// already applied), by [`vsgl_radiance`] with `diffuse`; with `visibility`, each VSGL that contributes is
/// tested with a shadow ray from the pixel to its mean position `μ_v` (VSGL eq. 3,
/// `V(x_p, μ_v)`). Pixels without a surface stay black. `progress` is told the number of
/// pixels finished; once it is cancelled the rows not yet begun stay black (the caller checks
/// `progress`).
pub fn shade_vsgls(
    tracer: &Tracer,
    gbuffer: &GBuffer,
    vsgls: &[Vsgl],
    diffuse: DiffuseEmission,
    visibility: bool,
    progress: Progress,
) -> Result<Image, VsglError> {
    let emitters = vsgls
        .iter()
        .map(|v| Emitter::new(v, diffuse))
        .collect::<Result<Vec<_>, _>>()?;
    let chunks = EmitterChunks::new(&emitters);
    shade_rows(gbuffer, progress, |g, o| {
        let surface = SgSurface::new(g.normal, g.omega_o, &g.brdf)?;
        let from = tracer.lift(g.position, g.geometric_normal);
        chunks.each_radiance(&surface, g.position, |i, c| {
            let mu = Vec3::from(emitters[i].mu);
            if c != Vec3::ZERO && (!visibility || tracer.unoccluded(from, mu)) {
                *o += c;
            }
        })?;
        Ok::<(), VsglError>(())
    })
}
