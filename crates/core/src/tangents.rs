//! MikkTSpace tangents for meshes without them. The glTF 2.0 specification (section 3.7.2.1):
//! "When tangents are not specified, client implementations SHOULD calculate tangents using
//! default MikkTSpace algorithms with the specified vertex positions, normals, and texture
//! coordinates associated with the normal texture."
//!
//! glTF's texture coordinates grow downwards in the image while its normal maps store +Y up,
//! so the bitangent of a glTF tangent frame points towards *decreasing* v. MikkTSpace's
//! bitangent follows increasing v: its handedness is negated here (three.js does the same
//! for glTF, `computeMikkTSpaceTangents(..., negateSign = true)`).
use crate::mesh::Mesh;
use bevy_mikktspace::{generate_tangents as mikktspace, Geometry, TangentSpace};
use glam::{Vec3, Vec4};
use std::collections::HashMap;

/// Why tangents could not be generated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TangentError {
    #[error("the mesh has no texture coordinates")]
    NoTextureCoordinates,
    #[error("a triangle refers to a vertex past the end of the vertex arrays")]
    IndexOutOfRange,
}

/// Gives `mesh` per-vertex MikkTSpace tangents in glTF's convention (see the module
/// documentation), splitting vertices whose triangles need different tangents (at UV seams
/// and mirrored islands). Vertices without a normal use their triangle's face normal; corners
/// MikkTSpace leaves without a tangent (degenerate texture mapping) get any unit vector
/// orthogonal to their normal. Triangles keep their order.
pub fn generate_tangents(mesh: &mut Mesh) -> Result<(), TangentError> {
    let uvs = mesh
        .uvs
        .as_ref()
        .ok_or(TangentError::NoTextureCoordinates)?;
    let n = mesh.positions.len();
    let in_range = |len: usize| mesh.triangles.iter().flatten().all(|&i| (i as usize) < len);
    if !in_range(n)
        || !in_range(uvs.len())
        || mesh.normals.as_ref().is_some_and(|v| !in_range(v.len()))
    {
        return Err(TangentError::IndexOutOfRange);
    }
    let mut corners = Corners {
        mesh: &*mesh,
        tangents: vec![None; mesh.triangles.len() * 3],
    };
    // bevy_mikktspace's error type has no variants: generation cannot fail.
    let _ = mikktspace(&mut corners);
    let tangents = corners.tangents;
    split_by_tangent(mesh, &tangents);
    Ok(())
}

/// The mesh as MikkTSpace sees it, and the tangent it returns per triangle corner.
struct Corners<'a> {
    mesh: &'a Mesh,
    tangents: Vec<Option<TangentSpace>>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.triangles[face][vert] as usize
    }
}

impl Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        match &self.mesh.normals {
            Some(normals) => normals[self.vertex(face, vert)].to_array(),
            None => face_normal(self.mesh, face).to_array(),
        }
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let uvs = self
            .mesh
            .uvs
            .as_ref()
            .expect("checked by generate_tangents");
        uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(&mut self, tangent: Option<TangentSpace>, face: usize, vert: usize) {
        self.tangents[face * 3 + vert] = tangent;
    }
}

/// The unit normal of triangle `face` by its winding (zero for a degenerate one).
fn face_normal(mesh: &Mesh, face: usize) -> Vec3 {
    let [a, b, c] = mesh.triangles[face].map(|i| mesh.positions[i as usize]);
    (b - a).cross(c - a).normalize_or_zero()
}

/// Stores one tangent per vertex, duplicating a vertex for each further distinct tangent its
/// triangle corners were given.
fn split_by_tangent(mesh: &mut Mesh, corners: &[Option<TangentSpace>]) {
    let mut tangents = vec![None; mesh.positions.len()];
    let mut copies: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    for (corner, t) in corners.iter().enumerate() {
        let (face, vert) = (corner / 3, corner % 3);
        let v = mesh.triangles[face][vert];
        let normal = match &mesh.normals {
            Some(normals) => normals[v as usize],
            None => face_normal(mesh, face),
        };
        let tangent = gltf_tangent(*t, normal);
        let key = (v, tangent.to_array().map(f32::to_bits));
        let index = *copies
            .entry(key)
            .or_insert_with(|| match tangents[v as usize] {
                None => {
                    tangents[v as usize] = Some(tangent);
                    v
                }
                Some(_) => {
                    let copy = mesh.positions.len() as u32;
                    mesh.positions.push(mesh.positions[v as usize]);
                    if let Some(n) = &mut mesh.normals {
                        n.push(n[v as usize]);
                    }
                    if let Some(uv) = &mut mesh.uvs {
                        uv.push(uv[v as usize]);
                    }
                    tangents.push(Some(tangent));
                    copy
                }
            });
        mesh.triangles[face][vert] = index;
    }
    let fallback = Vec4::new(1.0, 0.0, 0.0, 1.0);
    mesh.tangents = Some(
        tangents
            .into_iter()
            .map(|t| t.unwrap_or(fallback))
            .collect(),
    );
}

