//! Virtual point lights.
use glam::Vec3;
use slc_bounds::shading_normal::{emitted_cosine, flux_scale};
use slc_bounds::{BoundsError, Brdf, DiffuseLobe, GlossyLobe};

/// Which lobe of the surface BRDF a VPL reflects with. A reflective-shadow-map texel yields a
/// diffuse VPL (where kd > 0) and a glossy VPL (where the specular layer reflects); together
/// they reflect with the full BRDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VplLobe {
    Diffuse,
    Glossy,
}

/// A virtual point light: the photon that arrived at a surface point, re-emitted with one
/// lobe of that surface's BRDF (paper eq. 4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vpl {
    /// Position q on the surface.
    pub position: Vec3,
    /// Unit shading normal n (facing the side the photon arrived from): the BRDF's.
    pub normal: Vec3,
    /// Unit geometric normal n_g on the same side: equal to `normal` unless the surface is
    /// normal-mapped (then eq. 4 takes the adjoint correction of `slc_bounds::shading_normal`).
    pub geometric_normal: Vec3,
    /// Unit direction ωi from the VPL towards where the photon came from.
    pub omega_i: Vec3,
    /// Radiant flux Φ of the photon that arrived (W per channel).
    pub flux: Vec3,
    /// The surface's BRDF at q.
    pub brdf: Brdf,
    pub lobe: VplLobe,
    /// Stable id: 2k for the diffuse and 2k + 1 for the glossy VPL of RSM texel k, whatever
    /// texels are empty, so every backend derives the same random numbers from it.
    pub id: u32,
    /// The VPL's Russian-roulette number ξ in (0, 1) (paper eq. 3): `rng::vpl_xi(seed, id)`.
    pub xi: f32,
}

impl Vpl {
    /// Radiant intensity towards unit direction `omega_o`, paper eq. (4):
    /// `I(ωo) = Φ f(ωi, ωo) max(ωo·n, 0)` with f the VPL's lobe of the BRDF; on a tilted
    /// shading normal the cosine is `slc_bounds::shading_normal::emitted_cosine`'s
    /// `(ωi·n)(ωo·n_g)/(ωi·n_g)` (Veach's adjoint correction).
    #[inline]
    pub fn intensity(&self, omega_o: Vec3) -> Vec3 {
        let cos_o = emitted_cosine(self.normal, self.geometric_normal, self.omega_i, omega_o);
        if cos_o <= 0.0 {
            return Vec3::ZERO;
        }
        let f = match self.lobe {
            VplLobe::Diffuse => self.brdf.diffuse(self.normal, self.omega_i, omega_o),
            VplLobe::Glossy => self.brdf.specular(self.normal, self.omega_i, omega_o),
        };
        self.flux * f * cos_o
    }

    /// The diffuse lobe of this VPL (eq. 4 with f = kd/π) around the origin, validated by
    /// slc-bounds: the form every bound of it is built from. On a tilted shading normal it is
    /// the cosine lobe around n_g with flux `Φ (ωi·n)/(ωi·n_g)`, which contains the VPL's
    /// intensity (`slc_bounds::shading_normal`).
    pub fn diffuse_lobe(&self) -> Result<DiffuseLobe, BoundsError> {
        let scale = flux_scale(self.normal, self.geometric_normal, self.omega_i);
        DiffuseLobe::new(
            Vec3::ZERO,
            self.geometric_normal,
            self.flux * scale,
            self.brdf.kd,
        )
    }

    /// The glossy lobe of this VPL (eq. 4, 6; anisotropic where its BRDF is) around the
    /// origin, validated by slc-bounds.
    pub fn glossy_lobe(&self) -> Result<GlossyLobe, BoundsError> {
        GlossyLobe::new(
            Vec3::ZERO,
            self.normal,
            self.omega_i,
            self.brdf.alpha,
            self.flux,
            self.brdf.fresnel,
        )?
        .with_geometric_normal(self.geometric_normal)?
        .with_anisotropy(self.brdf.anisotropy)
    }

    /// Whether the shading normal differs from the geometric one (a normal-mapped surface).
    #[inline]
    pub fn is_tilted(&self) -> bool {
        self.normal != self.geometric_normal
    }
}
