//! Helpers shared by the file loaders: mesh clean-up and material warnings.
use crate::material::ALPHA_MIN;
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::tangents::generate_tangents;

/// Cleans `mesh` and adds it to `scene` unless nothing is left of it.
///
/// - Shading normals are dropped (the face normal is used, with a warning) when their count
///   differs from the vertex count, or when a vertex with a finite position has a zero or
///   non-finite normal; otherwise they are renormalized.
/// - Texture coordinates and tangents are dropped (with a warning) when their count differs.
/// - Defective triangles are removed and counted in `scene.report.skipped`.
/// - A mesh whose material has a normal map or an anisotropy and that has no tangents gets
///   MikkTSpace ones ([`generate_tangents`]); without texture coordinates neither can apply
///   (a warning).
pub(crate) fn add_mesh(scene: &mut Scene, mut mesh: Mesh) {
    if let Some(normals) = &mut mesh.normals {
        let bad = normals.len() != mesh.positions.len()
            || normals
                .iter()
                .zip(&mesh.positions)
                .any(|(n, p)| p.is_finite() && !(n.is_finite() && n.length_squared() > 0.0));
        if bad {
            scene.report.warnings.push(format!(
                "mesh '{}': vertex normals missing, zero or non-finite for some vertices; face normals are used",
                mesh.name
            ));
            mesh.normals = None;
        } else {
            normals.iter_mut().for_each(|n| *n = n.normalize_or_zero());
        }
    }
    if mesh
        .uvs
        .as_ref()
        .is_some_and(|uv| uv.len() != mesh.positions.len())
    {
        scene.report.warnings.push(format!(
            "mesh '{}': texture coordinates missing for some vertices; textures are not applied",
            mesh.name
        ));
        mesh.uvs = None;
    }
    if mesh
        .tangents
        .as_ref()
        .is_some_and(|t| t.len() != mesh.positions.len() || t.iter().any(|t| !t.is_finite()))
    {
        scene.report.warnings.push(format!(
            "mesh '{}': tangents missing or non-finite for some vertices; they are dropped (and generated where a normal map or an anisotropy needs them)",
            mesh.name
        ));
        mesh.tangents = None;
    }
    let skipped = mesh.remove_defective_triangles();
    if skipped.total() > 0 {
        scene.report.skipped.merge(skipped);
    }
    let needs_tangents = scene
        .materials
        .get(mesh.material)
        .is_some_and(|m| m.normal_map.is_some() || m.anisotropy.is_some());
    if needs_tangents && mesh.tangents.is_none() {
        if let Err(e) = generate_tangents(&mut mesh) {
            scene.report.warnings.push(format!(
                "mesh '{}': its normal map or anisotropy is not applied ({e})",
                mesh.name
            ));
        }
    }
    if !mesh.triangles.is_empty() {
        scene.meshes.push(mesh);
    }
}

/// The warning for a material whose GGX α is below [`ALPHA_MIN`] (it is clamped when used).
pub(crate) fn small_alpha_warning(material: &str, alpha: f32) -> Option<String> {
    (alpha < ALPHA_MIN).then(|| {
        format!("material '{material}': GGX alpha {alpha:e} is below the smallest supported {ALPHA_MIN:e}; it is clamped")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    fn tri(normals: Option<Vec<Vec3>>, uvs: Option<Vec<Vec2>>) -> Mesh {
        Mesh {
            name: "m".into(),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Y],
            normals,
            uvs,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..Default::default()
        }
    }

    #[test]
    fn normals_are_renormalized_or_dropped() {
        let mut scene = Scene::default();
        add_mesh(&mut scene, tri(Some(vec![Vec3::Z * 2.0; 4]), None));
        assert_eq!(scene.meshes[0].normals.as_ref().unwrap()[0], Vec3::Z);
        assert_eq!(scene.meshes[0].triangles.len(), 1);
        assert_eq!(scene.report.skipped.degenerate, 1);
        assert!(scene.report.warnings.is_empty());
        let zero = vec![Vec3::Z, Vec3::ZERO, Vec3::Z, Vec3::Z];
        add_mesh(&mut scene, tri(Some(zero), Some(vec![Vec2::ZERO; 3])));
        assert!(scene.meshes[1].normals.is_none() && scene.meshes[1].uvs.is_none());
        assert_eq!(scene.report.warnings.len(), 2);
    }

    #[test]
    fn empty_meshes_are_dropped() {
        let mut scene = Scene::default();
        let mut m = tri(None, None);
        m.triangles = vec![[0, 2, 3]];
        add_mesh(&mut scene, m);
        assert!(scene.meshes.is_empty());
        assert_eq!(scene.report.skipped.total(), 1);
    }

    #[test]
    fn alpha_warning() {
        assert!(small_alpha_warning("m", 1e-4).is_some());
        assert!(small_alpha_warning("m", ALPHA_MIN).is_none());
    }
}
