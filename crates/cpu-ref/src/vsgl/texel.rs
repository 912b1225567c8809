//! The radiant intensity of one RSM texel's VPL as two weighted normalized SGs (VSGL section
//! 3.1.1): `I_i(ω) = Φ_i ρ(ω'_i, ω) ⟨ω, n_i⟩ ≈ Φ_i R_d G(ω; n, λ_d)/A(λ_d) + Φ_i R_s G(ω; ξ_s,
//! λ_s)/A(λ_s)`.
use crate::rsm::RsmTexel;
use glam::Vec3;
use slc_bounds::sg::{SpecularLobeSg, COSINE_LOBE_SHARPNESS};
use slc_bounds::{BoundsError, SphericalGaussian};

/// The reflectances and normalized lobes of one texel (VSGL section 3.1.1, "the product of a
/// reflectance and normalized spherical Gaussian").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelLobes {
    /// `R_d = kd`: the integral of `kd/π ⟨ω, n⟩` over the sphere, per channel.
    pub diffuse_reflectance: Vec3,
    /// `G(ω; n, 2.133)/A(2.133)`: the shape of the cosine SG fit
    /// ([`slc_bounds::sg::clamped_cosine_sg`]) with unit integral. So `R_d G/A` keeps the
    /// energy of the true intensity exactly (the un-normalized fit `1.17 G` integrates 8.2 %
    /// above π) at the price of a peak 8.2 % above `kd/π` (`1/A(2.133) = 0.3443` vs `1/π`).
    pub diffuse_lobe: SphericalGaussian,
    /// `R_s`: the integral of the specular SG approximation of `ρ_s(ω'_i, ω) ⟨ω, n⟩`, per
    /// channel (the specular directional albedo as the SG sees it).
    pub specular_reflectance: Vec3,
    /// The fitted GGX lobe of [`SpecularLobeSg`] seen from `ω'_i` (reciprocity: the view
    /// direction of the fit is the photon's incoming direction), normalized: axis the true
    /// lobe's peak (the mirror direction of `ω'_i` for smooth lobes, bent towards `n` for rough
    /// ones), its sharpness the one that gives the peak value the true integral.
    pub specular_lobe: SphericalGaussian,
}

impl TexelLobes {
    /// The lobes of `texel`, about its shading normal. A photon arriving below the shading
    /// normal (`ω'_i·n ≤ 0`, possible with interpolated normals) reflects nothing, like the
    /// one-sided BRDF: both reflectances are zero. Fails for an invalid BRDF.
    pub fn new(texel: &RsmTexel) -> Result<Self, BoundsError> {
        let n = texel.normal;
        let diffuse_lobe = SphericalGaussian::normalized(n, COSINE_LOBE_SHARPNESS)?;
        let brdf = texel.brdf;
        let specular = SpecularLobeSg::new(n, texel.omega_i, brdf.isotropic_alpha(), brdf.fresnel)?;
        let specular_lobe = specular.lobe.to_normalized();
        if n.dot(texel.omega_i) <= 0.0 {
            return Ok(Self {
                diffuse_reflectance: Vec3::ZERO,
                diffuse_lobe,
                specular_reflectance: Vec3::ZERO,
                specular_lobe,
            });
        }
        Ok(Self {
            diffuse_reflectance: brdf.kd,
            diffuse_lobe,
            specular_reflectance: specular.weight * specular.lobe.integral(),
            specular_lobe,
        })
    }
}
