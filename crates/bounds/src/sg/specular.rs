//! The GGX specular lobe `ρ_s(ωo, ω) ⟨ω, n⟩` of VSGL eq. (2) as a spherical Gaussian: the
//! warped-NDF approximation of Wang et al. 2009 ("All-Frequency Rendering of Dynamic,
//! Spatially-Varying Reflectance", SIGGRAPH Asia, section 4).
use crate::check;
use crate::error::BoundsError;
use crate::fresnel::Fresnel;
use crate::ggx;
use crate::sg::lobe::SphericalGaussian;
use core::f64::consts::PI;
use glam::Vec3;

/// The smallest `ωo·n` used for the warp: at more grazing views the lobe's sharpness
/// `λ/(4 ωo·n)` would grow without bound while its weight, proportional to `ωo·n`, vanishes.
const MIN_COS_O: f32 = 1e-6;

/// The GGX NDF of the BRDF (eq. 7 of the stochastic-light-culling paper, [`ggx::d`]) as an SG
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
/// ([`crate::brdf::microfacet`]) seen from `ωo`, by the warp of Wang et al. 2009 (section 4):
/// the NDF SG of [`ggx_ndf_sg`] moves to the mirror direction `r = 2(ωo·n)n − ωo` with its
/// sharpness divided by `4 ωo·n` (the Jacobian `4|ωo·h|` of the half-vector map at h = n) and
/// its amplitude kept, and the remaining factors `F(ωi·h) G1(ωi) G1(ωo) ⟨ωi, n⟩ / (4 ⟨ωi, n⟩
/// ⟨ωo, n⟩)` are evaluated at the lobe axis `ωi = r`, where `h = n`:
/// `weight = F(ωo·n) G1(ωo·n)² / (4 ωo·n)`. Isotropic, so it underestimates the stretching of
/// the true lobe at grazing views (an ASG, Xu et al. 2013, would capture it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpecularLobeSg {
    /// The warped NDF lobe around the mirror direction.
    pub lobe: SphericalGaussian,
    /// Fresnel, masking and the cosine at the lobe axis over `4 ωo·n`, per channel.
    pub weight: Vec3,
}

impl SpecularLobeSg {
    /// The lobe for unit `n` and `omega_o` (pointing away from the surface), GGX roughness α in
    /// (0, 1] and a valid Fresnel model. A view below the surface gives a zero lobe (the BRDF
    /// is one-sided); views within 1e-6 of grazing are warped as at `ωo·n = 1e-6`.
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
        let c = cos_o.max(MIN_COS_O);
        let mirror = (2.0 * cos_o * n - omega_o).normalize();
        let sharpness = check::fits(
            f64::from(ndf.sharpness) / (4.0 * f64::from(c)),
            "warped GGX SG sharpness",
        )?;
        // G1(c)² / (4c) = (G1/cos)² c / 4, finite at grazing views.
        let g = ggx::g1_over_cos(alpha, c);
        Ok(Self {
            lobe: SphericalGaussian {
                axis: if mirror.is_finite() { mirror } else { n },
                sharpness,
                amplitude: ndf.amplitude,
            },
            weight: fresnel.eval(c) * (0.25 * g * g * c),
        })
    }
}
