//! A VSGL prepared for shading many receivers ([`Emitter`]) and its radiance at a receiver
//! (VSGL eq. 2 with the incoming radiance of eq. 3-5), written once for one VSGL (`f32`) and for
//! eight at a time (`slc_bounds::lanes`), so the two agree bit for bit.
use super::error::VsglError;
use super::light::Vsgl;
use core::f32::consts::{FRAC_1_PI, TAU};
use glam::Vec3;
use slc_bounds::lanes::{dot, Real};
use slc_bounds::sg::{
    finite, ggx_mixture, sg_integral, splat3, IrradianceFit, LobeStretch, SgLanes,
};
use slc_bounds::{BoundsError, SgSurface, SphericalGaussian};
use slc_core::frame::DiffuseEmission;

/// One emitted SG lobe `c_v G(ω; −ξ_v, λ_v)` of eq. (5), where it is present (a zero
/// coefficient leaves the lobe out) and where it is stretched by the emitter's
/// [`LobeStretch`] (the specular SGs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EmittedLobe<R: Real> {
    pub(crate) c: [R; 3],
    pub(crate) lobe: SgLanes<R>,
    pub(crate) present: R::Mask,
    pub(crate) stretched: R::Mask,
}

/// A VSGL's diffuse intensity in the [`DiffuseEmission::ClampedCosine`] form, where present.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClampedDiffuse<R: Real> {
    /// `Σ Φ R_d / π`, per channel.
    pub(crate) peak: [R; 3],
    pub(crate) normal: [R; 3],
    /// The normalized irradiance of the vMF-convolved cosine of the cluster's concentration
    /// κ, ready for each receiver's cosine.
    pub(crate) fit: IrradianceFit<R>,
    pub(crate) present: R::Mask,
}

/// A VSGL prepared for shading many receivers (one per lane of `R`): its position, the
/// emitted SG lobes `G(ω; −ξ_v, λ_v)` of eq. (5) with their coefficients `c_v` (the SG
/// diffuse lobe first, then the specular one as the three SGs of its GGX profile,
/// [`slc_bounds::sg::ggx_mixture`], with the specular lobe's stretch) and the clamped diffuse
/// intensity when it replaces the diffuse SG; `live` where the lane holds a VSGL.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Emitter<R: Real = f32> {
    pub(crate) mu: [R; 3],
    pub(crate) sigma2: R,
    /// `1/(2πσ_v²)`, the coefficient of eq. (1) and (5).
    pub(crate) density: R,
    pub(crate) lobes: [EmittedLobe<R>; 4],
    pub(crate) clamped: ClampedDiffuse<R>,
    pub(crate) stretch: LobeStretch<R>,
    pub(crate) live: R::Mask,
}

impl Emitter {
    /// A lane that holds no VSGL (finite values, nothing present).
    pub(crate) const DARK: Self = {
        let none = SgLanes {
            axis: [0.0, 0.0, 1.0],
            sharpness: 0.0,
            amplitude: 0.0,
        };
        let lobe = EmittedLobe {
            c: [0.0; 3],
            lobe: none,
            present: false,
            stretched: false,
        };
        Self {
            mu: [0.0; 3],
            sigma2: 1.0,
            density: 1.0,
            lobes: [lobe; 4],
            clamped: ClampedDiffuse {
                peak: [0.0; 3],
                normal: [0.0, 0.0, 1.0],
                fit: IrradianceFit {
                    mean: 0.0,
                    x: 1.0,
                    away: 0.25,
                },
                present: false,
            },
            stretch: LobeStretch::NONE,
            live: false,
        }
    };

    /// `vsgl` prepared for shading, its diffuse lobe as `diffuse` says. Fails for a `σ_v²`
    /// that is not positive and finite, or a lobe whose sharpness is not finite.
    pub(crate) fn new(vsgl: &Vsgl, diffuse: DiffuseEmission) -> Result<Self, VsglError> {
        let sigma2 = vsgl.sigma2;
        let density = 1.0 / (TAU * sigma2);
        if !(sigma2 > 0.0 && density.is_finite()) {
            return Err(VsglError::Variance(sigma2));
        }
        let mut e = Self {
            mu: vsgl.mu.to_array(),
            sigma2,
            density,
            live: true,
            ..Self::DARK
        };
        // I_v(−ω) ∝ G(−ω; ξ_v, λ_v) = G(ω; −ξ_v, λ_v): the light leaving μ_v towards x_p.
        let emitted = |xi: Vec3, lambda| SphericalGaussian::new(-xi, lambda, 1.0);
        let mut sgs: Vec<(Vec3, SphericalGaussian, bool)> = Vec::with_capacity(4);
        if vsgl.c_diffuse != Vec3::ZERO {
            if diffuse == DiffuseEmission::Sg {
                sgs.push((
                    vsgl.c_diffuse,
                    emitted(vsgl.xi_diffuse, vsgl.lambda_diffuse)?,
                    false,
                ));
            } else {
                e.clamped = ClampedDiffuse {
                    peak: (vsgl.c_diffuse * (sg_integral(vsgl.lambda_diffuse) * FRAC_1_PI))
                        .to_array(),
                    normal: vsgl.xi_diffuse.to_array(),
                    fit: IrradianceFit::new(vsgl.normal_concentration),
                    present: true,
                };
            }
        }
        if vsgl.c_specular != Vec3::ZERO {
            let lobe = emitted(vsgl.xi_specular, vsgl.lambda_specular)?;
            e.stretch = vsgl.specular_stretch();
            let stretched = e.stretch != LobeStretch::NONE;
            sgs.extend(ggx_mixture(&lobe).map(|g| (vsgl.c_specular, g, stretched)));
        }
        for (slot, (c, lobe, stretched)) in e.lobes.iter_mut().zip(sgs) {
            *slot = EmittedLobe {
                c: c.to_array(),
                lobe: SgLanes::splat(&lobe),
                present: true,
                stretched,
            };
        }
        Ok(e)
    }

