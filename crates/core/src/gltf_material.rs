//! glTF materials -> [`Material`]s with [`MaterialModel::MetallicRoughness`], and their textures.
//!
//! Base colour factor (RGB; alpha ignored), metallic and roughness factors are kept as given,
//! `doubleSided` maps to [`Material::double_sided`]. Base-colour textures are decoded from sRGB,
//! metallic-roughness textures are linear; both must use `TEXCOORD_0`. A texture that cannot
//! be read or decoded gives a warning and the factor alone is used. `KHR_materials_ior` sets
//! [`Material::eta`] for non-metallic materials (metallic factor 0) when `ior` >= 1 (at most
//! [`MAX_ETA`], which reflects as any larger index does to four digits); a metal's
//! Fresnel reflectance is its base colour, so `eta` stays `None` there (and without the
//! extension: Schlick with F0 = 0.04, the glTF default `ior` 1.5).
//!
//! `normalTexture` (linear, with its `scale`) becomes [`Material::normal_map`]; `alphaMode:
//! MASK` becomes [`Material::alpha_mask`] with `alphaCutoff` (default 0.5), the base colour
//! factor's alpha and the base-colour image's alpha channel. `alphaMode: BLEND` is drawn
//! opaque. `KHR_materials_anisotropy`'s strength and rotation become
//! [`Material::anisotropy`]; its `anisotropyTexture` is not read (listed as ignored). Emission, blending and every material extension slc does not read are recorded in
//! [`LoadReport::ignored`](crate::LoadReport) with the materials that use them.
use crate::gltf_document::SUPPORTED_EXTENSIONS;
use crate::gltf_loader::read_uri;
use crate::import_util::small_alpha_warning;
use crate::material::{AlphaMask, Material, MaterialAnisotropy, MaterialModel, NormalMap, MAX_ETA};
use crate::scene::{LoadReport, Scene};
use crate::texture::TextureId;
use crate::texture_decode::{decode_texture, Encoding};
use glam::Vec3;
use std::collections::HashMap;
use std::path::Path;

/// The glTF default material (spec: base colour 1, metallic 1, roughness 1), for primitives
/// without a material.
pub(crate) fn default_material() -> Material {
    Material::metallic_roughness("glTF default material", Vec3::ONE, 1.0, 1.0)
}

/// Appends one material per glTF material, in the document's order (so glTF material indices
/// are indices into `scene.materials`), and the textures they use to `scene.textures`.
pub(crate) fn load_materials(
    document: &gltf::Document,
    buffers: &[Vec<u8>],
    base: &Path,
    scene: &mut Scene,
) {
    let mut textures = TextureLoader {
        document,
        buffers,
        base,
        cache: HashMap::new(),
    };
    for (i, m) in document.materials().enumerate() {
        let name = m
            .name()
            .map_or_else(|| format!("material {i}"), str::to_string);
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, a] = pbr.base_color_factor();
        let base_color_texture = pbr
            .base_color_texture()
            .and_then(|t| textures.get(t.texture(), t.tex_coord(), Encoding::Srgb, &name, scene));
        let metallic_roughness_texture = pbr
            .metallic_roughness_texture()
            .and_then(|t| textures.get(t.texture(), t.tex_coord(), Encoding::Linear, &name, scene));
        let normal_map = m.normal_texture().and_then(|t| {
            let texture =
                textures.get(t.texture(), t.tex_coord(), Encoding::Linear, &name, scene)?;
            Some(NormalMap {
                texture,
                scale: t.scale(),
            })
        });
        let alpha_mask = match m.alpha_mode() {
            gltf::material::AlphaMode::Mask => Some(AlphaMask {
                cutoff: m.alpha_cutoff().unwrap_or(0.5),
                factor: a,
                texture: pbr.base_color_texture().and_then(|t| {
                    textures.get(t.texture(), t.tex_coord(), Encoding::Alpha, &name, scene)
                }),
            }),
            _ => None,
        };
        let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
        scene.report.warnings.extend(small_alpha_warning(
            &name,
            roughness.clamp(0.0, 1.0).powi(2),
        ));
        record_ignored(&m, &name, &mut scene.report);
        let anisotropy = read_anisotropy(&m, &name, &mut scene.report);
        scene.materials.push(Material {
            name,
            model: MaterialModel::MetallicRoughness {
                base_color: Vec3::new(r, g, b),
                base_color_texture,
                metallic,
                roughness,
                metallic_roughness_texture,
            },
            eta: m
                .ior()
                .filter(|&ior| metallic == 0.0 && ior >= 1.0)
                // Larger indices reflect as MAX_ETA does to four digits.
                .map(|ior| ior.min(MAX_ETA)),
            double_sided: m.double_sided(),
            normal_map,
            alpha_mask,
            anisotropy,
        });
    }
}

