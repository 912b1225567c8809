//! Materials: a Lambertian diffuse layer plus a GGX specular layer.
use crate::texture::{Texture, TextureId};
use glam::{Vec2, Vec3, Vec4};
use slc_bounds::{Anisotropy, Brdf, Fresnel};

/// The smallest GGX α a material may have. The method cannot render α = 0 (perfect mirrors):
/// the bounding spheroid's polar semi-axis grows as (1+α²)/(2α) and the GGX peak as 1/(πα²).
/// Loaders clamp smaller values up to this one and count the clamp as a warning.
pub const ALPHA_MIN: f32 = 1e-3;

/// How a material's parameters are given.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialModel {
    /// Diffuse albedo, F0 and α given directly (OBJ+MTL, built-in scenes). A diffuse texture,
    /// when present, multiplies `kd`.
    Direct {
        kd: Vec3,
        kd_texture: Option<TextureId>,
        f0: Vec3,
        alpha: f32,
    },
    /// glTF 2.0 metallic-roughness: `kd = base (1 - metallic)`,
    /// `F0 = 0.04 (1 - metallic) + base metallic`, `alpha = roughness²` (clamped to [`ALPHA_MIN`]).
    /// Textures multiply the factors: base colour (RGB), metallic (blue) and roughness (green).
    MetallicRoughness {
        base_color: Vec3,
        base_color_texture: Option<TextureId>,
        metallic: f32,
        roughness: f32,
        metallic_roughness_texture: Option<TextureId>,
    },
}

/// The largest relative index of refraction a material takes. The dielectric Fresnel factor
/// (supplemental eq. 3-5) squares η, which overflows `f32` above 1.8e19 (a NaN in every
/// glossy pixel); at η = 1e4 it is already within 4e-4 of 1 at every angle
/// (`((η − 1)/(η + 1))²` at normal incidence), so no larger value models anything more.
pub const MAX_ETA: f32 = 1e4;

/// `eta`, or why it cannot be a relative index of refraction: finite, above 0, at most
/// [`MAX_ETA`].
pub fn check_eta(eta: f32) -> Result<f32, String> {
    if eta > 0.0 && eta <= MAX_ETA {
        Ok(eta)
    } else {
        Err(format!(
            "eta {eta} must be above 0 and at most {MAX_ETA:e} (beyond it the Fresnel factor is 1 to four digits, and eta² overflows f32 above 1.8e19)"
        ))
    }
}

/// A surface material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub model: MaterialModel,
    /// Relative index of refraction: when set, the exact dielectric Fresnel factor replaces
    /// Schlick's approximation for the specular layer ([`check_eta`]: in (0, [`MAX_ETA`])).
    pub eta: Option<f32>,
    /// One-sided surfaces (the default) are black and reflect nothing seen from behind; they
    /// still block light. Two-sided ones flip their normal towards the viewer.
    pub double_sided: bool,
    /// A tangent-space normal map perturbing the shading normal (glTF `normalTexture`).
    pub normal_map: Option<NormalMap>,
    /// A cut-out mask (glTF `alphaMode: MASK`, OBJ `d` / `map_d`): where the coverage is below
    /// the cutoff the surface does not exist, for every ray and rasterizer.
    pub alpha_mask: Option<AlphaMask>,
    /// An anisotropic specular lobe (glTF `KHR_materials_anisotropy`).
    pub anisotropy: Option<MaterialAnisotropy>,
}

/// glTF `KHR_materials_anisotropy` (its factors; the texture is not read): the GGX roughness
/// grows to `α_t = mix(α, 1, s²)` along a direction rotated by `rotation` (radians,
/// counter-clockwise) from the tangent towards the bitangent; α stays along the
/// perpendicular direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialAnisotropy {
    /// `anisotropyStrength` s in [0, 1].
    pub strength: f32,
    /// `anisotropyRotation` in radians.
    pub rotation: f32,
}