    /// [`super::vsgl_radiance`] at the receiver `surface` at `x_p` ([`Emitter::radiance_in`]
    /// for one VSGL).
    pub(crate) fn radiance(&self, surface: &SgSurface, x_p: Vec3) -> Result<Vec3, VsglError> {
        let (radiance, overflow) = self.radiance_in(surface, x_p.to_array());
        if overflow {
            return Err(OVERFLOW.into());
        }
        Ok(Vec3::from(radiance))
    }
}

/// The error of a lane whose `λ_σ` or lobe product leaves `f32`.
pub(crate) const OVERFLOW: BoundsError = BoundsError::Overflow("VSGL λ_σ or SG product");

impl<R: Real> Emitter<R> {
    /// [`super::vsgl_radiance`] of each lane's VSGL at the receiver `surface` at `x_p`, with
    /// the SG algebra in `f32` (`SgSurface::radiance_lanes`: the GPU's forms, held to the `f64`
    /// ones within 3e-5 by slc_bounds' tests), and the live lanes where `λ_σ` or a lobe
    /// product leaves `f32`. A receiver at `μ_v` itself sees the constant `λ_σ = 0`.
    #[inline(always)]
    pub(crate) fn radiance_in(&self, surface: &SgSurface, x_p: [R; 3]) -> ([R; 3], R::Mask) {
        let zero = R::splat(0.0);
        let d = [
            self.mu[0] - x_p[0],
            self.mu[1] - x_p[1],
            self.mu[2] - x_p[2],
        ];
        let r2 = dot(d, d);
        let near = r2.gt(zero);
        let sharpness = r2 / self.sigma2;
        let mut overflow = near & !finite(sharpness);
        let r = r2.sqrt();
        // ξ_μ = d / |d| and λ_σ = |d|²/σ_v² of eq. (4); the constant lobe at μ_v itself.
        let z = splat3::<R>(Vec3::Z);
        let position = SgLanes {
            axis: [
                R::select(near, d[0] / r, z[0]),
                R::select(near, d[1] / r, z[1]),
                R::select(near, d[2] / r, z[2]),
            ],
            sharpness: R::select(near, sharpness, zero),
            amplitude: self.density,
        };
        let mut radiance = [zero; 3];
        // The stretch towards the receiver, formed once for the specular SGs (one axis).
        let (mut k, mut have_k) = (R::splat(1.0), false);
        for lobe in &self.lobes {
            if !R::any(lobe.present) {
                continue;
            }
            let mut emitted = lobe.lobe;
            if R::any(lobe.stretched) {
                if !have_k {
                    (k, have_k) = (self.stretch.factor(position.axis), true);
                }
                let l = emitted.sharpness;
                let a = self.stretch.amplitude_factor(l, k, position.sharpness);
                emitted.sharpness = R::select(lobe.stretched, l * k, l);
                emitted.amplitude =
                    R::select(lobe.stretched, emitted.amplitude * a, emitted.amplitude);
            }
            let (product, over) = emitted.product(&position);
            overflow = overflow | (over & lobe.present);
            let shaded = surface.radiance_lanes(&product);
            for (c, out) in radiance.iter_mut().enumerate() {
                *out = *out + R::select(lobe.present, lobe.c[c] * shaded[c], zero);
            }
        }
        let clamped = &self.clamped;
        if R::any(clamped.present) {
            let cos = -dot(clamped.normal, position.axis);
            let towards_receiver = R::select(near, clamped.fit.at(cos), R::splat(0.25));
            let lit = clamped.present & towards_receiver.gt(zero);
            if R::any(lit) {
                let shaded = surface.radiance_lanes(&position);
                for (c, out) in radiance.iter_mut().enumerate() {
                    let v = clamped.peak[c] * towards_receiver * shaded[c];
                    *out = *out + R::select(lit, v, zero);
                }
            }
        }
        (radiance, overflow & self.live)
    }
}
