//! Meshes made in code: flat-shaded parallelograms and boxes whose front faces are
//! counter-clockwise seen from the side their normal points to.
use crate::mesh::Mesh;
use glam::Vec3;

/// The parallelogram `p0 + s eu + t ev`, (s, t) in [0, 1]², as two triangles (p0, p1, p2),
/// (p0, p2, p3) with p1 = p0 + eu, p2 = p0 + eu + ev, p3 = p0 + ev (the convention of
/// `shared/reference/cornell-a`). Its normal, stored per vertex, is normalize(eu × ev).
pub fn quad(name: &str, p0: Vec3, eu: Vec3, ev: Vec3, material: usize) -> Mesh {
    let mut mesh = Mesh {
        name: name.to_string(),
        normals: Some(Vec::new()),
        material,
        ..Mesh::default()
    };
    push_quad(&mut mesh, p0, eu, ev);
    mesh
}

/// A box (parallelepiped) with centre `centre` and half-axes `axes`: 6 faces of 2 triangles,
/// each face with its own 4 vertices and flat normals pointing outward (for either
/// handedness of `axes`).
pub fn cuboid(name: &str, centre: Vec3, axes: [Vec3; 3], material: usize) -> Mesh {
    let [a, b, c] = axes;
    // Make the axes right-handed so that the faces below face outward.
    let axes = if a.cross(b).dot(c) < 0.0 {
        [a, b, -c]
    } else {
        axes
    };
    let mut mesh = Mesh {
        name: name.to_string(),
        normals: Some(Vec::new()),
        material,
        ..Mesh::default()
    };
    for i in 0..3 {
        let (ai, aj, ak) = (axes[i], axes[(i + 1) % 3], axes[(i + 2) % 3]);
        // aj × ak points along +ai, ak × aj along -ai.
        push_quad(&mut mesh, centre + ai - aj - ak, 2.0 * aj, 2.0 * ak);
        push_quad(&mut mesh, centre - ai - aj - ak, 2.0 * ak, 2.0 * aj);
    }
    mesh
}

/// Appends a parallelogram with its own four vertices to `mesh` (whose normals are `Some`).
fn push_quad(mesh: &mut Mesh, p0: Vec3, eu: Vec3, ev: Vec3) {
    let first = mesh.positions.len() as u32;
    let normal = eu.cross(ev).normalize_or_zero();
    mesh.positions.extend([p0, p0 + eu, p0 + eu + ev, p0 + ev]);
    if let Some(normals) = &mut mesh.normals {
        normals.extend([normal; 4]);
    }
    mesh.triangles
        .extend([[first, first + 1, first + 2], [first, first + 2, first + 3]]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// normalize((v1 - v0) × (v2 - v0)) of every triangle with its centroid.
    fn faces(m: &Mesh) -> Vec<(Vec3, Vec3)> {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                ((b - a).cross(c - a).normalize(), (a + b + c) / 3.0)
            })
            .collect()
    }

    #[test]
    fn quad_is_counter_clockwise_around_its_normal() {
        let q = quad("q", Vec3::ZERO, Vec3::X, Vec3::NEG_Z, 0);
        assert_eq!(q.triangles.len(), 2);
        for (n, _) in faces(&q) {
            assert!((n - Vec3::Y).length() < 1e-6);
        }
        assert!(q.normals.unwrap().iter().all(|&n| n == Vec3::Y));
    }

    #[test]
    fn cuboid_faces_point_outward_for_either_handedness() {
        let r = glam::Quat::from_rotation_y(0.3);
        let axes = [r * Vec3::X * 0.3, r * Vec3::Y * 0.6, r * Vec3::Z * 0.2];
        for axes in [axes, [axes[1], axes[0], axes[2]]] {
            let centre = Vec3::new(0.5, 1.0, -0.2);
            let b = cuboid("b", centre, axes, 0);
            assert_eq!((b.triangles.len(), b.positions.len()), (12, 24));
            for ((n, centroid), stored) in faces(&b).into_iter().zip(
                b.triangles
                    .iter()
                    .map(|t| b.normals.as_ref().unwrap()[t[0] as usize]),
            ) {
                assert!(n.dot(centroid - centre) > 0.0);
                assert!((n - stored).length() < 1e-5);
            }
        }
    }
}
