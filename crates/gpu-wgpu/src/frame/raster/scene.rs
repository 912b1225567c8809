//! The scene on the GPU: every mesh's vertices and triangles flattened into two storage
//! buffers, the materials (`slc_core::Material`, both models, η, two-sidedness, normal maps
//! and alpha masks) and the
//! textures as RGB float triples, exactly what `Material::brdf_at` and `Texture::sample`
//! read on the CPU (`scene.wesl` mirrors them). Triangle t of the flattened order is
//! triangle `t − first` of its mesh, meshes in scene order.
//!
//! Out-of-domain scenes are [`GpuError::Input`]: no triangle, a vertex, normal or texture
//! coordinate or tangent index past its array, a triangle with a non-finite position, a material index past the
//! materials, more triangles than 32-bit triangle ids allow; buffers beyond the
//! storage-binding limit are [`GpuError::BufferTooLarge`].
use crate::device::buffers::upload;
use crate::device::context::{GpuContext, GpuError};
use crate::frame::raster::records::{
    GpuMaterial, GpuTextureInfo, GpuTriangle, GpuVertex, MATERIAL_ALPHA_MASK, MATERIAL_DIELECTRIC,
    MATERIAL_DIRECT, MATERIAL_DOUBLE_SIDED, MATERIAL_METALLIC_ROUGHNESS, NO_TEXTURE,
    TRIANGLE_NORMALS, TRIANGLE_TANGENTS, TRIANGLE_UVS,
};
use glam::Vec3;
use slc_core::{Material, MaterialModel, Mesh, Scene, TextureId};

/// The uploaded scene (see the module documentation).
pub struct GpuScene {
    pub(crate) vertices: wgpu::Buffer,
    pub(crate) triangles: wgpu::Buffer,
    pub(crate) materials: wgpu::Buffer,
    pub(crate) textures: wgpu::Buffer,
    pub(crate) texels: wgpu::Buffer,
    pub triangle_count: u32,
    /// `Scene::bounds` (every vertex used by a triangle).
    pub bounds: (Vec3, Vec3),
    /// The largest absolute coordinate, at least 1 (the scale `Tracer` takes its ray
    /// epsilon from); near planes and shadow biases are relative to it.
    pub extent: f32,
}

impl GpuScene {
    /// Validates and uploads `scene` (see the module documentation).
    pub fn upload(ctx: &GpuContext, scene: &Scene) -> Result<Self, GpuError> {
        let mut vertices = Vec::new();
        let mut triangles = Vec::with_capacity(scene.triangle_count());
        for mesh in &scene.meshes {
            append_mesh(mesh, scene.materials.len(), &mut vertices, &mut triangles)?;
        }
        let triangle_count = u32::try_from(triangles.len())
            .ok()
            .filter(|&n| n.checked_mul(3).is_some())
            .ok_or_else(|| {
                GpuError::Input(format!(
                    "{} triangles exceed the 32-bit triangle ids",
                    triangles.len()
                ))
            })?;
        let Some(bounds) = scene.bounds() else {
            return Err(GpuError::Input(format!(
                "scene '{}' has no triangle",
                scene.name
            )));
        };
        let extent = bounds.0.abs().max(bounds.1.abs()).max_element().max(1.0);
        let materials: Vec<GpuMaterial> = scene
            .materials
            .iter()
            .map(|m| material(m, scene.textures.len()))
            .collect();
        let mut infos = Vec::with_capacity(scene.textures.len());
        let mut texels = Vec::new();
        for t in &scene.textures {
            if t.texels.len() as u64 != u64::from(t.width) * u64::from(t.height) {
                return Err(GpuError::Input(format!(
                    "texture '{}' of {}x{} has {} texels",
                    t.name,
                    t.width,
                    t.height,
                    t.texels.len()
                )));
            }
            let offset = u32::try_from(texels.len())
                .map_err(|_| GpuError::Input("texture texels exceed 32-bit offsets".to_string()))?;
            infos.push(GpuTextureInfo {
                offset,
                width: t.width,
                height: t.height,
                pad: 0,
            });
            texels.extend(t.texels.iter().flat_map(|c| c.to_array()));
        }
        if u32::try_from(texels.len()).is_err() {
            return Err(GpuError::Input(
                "texture texels exceed 32-bit offsets".to_string(),
            ));
        }
        Ok(Self {
            vertices: upload(ctx, "scene vertices", &vertices)?,
            triangles: upload(ctx, "scene triangles", &triangles)?,
            materials: upload(ctx, "scene materials", &materials)?,
            textures: upload(ctx, "scene textures", &infos)?,
            texels: upload(ctx, "scene texels", &texels)?,
            triangle_count,
            bounds,
            extent,
        })
    }

    /// The five scene buffers in the binding order of `scene.wesl` (0 to 4).
    pub(crate) fn bindings(&self) -> [&wgpu::Buffer; 5] {
        [
            &self.vertices,
            &self.triangles,
            &self.materials,
            &self.textures,
            &self.texels,
        ]
    }
}

