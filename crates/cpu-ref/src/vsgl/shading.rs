//! Shading by VSGLs (VSGL section 3.2): the incoming radiance of a VSGL as one spherical
//! Gaussian (eq. 3-5) integrated against the receiver's diffuse + GGX lobe (eq. 2).
use super::error::VsglError;
use super::light::Vsgl;
use crate::tracer::Tracer;
use core::f32::consts::{FRAC_1_PI, TAU};
use glam::Vec3;
use rayon::prelude::*;
use slc_bounds::sg::{sg_integral, IrradianceFit};
use slc_bounds::{SgSurface, SphericalGaussian};
use slc_core::frame::DiffuseEmission;
use slc_core::{GBuffer, Image};

/// The radiance reflected towards the receiver's view by one VSGL (eq. 2), without visibility:
/// for each lobe `c_v G(ω; ξ_v, λ_v)` of the VSGL's radiant intensity, the incoming radiance of
/// eq. (5),
///
/// `L_in(ω) ≈ c_v/(2πσ_v²) G(ω; −ξ_v, λ_v) G(ω; ξ_μ, λ_σ)`, `ξ_μ = (μ_v − x_p)/|μ_v − x_p|`,
/// `λ_σ = |μ_v − x_p|²/σ_v²` (eq. 4),
///
/// a product of two SGs and so one SG, shaded in closed form by `surface` ([`SgSurface`]: the
/// SG's irradiance for the diffuse term, the fitted GGX lobe for the specular one); the
/// diffuse lobe as `diffuse` says. A receiver at `μ_v` itself sees the constant `λ_σ = 0` (and
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

/// A VSGL's diffuse intensity in the [`DiffuseEmission::ClampedCosine`] form.
struct ClampedDiffuse {
    /// `Σ Φ R_d / π`, per channel.
    peak: Vec3,
    normal: Vec3,
    /// The normalized irradiance of the vMF-convolved cosine of the cluster's concentration
    /// κ, ready for each receiver's cosine.
    fit: IrradianceFit,
}

/// A VSGL prepared for shading many receivers: its position, the emitted SG lobes
/// `G(ω; −ξ_v, λ_v)` of eq. (5) with their coefficients `c_v` (zero lobes left out) and the
/// clamped diffuse intensity when it replaces the diffuse SG.
pub(crate) struct Emitter {
    mu: Vec3,
    sigma2: f32,
    /// `1/(2πσ_v²)`, the coefficient of eq. (1) and (5).
    density: f32,
    lobes: [(Vec3, SphericalGaussian); 2],
    count: usize,
    clamped: Option<ClampedDiffuse>,
}

impl Emitter {
    pub(crate) fn new(vsgl: &Vsgl, diffuse: DiffuseEmission) -> Result<Self, VsglError> {
        let sigma2 = vsgl.sigma2;
        let density = 1.0 / (TAU * sigma2);
        if !(sigma2 > 0.0 && density.is_finite()) {
            return Err(VsglError::Variance(sigma2));
        }
        let unused = (Vec3::ZERO, SphericalGaussian::new(Vec3::Z, 0.0, 0.0)?);
        let mut lobes = [unused; 2];
        let mut count = 0;
        let mut clamped = None;
        let sg_diffuse = diffuse == DiffuseEmission::Sg;
        for (c, xi, lambda, as_sg) in [
            (
                vsgl.c_diffuse,
                vsgl.xi_diffuse,
                vsgl.lambda_diffuse,
                sg_diffuse,
            ),
            (
                vsgl.c_specular,
                vsgl.xi_specular,
                vsgl.lambda_specular,
                true,
            ),
        ] {
            if c == Vec3::ZERO {
                continue;
            }
            if as_sg {
                // I_v(−ω) ∝ G(−ω; ξ_v, λ_v) = G(ω; −ξ_v, λ_v): the light leaving μ_v towards x_p.
                lobes[count] = (c, SphericalGaussian::new(-xi, lambda, 1.0)?);
                count += 1;
            } else {
                clamped = Some(ClampedDiffuse {
                    peak: c * (sg_integral(lambda) * FRAC_1_PI),
                    normal: xi,
                    fit: IrradianceFit::new(vsgl.normal_concentration),
                });
            }
        }
        Ok(Self {
            mu: vsgl.mu,
            sigma2,
            density,
            lobes,
            count,
            clamped,
        })
    }

    /// [`vsgl_radiance`] at the receiver `surface` at `x_p`, with the SG algebra in `f32`
    /// (`SgSurface::radiance_f32`: the GPU's forms, held to the `f64` ones within 3e-5 by
    /// slc_bounds' tests; with the `f64` forms this loop took 1.4-1.5x as long).
    pub(crate) fn radiance(&self, surface: &SgSurface, x_p: Vec3) -> Result<Vec3, VsglError> {
        let d = self.mu - x_p;
        let r2 = d.length_squared();
        let position = if r2 > 0.0 {
            let sharpness = r2 / self.sigma2;
            if !sharpness.is_finite() {
                return Err(slc_bounds::BoundsError::Overflow("VSGL λ_σ").into());
            }
            // d / |d| is a unit vector: the literal skips `new`'s check in the inner loop.
            SphericalGaussian {
                axis: d / r2.sqrt(),
                sharpness,
                amplitude: self.density,
            }
        } else {
            SphericalGaussian::new(Vec3::Z, 0.0, self.density)?
        };
        let mut radiance = Vec3::ZERO;
        for (c, emitted) in &self.lobes[..self.count] {
            radiance += *c * surface.radiance_f32(&emitted.product_f32(&position)?);
        }
        if let Some(diffuse) = &self.clamped {
            let towards_receiver = if r2 > 0.0 {
                diffuse.fit.at(-diffuse.normal.dot(position.axis))
            } else {
                0.25
            };
            if towards_receiver > 0.0 {
                radiance += diffuse.peak * towards_receiver * surface.radiance_f32(&position);
            }
        }
        Ok(radiance)
    }
}

/// Indirect radiance at every pixel of `gbuffer` from every VSGL of `vsgls` (their weights
/// already applied), by [`vsgl_radiance`] with `diffuse`; with `visibility`, each VSGL that contributes is
/// tested with a shadow ray from the pixel to its mean position `μ_v` (VSGL eq. 3,
/// `V(x_p, μ_v)`). Pixels without a surface stay black. `progress` is called with the number
/// of pixels finished.
pub fn shade_vsgls(
    tracer: &Tracer,
    gbuffer: &GBuffer,
    vsgls: &[Vsgl],
    diffuse: DiffuseEmission,
    visibility: bool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Image, VsglError> {
    let emitters = vsgls
        .iter()
        .map(|v| Emitter::new(v, diffuse))
        .collect::<Result<Vec<_>, _>>()?;
    let mut image = Image::new(gbuffer.width, gbuffer.height);
    let w = gbuffer.width as usize;
    image
        .pixels
        .par_chunks_mut(w)
        .zip(gbuffer.samples.par_chunks(w))
        .try_for_each(|(out, row)| {
            for (o, g) in out.iter_mut().zip(row) {
                let Some(g) = g else { continue };
                let surface = SgSurface::new(g.normal, g.omega_o, &g.brdf)?;
                let from = tracer.lift(g.position, g.geometric_normal);
                for emitter in &emitters {
                    let c = emitter.radiance(&surface, g.position)?;
                    if c != Vec3::ZERO && (!visibility || tracer.unoccluded(from, emitter.mu)) {
                        *o += c;
                    }
                }
            }
            progress(w as u64);
            Ok::<(), VsglError>(())
        })?;
    Ok(image)
}
