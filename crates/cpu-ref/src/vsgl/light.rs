//! The parameters of one virtual spherical Gaussian light (VSGL section 3.1).
use super::sums::ClusterSums;
use core::f32::consts::TAU;
use glam::Vec3;
use slc_bounds::sg::{exact_sharpness, ggx_mixture, LobeStretch, COSINE_LOBE_SHARPNESS};
use slc_bounds::{BoundsError, SphericalGaussian, ToksvigSum};

/// A VSGL: the radiant intensity `I_v(ω) ≈ c_d G(ω; ξ_d, λ_d) + c_s G(ω; ξ_s, λ_s)` of a
/// cluster of VPLs (section 3.1.1, one SG per BRDF component) and its isotropic Gaussian
/// positional distribution `(μ_v, σ_v²)` (section 3.1.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vsgl {
    /// `c_v = Σ Φ_i R_{d,i} / A(λ_v)` of the diffuse lobe, per channel.
    pub c_diffuse: Vec3,
    /// `ξ_v = ξ̄_v/|ξ̄_v|` of the diffuse lobe (+z for a zero mean vector).
    pub xi_diffuse: Vec3,
    /// `λ_v` of the diffuse lobe, from `|ξ̄_v|` by the map's inverse (`|ξ̄_v|/(1 − |ξ̄_v|)`).
    pub lambda_diffuse: f32,
    /// The concentration κ of the cluster's normals (weighted by `Φ R_d`) about `ξ_d`: the
    /// von Mises-Fisher sharpness whose mean length `coth κ − 1/κ` is that of the mean normal,
    /// `|ξ̄_v|` over the mean length of one texel's diffuse lobe. Infinite (at most 1.7e7) for
    /// coplanar texels. `DiffuseEmission::ClampedCosine` uses it.
    pub normal_concentration: f32,
    /// `c_v` of the specular lobe, per channel.
    pub c_specular: Vec3,
    /// `ξ_v` of the specular lobe.
    pub xi_specular: Vec3,
    /// `λ_v` of the specular lobe.
    pub lambda_specular: f32,
    /// The direction of the specular-weighted mean normal (sum (g); zero where it is zero),
    /// which with `ξ_s` spans the plane of incidence of the lobe's stretch
    /// ([`Vsgl::specular_stretch`]).
    pub specular_normal: Vec3,
    /// `μ_v = Σ w_i x_i / Σ w_i` (zero for an empty cluster).
    pub mu: Vec3,
    /// `σ_v² = Σ w_i |x_i|² / Σ w_i − |μ_v|²`, clamped to at least the floor given.
    pub sigma2: f32,
    /// The positional weight `Σ w_i`, the total of the RGB channels of `Σ Φ_i (R_d + R_s)`.
    pub weight: f32,
}

impl Vsgl {
    /// The VSGL of a cluster: the Toksvig back-conversion of its lobe buffers (section 3.1.1,
    /// with the map the sums were built with) and its weighted mean and variance (3.1.2).
    ///
    /// A single VPL has `σ_v² = 0`, for which eq. (1) and the `λ_σ = d²/σ_v²` of eq. (4)
    /// diverge (the VSGL degenerates into the VPL): `σ_v²` is clamped to `sigma2_floor` (≥ 0),
    /// which should be a small positive area, e.g. the squared world size of a level-0 texel's
    /// footprint or `1e-8` of the squared scene diagonal. Fails with [`BoundsError::Overflow`]
    /// if a coefficient leaves the `f32` range.
    pub fn from_sums(sums: &ClusterSums, sigma2_floor: f32) -> Result<Self, BoundsError> {
        let (xi_diffuse, lambda_diffuse, c_diffuse) =
            filtered(&sums.diffuse_lobe, sums.diffuse_weight.as_vec3())?;
        let texel_mean = sums.diffuse_lobe.map().length(COSINE_LOBE_SHARPNESS);
        let mean_normal = sums.diffuse_lobe.mean_vector().length() / texel_mean;
        let normal_concentration = exact_sharpness(mean_normal);
        let (xi_specular, lambda_specular, c_specular) =
            filtered(&sums.specular_lobe, sums.specular_weight.as_vec3())?;
        let specular_normal = sums.specular_normal.normalize_or_zero().as_vec3();
        let weight = sums.weight();
        let (mu, sigma2) = if weight > 0.0 {
            let mu = sums.weighted_position / weight;
            let sigma2 = sums.weighted_squared_norm / weight - mu.length_squared();
            (mu.as_vec3(), sigma2.max(0.0) as f32)
        } else {
            (Vec3::ZERO, 0.0)
        };
        Ok(Self {
            c_diffuse,
            xi_diffuse,
            lambda_diffuse,
            normal_concentration,
            c_specular,
            xi_specular,
            lambda_specular,
            specular_normal,
            mu,
            sigma2: sigma2.max(sigma2_floor),
            weight: weight as f32,
        })
    }