impl MaterialAnisotropy {
    /// The lobe's anisotropy at a point with unit shading normal `n`, interpolated `tangent`
    /// (xyz: the direction of increasing u, w: the handedness ±1) and roughness `alpha`: the
    /// glTF frame T (orthogonalised against n), B = w (n × T), the direction
    /// `cos(rotation) T + sin(rotation) B` and `α_t = α + (1 − α) s²`. `None` where s = 0 (the
    /// lobe is isotropic) or the frame degenerates.
    pub fn at(&self, n: Vec3, tangent: Vec4, alpha: f32) -> Option<Anisotropy> {
        let s = self.strength.clamp(0.0, 1.0);
        if s == 0.0 {
            return None;
        }
        let (t, b) = tangent_frame(n, tangent)?;
        let (sin, cos) = self.rotation.sin_cos();
        let direction = (t * cos + b * sin).try_normalize()?;
        // Orthogonal to n up to the f32 rounding of the frame: remove what is left.
        let direction = (direction - n * n.dot(direction)).try_normalize()?;
        Some(Anisotropy {
            tangent: direction,
            alpha_t: (alpha + (1.0 - alpha) * s * s).clamp(alpha, 1.0),
        })
    }
}

/// A tangent-space normal map in glTF's convention: texel values `c` in [0, 1]³ encode the
/// normal `(2c - 1) (scale, scale, 1)` (renormalised) in the frame (T, B, N) with
/// `B = w (N x T)`, +X towards increasing u and +Y towards decreasing v (the image's up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalMap {
    /// A linear texture.
    pub texture: TextureId,
    pub scale: f32,
}

impl NormalMap {
    /// The perturbed shading normal at a point with interpolated unit normal `n` and tangent
    /// `tangent` (xyz: the direction of increasing u, w: the handedness ±1), where the map
    /// reads `texel`. The tangent is made orthogonal to `n` first (Gram-Schmidt), as MikkTSpace
    /// expects; `None` where the frame or the result degenerates (the caller keeps `n`).
    pub fn perturb(&self, n: Vec3, tangent: Vec4, texel: Vec3) -> Option<Vec3> {
        let (t, b) = tangent_frame(n, tangent)?;
        let c = (texel * 2.0 - Vec3::ONE) * Vec3::new(self.scale, self.scale, 1.0);
        (t * c.x + b * c.y + n * c.z).try_normalize()
    }
}

/// glTF's tangent frame at a point with unit normal `n` and interpolated `tangent` (xyz: the
/// direction of increasing u, w: the handedness ±1): T, the tangent made orthogonal to n
/// (Gram-Schmidt, as MikkTSpace expects), and B = w (n × T); `None` where T degenerates.
fn tangent_frame(n: Vec3, tangent: Vec4) -> Option<(Vec3, Vec3)> {
    let t = (tangent.truncate() - n * n.dot(tangent.truncate())).try_normalize()?;
    Some((t, n.cross(t) * if tangent.w < 0.0 { -1.0 } else { 1.0 }))
}

/// A cut-out mask: the surface exists where `factor * texture` (the texture's alpha) is at
/// least `cutoff` (glTF: "rendered fully opaque" there, "fully transparent" elsewhere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaMask {
    pub cutoff: f32,
    /// glTF `baseColorFactor`'s alpha, OBJ `d`.
    pub factor: f32,
    /// A texture holding the coverage in every channel (see `Encoding::Alpha` of the loaders).
    pub texture: Option<TextureId>,
}

impl AlphaMask {
    /// Whether the surface is cut away at `uv` (without texture coordinates only the factor
    /// counts).
    pub fn cuts(&self, uv: Option<Vec2>, textures: &[Texture]) -> bool {
        let coverage = match (self.texture.and_then(|id| textures.get(id)), uv) {
            (Some(t), Some(uv)) => t.sample(uv).x,
            _ => 1.0,
        };
        self.factor * coverage < self.cutoff
    }
}

/// glTF's metallic-roughness parameters as kd and F0 (glTF 2.0 specification, appendix B):
/// the dielectric F0 of 0.04 blended towards the base colour by `metallic`, and kd the
/// non-metallic part of the base colour.
pub fn metallic_kd_f0(base: Vec3, metallic: f32) -> (Vec3, Vec3) {
    (
        base * (1.0 - metallic),
        Vec3::splat(0.04 * (1.0 - metallic)) + base * metallic,
    )
}

impl Material {
    /// A one-sided material with explicit kd, F0 and α.
    pub fn direct(name: &str, kd: Vec3, f0: Vec3, alpha: f32) -> Self {
        Self::one_sided(
            name,
            MaterialModel::Direct {
                kd,
                kd_texture: None,
                f0,
                alpha: alpha.max(ALPHA_MIN),
            },
        )
    }