/// A MikkTSpace result in glTF's convention: handedness negated (module documentation); a
/// unit vector orthogonal to `normal` where MikkTSpace gave none.
fn gltf_tangent(t: Option<TangentSpace>, normal: Vec3) -> Vec4 {
    match t {
        Some(t) => {
            let [x, y, z, w] = t.tangent_encoded();
            Vec4::new(x, y, z, -w)
        }
        None => normal.any_orthonormal_vector().extend(1.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// The floor quad of `scenes/materials`: y = 0, normal +y, u = 2 (x + 1), v = 2 (z + 1).
    fn floor() -> Mesh {
        let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        Mesh {
            positions: p.iter().map(|&(x, z)| Vec3::new(x, 0.0, z)).collect(),
            normals: Some(vec![Vec3::Y; 4]),
            uvs: Some(
                p.iter()
                    .map(|&(x, z)| Vec2::new(2.0 * (x + 1.0), 2.0 * (z + 1.0)))
                    .collect(),
            ),
            triangles: vec![[0, 2, 1], [0, 3, 2]],
            ..Default::default()
        }
    }

    #[test]
    fn gltf_frame_of_a_plane() {
        let mut m = floor();
        generate_tangents(&mut m).unwrap();
        let t = m.tangents.as_ref().unwrap();
        assert_eq!(t.len(), 4, "no vertex needs splitting");
        for t in t {
            // T = dp/du = +x; the bitangent w (N x T) = w (y x x) = -w z must point towards
            // decreasing v (-z): w = +1.
            assert!((t.truncate() - Vec3::X).length() < 1e-6, "{t}");
            assert_eq!(t.w, 1.0);
        }
    }

    #[test]
    fn mirrored_uvs_flip_the_handedness_and_split_shared_vertices() {
        // Two triangles sharing an edge, the second with u mirrored: different tangents at
        // the shared vertices, which are duplicated.
        let mut m = Mesh {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::new(1.0, 0.0, -1.0),
                Vec3::new(2.0, 0.0, 0.0),
            ],
            normals: Some(vec![Vec3::Y; 4]),
            uvs: Some(vec![
                Vec2::new(0.0, 1.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(0.0, 1.0),
            ]),
            triangles: vec![[0, 1, 2], [1, 3, 2]],
            ..Default::default()
        };
        generate_tangents(&mut m).unwrap();
        let t = m.tangents.as_ref().unwrap();
        assert_eq!(m.positions.len(), 6);
        assert_eq!(m.uvs.as_ref().unwrap().len(), 6);
        let first: Vec<Vec4> = m.triangles[0].iter().map(|&i| t[i as usize]).collect();
        let second: Vec<Vec4> = m.triangles[1].iter().map(|&i| t[i as usize]).collect();
        assert!(first.iter().all(|t| t.x > 0.99 && t.w == 1.0), "{first:?}");
        assert!(
            second.iter().all(|t| t.x < -0.99 && t.w == -1.0),
            "{second:?}"
        );
        // The geometry is unchanged.
        for (tri, expected) in m.triangles.iter().zip([[0usize, 1, 2], [1, 3, 2]]) {
            for (&i, e) in tri.iter().zip(expected) {
                assert_eq!(
                    m.positions[i as usize],
                    [
                        Vec3::ZERO,
                        Vec3::X,
                        Vec3::new(1.0, 0.0, -1.0),
                        Vec3::new(2.0, 0.0, 0.0)
                    ][e]
                );
            }
        }
    }

    #[test]
    fn degenerate_uvs_get_an_orthogonal_tangent_and_errors_are_typed() {
        let mut m = floor();
        m.uvs = Some(vec![Vec2::ZERO; 4]);
        generate_tangents(&mut m).unwrap();
        for (t, n) in m
            .tangents
            .as_ref()
            .unwrap()
            .iter()
            .zip(m.normals.as_ref().unwrap())
        {
            assert!(
                t.truncate().dot(*n).abs() < 1e-6 && (t.truncate().length() - 1.0).abs() < 1e-6
            );
        }
        let mut m = floor();
        m.uvs = None;
        assert_eq!(
            generate_tangents(&mut m),
            Err(TangentError::NoTextureCoordinates)
        );
        let mut m = floor();
        m.triangles.push([0, 1, 7]);
        assert_eq!(
            generate_tangents(&mut m),
            Err(TangentError::IndexOutOfRange)
        );
    }
}