    /// The VSGL with its radiant intensity and weight multiplied by `factor` (position and
    /// variance kept): a sampled cluster with its Monte Carlo weight `1/(N P)` (section 4.2).
    pub fn scaled(self, factor: f32) -> Self {
        Self {
            c_diffuse: self.c_diffuse * factor,
            c_specular: self.c_specular * factor,
            weight: self.weight * factor,
            ..self
        }
    }

    /// The radiant intensity `I_v(ω) ≈ c_d G(ω; ξ_d, λ_d) + c_s G(ω; ξ_s, λ_s)` towards the
    /// unit direction `omega` (section 3.1.1), per channel, with the specular lobe as the
    /// shading takes it ([`Vsgl::specular_intensity`]).
    pub fn intensity(&self, omega: Vec3) -> Vec3 {
        let diffuse = SphericalGaussian {
            axis: self.xi_diffuse,
            sharpness: self.lambda_diffuse,
            amplitude: 1.0,
        };
        self.c_diffuse * diffuse.eval(omega) + self.specular_intensity(omega)
    }

    /// The specular part `c_s G(ω; ξ_s, λ_s)` of [`Vsgl::intensity`], the SG replaced by the
    /// SGs of GGX's profile ([`slc_bounds::sg::ggx_mixture`], which keeps its integral), each
    /// stretched ([`Vsgl::specular_stretch`]): sharpness `λ k(ω)` along ω.
    pub fn specular_intensity(&self, omega: Vec3) -> Vec3 {
        let lobe = SphericalGaussian {
            axis: self.xi_specular,
            sharpness: self.lambda_specular,
            amplitude: 1.0,
        };
        let k = self.specular_stretch().factor(omega.to_array());
        let sum = ggx_mixture(&lobe)
            .map(|g| {
                let stretched = SphericalGaussian {
                    sharpness: g.sharpness * k,
                    ..g
                };
                stretched.eval(omega)
            })
            .sum::<f32>();
        self.c_specular * sum
    }

    /// The stretch of the specular lobe ([`LobeStretch::new`] of `ξ_s`, `λ_s` and the
    /// specular-weighted mean normal): none for broad lobes or an unknown normal.
    pub fn specular_stretch(&self) -> LobeStretch {
        LobeStretch::new(self.xi_specular, self.lambda_specular, self.specular_normal)
    }

    /// The coefficients `c_v/(2π σ_v²)` of the emitted radiance of eq. (1) (and of `c_in` in
    /// eq. 5), `[diffuse, specular]`; infinite for `σ_v² = 0` (see [`Vsgl::from_sums`]).
    pub fn emitted_coefficients(&self) -> [Vec3; 2] {
        let k = 1.0 / (TAU * self.sigma2);
        [self.c_diffuse * k, self.c_specular * k]
    }
}

/// `(ξ_v, λ_v, c_v)` of one lobe buffer: the axis and sharpness of the filtered lobe and the
/// RGB weight `Σ Φ_i R_i` over `A(λ_v)` (the scalar lobe's amplitude is the total over `A`).
fn filtered(lobe: &ToksvigSum, rgb_weight: Vec3) -> Result<(Vec3, f32, Vec3), BoundsError> {
    let sg = lobe.to_lobe()?;
    let c = rgb_weight / slc_bounds::sg::sg_integral(sg.sharpness);
    Ok((sg.axis, sg.sharpness, c))
}