    /// A one-sided, untextured glTF metallic-roughness material.
    pub fn metallic_roughness(name: &str, base_color: Vec3, metallic: f32, roughness: f32) -> Self {
        Self::one_sided(
            name,
            MaterialModel::MetallicRoughness {
                base_color,
                base_color_texture: None,
                metallic,
                roughness,
                metallic_roughness_texture: None,
            },
        )
    }

    /// A one-sided material of `model`, without η, normal map, alpha mask or anisotropy.
    fn one_sided(name: &str, model: MaterialModel) -> Self {
        Self {
            name: name.to_string(),
            model,
            eta: None,
            double_sided: false,
            normal_map: None,
            alpha_mask: None,
            anisotropy: None,
        }
    }

    /// The BRDF at texture coordinate `uv`.
    pub fn brdf_at(&self, uv: Option<Vec2>, textures: &[Texture]) -> Brdf {
        let lookup = |id: Option<TextureId>| match (id, uv) {
            (Some(id), Some(uv)) => textures.get(id).map_or(Vec3::ONE, |t| t.sample(uv)),
            _ => Vec3::ONE,
        };
        let (kd, f0, alpha) = match self.model {
            MaterialModel::Direct {
                kd,
                kd_texture,
                f0,
                alpha,
            } => (kd * lookup(kd_texture), f0, alpha),
            MaterialModel::MetallicRoughness {
                base_color,
                base_color_texture: base_texture,
                metallic,
                roughness,
                metallic_roughness_texture: mr_texture,
            } => {
                let mr = lookup(mr_texture);
                let (m, r) = (
                    (metallic * mr.z).clamp(0.0, 1.0),
                    (roughness * mr.y).clamp(0.0, 1.0),
                );
                let (kd, f0) = metallic_kd_f0(base_color * lookup(base_texture), m);
                (kd, f0, r * r)
            }
        };
        let fresnel = match self.eta {
            Some(eta) => Fresnel::Dielectric(eta),
            None => Fresnel::Schlick(f0.clamp(Vec3::ZERO, Vec3::ONE)),
        };
        Brdf {
            kd: kd.clamp(Vec3::ZERO, Vec3::ONE),
            fresnel,
            alpha: alpha.clamp(ALPHA_MIN, 1.0),
            anisotropy: None,
        }
    }

    /// The BRDF at a surface point: [`Self::brdf_at`] with the anisotropy of
    /// [`MaterialAnisotropy::at`] for unit shading normal `n` and interpolated `tangent`
    /// (isotropic without tangents).
    pub fn surface_brdf(
        &self,
        uv: Option<Vec2>,
        n: Vec3,
        tangent: Option<Vec4>,
        textures: &[Texture],
    ) -> Brdf {
        let mut brdf = self.brdf_at(uv, textures);
        brdf.anisotropy = self
            .anisotropy
            .zip(tangent)
            .and_then(|(a, t)| a.at(n, t, brdf.alpha));
        brdf
    }

    /// The normal-mapped shading normal at a point whose interpolated unit vertex normal is
    /// `n` on a triangle with face normal `geometric` (either side), with interpolated
    /// `tangent` (xyz; w from the triangle's first vertex) and texture coordinate `uv`: `n`
    /// perturbed by the normal map (section 3.9.3 of glTF 2.0). `None` (the caller keeps
    /// `n`) where the material has no map, the mesh no tangents or texture coordinates, or
    /// the perturbed normal would leave `n`'s side or cross the triangle's plane.
    pub fn mapped_normal(
        &self,
        n: Vec3,
        geometric: Vec3,
        tangent: Option<Vec4>,
        uv: Option<Vec2>,
        textures: &[Texture],
    ) -> Option<Vec3> {
        let (map, tangent, uv) = (self.normal_map?, tangent?, uv?);
        let texture = textures.get(map.texture)?;
        let side = n.dot(geometric);
        map.perturb(n, tangent, texture.sample(uv))
            .filter(|p| p.dot(n) > 0.0 && p.dot(geometric) * side > 0.0)
    }

    /// Whether the surface is cut away at `uv` by its alpha mask (never without one).
    pub fn cuts(&self, uv: Option<Vec2>, textures: &[Texture]) -> bool {
        self.alpha_mask.is_some_and(|m| m.cuts(uv, textures))
    }