/// Appends `mesh`'s vertices and its triangles (with global indices) after validating them.
fn append_mesh(
    mesh: &Mesh,
    material_count: usize,
    vertices: &mut Vec<GpuVertex>,
    triangles: &mut Vec<GpuTriangle>,
) -> Result<(), GpuError> {
    let bad = |what: String| Err(GpuError::Input(format!("mesh '{}': {what}", mesh.name)));
    if mesh.material >= material_count {
        return bad(format!("material {} of {material_count}", mesh.material));
    }
    let n = mesh.positions.len();
    let base = u32::try_from(vertices.len() + n)
        .map(|_| vertices.len() as u32)
        .map_err(|_| GpuError::Input("vertices exceed 32-bit indices".to_string()))?;
    let limit = [
        Some(n),
        mesh.normals.as_ref().map(Vec::len),
        mesh.uvs.as_ref().map(Vec::len),
        mesh.tangents.as_ref().map(Vec::len),
    ];
    for (k, t) in mesh.triangles.iter().enumerate() {
        if t.iter()
            .any(|&i| limit.iter().flatten().any(|&len| i as usize >= len))
        {
            return bad(format!("triangle {k} {t:?} indexes past a vertex array"));
        }
        if t.iter().any(|&i| !mesh.positions[i as usize].is_finite()) {
            return bad(format!("triangle {k} has a non-finite vertex position"));
        }
        let flags = mesh.normals.as_ref().map_or(0, |_| TRIANGLE_NORMALS)
            | mesh.uvs.as_ref().map_or(0, |_| TRIANGLE_UVS)
            | mesh.tangents.as_ref().map_or(0, |_| TRIANGLE_TANGENTS);
        triangles.push(GpuTriangle {
            vertices: [base + t[0], base + t[1], base + t[2], mesh.material as u32],
            info: [flags, 0, 0, 0],
        });
    }
    vertices.extend((0..n).map(|i| {
        let p = mesh.positions[i];
        let normal = mesh
            .normals
            .as_ref()
            .and_then(|v| v.get(i).copied())
            .unwrap_or(Vec3::ZERO);
        let uv = mesh
            .uvs
            .as_ref()
            .and_then(|v| v.get(i).copied())
            .unwrap_or_default();
        let tangent = mesh
            .tangents
            .as_ref()
            .and_then(|v| v.get(i).copied())
            .unwrap_or_default();
        GpuVertex {
            position_u: [p.x, p.y, p.z, uv.x],
            normal_v: [normal.x, normal.y, normal.z, uv.y],
            tangent: tangent.to_array(),
        }
    }));
    Ok(())
}

/// A texture id as the shader sees it: [`NO_TEXTURE`] where `brdf_at` would find none.
fn texture_id(id: Option<TextureId>, texture_count: usize) -> u32 {
    id.filter(|&i| i < texture_count)
        .map_or(NO_TEXTURE, |i| i as u32)
}

fn material(m: &Material, texture_count: usize) -> GpuMaterial {
    let mut flags = 0;
    if m.double_sided {
        flags |= MATERIAL_DOUBLE_SIDED;
    }
    if m.eta.is_some() {
        flags |= MATERIAL_DIELECTRIC;
    }
    if m.alpha_mask.is_some() {
        flags |= MATERIAL_ALPHA_MASK;
    }
    let eta = m.eta.unwrap_or(0.0);
    let maps = [
        texture_id(m.normal_map.map(|n| n.texture), texture_count),
        texture_id(m.alpha_mask.and_then(|a| a.texture), texture_count),
        0,
        0,
    ];
    let map_params = [
        m.normal_map.map_or(1.0, |n| n.scale),
        m.alpha_mask.map_or(0.0, |a| a.cutoff),
        m.alpha_mask.map_or(1.0, |a| a.factor),
        0.0,
    ];
    let anisotropy = m.anisotropy.map_or([0.0; 4], |a| {
        let (sin, cos) = a.rotation.sin_cos();
        [a.strength.clamp(0.0, 1.0), cos, sin, 0.0]
    });
    match m.model {
        MaterialModel::Direct {
            kd,
            kd_texture,
            f0,
            alpha,
        } => GpuMaterial {
            color: kd.extend(0.0).to_array(),
            f0_alpha: f0.extend(alpha).to_array(),
            params: [0.0, 0.0, eta, 0.0],
            info: [
                MATERIAL_DIRECT,
                texture_id(kd_texture, texture_count),
                NO_TEXTURE,
                flags,
            ],
            maps,
            map_params,
            anisotropy,
        },
        MaterialModel::MetallicRoughness {
            base_color,
            base_color_texture,
            metallic,
            roughness,
            metallic_roughness_texture,
        } => GpuMaterial {
            color: base_color.extend(0.0).to_array(),
            f0_alpha: [0.0; 4],
            params: [metallic, roughness, eta, 0.0],
            info: [
                MATERIAL_METALLIC_ROUGHNESS,
                texture_id(base_color_texture, texture_count),
                texture_id(metallic_roughness_texture, texture_count),
                flags,
            ],
            maps,
            map_params,
            anisotropy,
        },
    }
}