/// Records what of material `m` slc does not model: emission, alpha blending (drawn opaque),
/// and extensions other than the ones it reads.
fn record_ignored(m: &gltf::Material, name: &str, report: &mut LoadReport) {
    if Vec3::from(m.emissive_factor()).max_element() > 0.0 || m.emissive_texture().is_some() {
        report.ignore("emission", name);
    }
    if m.alpha_mode() == gltf::material::AlphaMode::Blend {
        report.ignore("alphaMode BLEND (drawn opaque)", name);
    }
    for e in m.extensions().into_iter().flat_map(|e| e.keys()) {
        if !SUPPORTED_EXTENSIONS.contains(&e.as_str()) {
            report.ignore(e, name);
        }
    }
}

/// `KHR_materials_anisotropy` of material `m`: `None` without the extension or with strength
/// 0. A strength outside [0, 1] is clamped and a non-finite value replaced by the default
/// (0), with a warning; the texture is listed as ignored.
fn read_anisotropy(
    m: &gltf::Material,
    name: &str,
    report: &mut LoadReport,
) -> Option<MaterialAnisotropy> {
    const NAME: &str = "KHR_materials_anisotropy";
    let ext = m.extensions()?.get(NAME)?;
    if ext.get("anisotropyTexture").is_some() {
        report.ignore("KHR_materials_anisotropy anisotropyTexture", name);
    }
    let mut read = |key: &str, range: (f32, f32)| {
        let value = ext
            .get(key)
            .map(|v| v.as_f64().map_or(f32::NAN, |x| x as f32));
        match value {
            None => 0.0,
            Some(x) if x.is_finite() && x >= range.0 && x <= range.1 => x,
            Some(x) => {
                let fixed = if x.is_finite() {
                    x.clamp(range.0, range.1)
                } else {
                    0.0
                };
                report.warnings.push(format!(
                    "material '{name}': {NAME} {key} {x} is out of range; {fixed} is used"
                ));
                fixed
            }
        }
    };
    let strength = read("anisotropyStrength", (0.0, 1.0));
    let rotation = read("anisotropyRotation", (f32::MIN, f32::MAX));
    (strength > 0.0).then_some(MaterialAnisotropy { strength, rotation })
}

/// Decodes each (image, encoding) pair once; failures are remembered (and warned about) once.
struct TextureLoader<'a> {
    document: &'a gltf::Document,
    buffers: &'a [Vec<u8>],
    base: &'a Path,
    cache: HashMap<(usize, Encoding), Option<TextureId>>,
}

impl TextureLoader<'_> {
    fn get(
        &mut self,
        texture: gltf::Texture,
        tex_coord: u32,
        encoding: Encoding,
        material: &str,
        scene: &mut Scene,
    ) -> Option<TextureId> {
        let image = texture.source();
        let name = image
            .name()
            .map_or_else(|| format!("image {}", image.index()), str::to_string);
        if tex_coord != 0 {
            scene.report.warnings.push(format!(
                "material '{material}': texture '{name}' uses TEXCOORD_{} (only TEXCOORD_0 is read); the factor is used instead",
                tex_coord
            ));
            return None;
        }
        if let Some(&id) = self.cache.get(&(image.index(), encoding)) {
            return id;
        }
        let decoded = self
            .bytes(image.index())
            .and_then(|bytes| decode_texture(&bytes, &name, encoding));
        let id = match decoded {
            Ok(texture) => {
                scene.textures.push(texture);
                Some(scene.textures.len() - 1)
            }
            Err(e) => {
                scene.report.warnings.push(format!(
                    "material '{material}': texture '{name}' cannot be used ({e}); the factor is used instead"
                ));
                None
            }
        };
        self.cache.insert((image.index(), encoding), id);
        id
    }

    /// The encoded bytes of image `index`: a buffer view or a URI. Reads the image's JSON:
    /// the `gltf` crate's `source()` panics on an image with neither, or a view without
    /// `mimeType` (the format is guessed from the bytes here).
    fn bytes(&self, index: usize) -> Result<Vec<u8>, String> {
        let json = self.document.as_json().images.get(index);
        if let Some(view) = json.and_then(|j| j.buffer_view) {
            let view = self.document.views().nth(view.value());
            return view
                .and_then(|v| {
                    let data = self.buffers.get(v.buffer().index())?;
                    data.get(v.offset()..v.offset().checked_add(v.length())?)
                })
                .map(<[u8]>::to_vec)
                .ok_or_else(|| "its buffer view lies outside its buffer".to_string());
        }
        match json.and_then(|j| j.uri.as_deref()) {
            Some(uri) => read_uri(uri, self.base),
            None => Err("the image has neither a uri nor a bufferView".into()),
        }
    }
}