    /// Whether the specular layer can reflect anything (F0 > 0 or a dielectric).
    pub fn has_specular(&self) -> bool {
        match self.model {
            MaterialModel::Direct { f0, .. } => self.eta.is_some() || f0.max_element() > 0.0,
            MaterialModel::MetallicRoughness { .. } => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gltf_mapping_matches_the_reference_table() {
        // shared/reference/cornell-a: copper box, metallic 1, roughness sqrt(0.2).
        let m =
            Material::metallic_roughness("box", Vec3::new(0.95, 0.64, 0.54), 1.0, 0.2f32.sqrt());
        let b = m.brdf_at(None, &[]);
        assert_eq!(b.kd, Vec3::ZERO);
        assert_eq!(b.fresnel, Fresnel::Schlick(Vec3::new(0.95, 0.64, 0.54)));
        assert!((b.alpha - 0.2).abs() < 1e-6);
    }

    #[test]
    fn anisotropy_follows_khr_materials_anisotropy() {
        let mut m = Material::direct("m", Vec3::ONE, Vec3::splat(0.5), 0.25);
        let n = Vec3::Z;
        let tangent = Vec4::new(1.0, 0.0, 0.3, 1.0); // not orthogonal to n: Gram-Schmidt
        assert_eq!(m.surface_brdf(None, n, Some(tangent), &[]).anisotropy, None);
        let at = |strength: f32, rotation: f32, w: f32| {
            MaterialAnisotropy { strength, rotation }.at(n, tangent.with_w(w), 0.25)
        };
        // α_t = mix(α, 1, s²) along T rotated towards B = w (n × T).
        let a = at(0.5, 0.0, 1.0).unwrap();
        assert!((a.alpha_t - (0.25 + 0.75 * 0.25)).abs() < 1e-6);
        assert!((a.tangent - Vec3::X).length() < 1e-6);
        let quarter = core::f32::consts::FRAC_PI_2;
        assert!((at(1.0, quarter, 1.0).unwrap().tangent - Vec3::Y).length() < 1e-6);
        assert!((at(1.0, quarter, -1.0).unwrap().tangent + Vec3::Y).length() < 1e-6);
        assert_eq!(at(1.0, 0.0, 1.0).unwrap().alpha_t, 1.0);
        assert_eq!(at(0.0, 0.3, 1.0), None);
        assert_eq!(
            MaterialAnisotropy {
                strength: 1.0,
                rotation: 0.0
            }
            .at(n, Vec4::new(0.0, 0.0, 1.0, 1.0), 0.25),
            None,
            "a tangent along the normal has no frame"
        );
        m.anisotropy = Some(MaterialAnisotropy {
            strength: 0.5,
            rotation: 0.0,
        });
        let brdf = m.surface_brdf(None, n, Some(tangent), &[]);
        assert_eq!(brdf.anisotropy, at(0.5, 0.0, 1.0));
        assert_eq!(brdf.alpha, 0.25);
        assert_eq!(m.surface_brdf(None, n, None, &[]).anisotropy, None);
    }

    /// A 1x1 normal map storing `texel`.
    fn normal_mapped(texel: Vec3, scale: f32) -> (Material, Vec<Texture>) {
        let mut m = Material::direct("m", Vec3::ONE, Vec3::ZERO, 1.0);
        m.normal_map = Some(NormalMap { texture: 0, scale });
        let t = Texture {
            name: "n".into(),
            width: 1,
            height: 1,
            texels: vec![texel],
        };
        (m, vec![t])
    }

    #[test]
    fn normal_map_frame_follows_gltf() {
        let (n, t) = (Vec3::Z, Vec4::new(1.0, 0.0, 0.0, 1.0));
        let uv = Some(Vec2::splat(0.5));
        let at = |texel: Vec3, scale: f32, tangent: Vec4| {
            let (m, tex) = normal_mapped(texel, scale);
            m.mapped_normal(n, n, Some(tangent), uv, &tex).unwrap_or(n)
        };
        let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-6;
        // Flat: the vertex normal.
        assert!(close(at(Vec3::new(0.5, 0.5, 1.0), 1.0, t), n));
        // +X leans towards the tangent, +Y towards w (N x T) = +y for w = +1, -y for w = -1.
        let s = std::f32::consts::FRAC_1_SQRT_2;
        let x = Vec3::new(0.5 + 0.5 * s, 0.5, 0.5 + 0.5 * s);
        let y = Vec3::new(0.5, 0.5 + 0.5 * s, 0.5 + 0.5 * s);
        assert!(close(at(x, 1.0, t), Vec3::new(s, 0.0, s)));
        assert!(close(at(y, 1.0, t), Vec3::new(0.0, s, s)));
        assert!(close(
            at(y, 1.0, Vec4::new(1.0, 0.0, 0.0, -1.0)),
            Vec3::new(0.0, -s, s)
        ));
        // The tangent is made orthogonal to n first; scale multiplies x and y.
        assert!(close(
            at(x, 1.0, Vec4::new(1.0, 0.0, 5.0, 1.0)),
            Vec3::new(s, 0.0, s)
        ));
        let half = Vec3::new(0.5, 0.0, 1.0).normalize();
        assert!(close(at(x, 0.5, t), half));
        assert!(close(at(x, 0.0, t), n));
    }

    #[test]
    fn broken_normal_maps_keep_the_vertex_normal() {
        let n = Vec3::Z;
        let uv = Some(Vec2::ZERO);
        let t = Some(Vec4::new(1.0, 0.0, 0.0, 1.0));
        // Pointing below the surface, zero, a tangent along n, no tangent, no uv, no texture.
        for (texel, tangent, uv) in [
            (Vec3::new(0.5, 0.5, 0.0), t, uv),
            (Vec3::splat(0.5), t, uv),
            (
                Vec3::new(1.0, 0.5, 0.5),
                Some(Vec4::new(0.0, 0.0, 1.0, 1.0)),
                uv,
            ),
            (Vec3::new(1.0, 0.5, 0.5), None, uv),
            (Vec3::new(1.0, 0.5, 0.5), t, None),
        ] {
            let (m, tex) = normal_mapped(texel, 1.0);
            assert_eq!(
                m.mapped_normal(n, n, tangent, uv, &tex).unwrap_or(n),
                n,
                "{texel} {tangent:?} {uv:?}"
            );
        }
        let (m, _) = normal_mapped(Vec3::new(1.0, 0.5, 0.5), 1.0);
        assert_eq!(m.mapped_normal(n, n, t, uv, &[]), None);
        // A tilt that crosses the triangle's plane (a steep vertex normal, tilted further).
        let (m, tex) = normal_mapped(Vec3::new(1.0, 0.5, 0.75), 1.0);
        let steep = Vec3::new(0.9, 0.0, 0.1).normalize();
        let tangent = Some(Vec4::new(0.1, 0.0, -0.9, 1.0));
        assert!(m.mapped_normal(steep, steep, tangent, uv, &tex).is_some());
        assert_eq!(m.mapped_normal(steep, Vec3::Z, tangent, uv, &tex), None);
    }

    #[test]
    fn alpha_mask_cutoff() {
        let mut m = Material::direct("m", Vec3::ONE, Vec3::ZERO, 1.0);
        assert!(!m.cuts(None, &[]));
        let coverage = Texture {
            name: "a".into(),
            width: 2,
            height: 1,
            texels: vec![Vec3::splat(0.2), Vec3::ONE],
        };
        m.alpha_mask = Some(AlphaMask {
            cutoff: 0.5,
            factor: 1.0,
            texture: Some(0),
        });
        let tex = [coverage];
        assert!(m.cuts(Some(Vec2::new(0.25, 0.5)), &tex));
        assert!(!m.cuts(Some(Vec2::new(0.75, 0.5)), &tex));
        // Without texture coordinates only the factor counts; the factor scales the texture.
        assert!(!m.cuts(None, &tex));
        m.alpha_mask = Some(AlphaMask {
            cutoff: 0.5,
            factor: 0.4,
            texture: Some(0),
        });
        assert!(m.cuts(Some(Vec2::new(0.75, 0.5)), &tex) && m.cuts(None, &tex));
    }

    #[test]
    fn alpha_is_clamped() {
        let m = Material::direct("mirror", Vec3::ZERO, Vec3::ONE, 0.0);
        assert_eq!(m.brdf_at(None, &[]).alpha, ALPHA_MIN);
    }
}
