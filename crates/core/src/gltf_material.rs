//! glTF materials -> [`Material`]s with [`MaterialModel::MetallicRoughness`], and their textures.
//!
//! Base colour factor (RGB; alpha ignored), metallic and roughness factors are kept as given,
//! `doubleSided` maps to [`Material::double_sided`]. Base-colour textures are decoded from sRGB,
//! metallic-roughness textures are linear; both must use `TEXCOORD_0`. A texture that cannot
//! be read or decoded gives a warning and the factor alone is used. `KHR_materials_ior` sets
//! [`Material::eta`] for non-metallic materials (metallic factor 0) when `ior` >= 1; a metal's
//! Fresnel reflectance is its base colour, so `eta` stays `None` there (and without the
//! extension: Schlick with F0 = 0.04, the glTF default `ior` 1.5). Emission and alpha modes are
//! ignored with a warning.
use crate::gltf_loader::read_uri;
use crate::import_util::small_alpha_warning;
use crate::material::{Material, MaterialModel};
use crate::scene::Scene;
use crate::texture::TextureId;
use crate::texture_decode::{decode_texture, Encoding};
use glam::Vec3;
use std::collections::HashMap;
use std::path::Path;

/// The glTF default material (spec: base colour 1, metallic 1, roughness 1), for primitives
/// without a material.
pub(crate) fn default_material() -> Material {
    Material {
        name: "glTF default material".into(),
        model: MaterialModel::MetallicRoughness {
            base_color: Vec3::ONE,
            base_color_texture: None,
            metallic: 1.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
        },
        eta: None,
        double_sided: false,
    }
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
        let [r, g, b, _] = pbr.base_color_factor();
        let base_color_texture = pbr
            .base_color_texture()
            .and_then(|t| textures.get(&t, Encoding::Srgb, &name, scene));
        let metallic_roughness_texture = pbr
            .metallic_roughness_texture()
            .and_then(|t| textures.get(&t, Encoding::Linear, &name, scene));
        let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
        let warnings = &mut scene.report.warnings;
        warnings.extend(small_alpha_warning(
            &name,
            roughness.clamp(0.0, 1.0).powi(2),
        ));
        if Vec3::from(m.emissive_factor()).max_element() > 0.0 {
            warnings.push(format!(
                "material '{name}': emission is ignored (only punctual lights emit)"
            ));
        }
        if m.alpha_mode() != gltf::material::AlphaMode::Opaque {
            warnings.push(format!(
                "material '{name}': alpha mode {:?} is ignored (treated as opaque)",
                m.alpha_mode()
            ));
        }
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
                .filter(|&ior| metallic == 0.0 && ior.is_finite() && ior >= 1.0),
            double_sided: m.double_sided(),
        });
    }
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
        info: &gltf::texture::Info,
        encoding: Encoding,
        material: &str,
        scene: &mut Scene,
    ) -> Option<TextureId> {
        let image = info.texture().source();
        let name = image
            .name()
            .map_or_else(|| format!("image {}", image.index()), str::to_string);
        if info.tex_coord() != 0 {
            scene.report.warnings.push(format!(
                "material '{material}': texture '{name}' uses TEXCOORD_{} (only TEXCOORD_0 is read); the factor is used instead",
                info.tex_coord()
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
