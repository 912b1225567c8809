//! The GGX specular lobe `ρ_s(ωo, ω) ⟨ω, n⟩` of VSGL eq. (2) as a spherical Gaussian fitted
//! to the true lobe's peak and integral ([`crate::sg::SpecularFit`]), and the GGX NDF's own SG.
use crate::check;
use crate::error::BoundsError;
use crate::fresnel::Fresnel;
use crate::sg::integral::integral_f64;
use crate::sg::lobe::SphericalGaussian;
use crate::sg::specular_fit::{SpecularFit, TABLE_MIN_COS};
use core::f64::consts::PI;
use glam::Vec3;

/// The smallest `ωo·n` of the fit ([`crate::sg::TABLE_MIN_COS`]): more grazing views are fitted as
/// this one.
const MIN_COS_O: f32 = TABLE_MIN_COS as f32;

/// The GGX NDF of the BRDF (eq. 7 of the stochastic-light-culling paper, [`crate::ggx::d`]) as an SG
/// over half vectors, `D(h) ≈ 1/(πα²) G(h; n, 2/α²)`: the peak value of D and, for small α,
/// the unit projected area `∫ D(h) (h·n) dh = 1` (Wang et al. 2009 fit the Cook-Torrance NDF the
/// same way; this is its GGX form as in Pettineo's "SG Series Part 4"). Fails for a non-unit
/// `n` or α outside (0, 1], and with [`BoundsError::Overflow`] for α below about 1e-19.
pub fn ggx_ndf_sg(n: Vec3, alpha: f32) -> Result<SphericalGaussian, BoundsError> {
    let n = check::unit(n, "normal")?;
    let a2 = f64::from(check::alpha(alpha)?).powi(2);
    Ok(SphericalGaussian {
        axis: n,
        sharpness: check::fits(2.0 / a2, "GGX SG sharpness")?,
        amplitude: check::fits(1.0 / (PI * a2), "GGX SG amplitude")?,
    })
}

/// `ρ_s(ωo, ω) ⟨ω, n⟩ ≈ weight · lobe(ω)` for the specular part of the project's BRDF
/// ([`crate::brdf::microfacet`]) seen from `ωo`: the SG through the true lobe's peak with the
/// true lobe's integral ([`SpecularFit`], tabulated over α and the view angle by quadrature),
/// and `weight = F(x)` at the cosine `x` where Schlick's Fresnel takes its mean over the true
/// lobe (so the weighted integral is exact for Schlick's Fresnel).
///
/// This replaces the warp of Wang et al. 2009 (section 4: the NDF SG of [`ggx_ndf_sg`] moved to
/// the mirror direction with its sharpness over `4 ωo·n`, weighted by `F G1² / (4 ωo·n)`),
/// which overestimates the lobe's integral by up to 2.1x (α = 1, normal view), misses the
/// peak's bend towards the normal for rough lobes and underestimates grazing views by orders
/// of magnitude. Isotropic, so it cannot follow the stretching of the true lobe at grazing
/// views (an ASG, Xu et al. 2013, would).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpecularLobeSg {
    /// The fitted lobe around the peak direction.
    pub lobe: SphericalGaussian,
    /// Fresnel at the lobe's mean Schlick cosine ([`SpecularFit::fresnel_cos`]), per channel.
    pub weight: Vec3,
}

impl SpecularLobeSg {
    /// The lobe for unit `n` and `omega_o` (pointing away from the surface), GGX roughness α in
    /// (0, 1] and a valid Fresnel model. A view below the surface gives a zero lobe (the BRDF
    /// is one-sided); views within 1e-6 of grazing are fitted as at `ωo·n = 1e-6`. Fails with
    /// [`BoundsError::Overflow`] where the sharpness does not fit `f32` (α below about 4e-17 at
    /// grazing views; at normal ones [`ggx_ndf_sg`]'s limit, about 1e-19, comes first).
    pub fn new(n: Vec3, omega_o: Vec3, alpha: f32, fresnel: Fresnel) -> Result<Self, BoundsError> {
        let ndf = ggx_ndf_sg(n, alpha)?;
        let omega_o = check::unit(omega_o, "view direction")?;
        let fresnel = check::fresnel(fresnel)?;
        let n = ndf.axis;
        let cos_o = n.dot(omega_o);
        if cos_o <= 0.0 {
            return Ok(Self {
                lobe: SphericalGaussian {
                    amplitude: 0.0,
                    ..ndf
                },
                weight: Vec3::ZERO,
            });
        }
        let c = f64::from(cos_o.max(MIN_COS_O));
        let fit = SpecularFit::lookup(f64::from(alpha), c);
        let sharpness = fit.sharpness(f64::from(alpha), c);
        // The peak, between the mirror direction and n (formed in f32 with the operations of
        // the GPU's `make_surface`, so that sharp lobes agree).
        let mirror = (2.0 * cos_o * n - omega_o).normalize();
        let mirror = if mirror.is_finite() { mirror } else { n };
        let w = fit.mirror_weight as f32;
        let axis = (mirror * w + n * (1.0 - w)).normalize_or(n);
        Ok(Self {
            lobe: SphericalGaussian {
                axis,
                sharpness: check::fits(sharpness, "GGX SG sharpness")?,
                amplitude: check::fits(fit.integral / integral_f64(sharpness), "GGX SG amplitude")?,
            },
            weight: fresnel.eval(fit.fresnel_cos.clamp(0.0, 1.0) as f32),
        })
    }
}
