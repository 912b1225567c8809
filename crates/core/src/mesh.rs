//! Triangle meshes.
use glam::{Vec2, Vec3, Vec4};

/// An indexed triangle mesh in world space with one material.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals; the face normal is used where absent.
    pub normals: Option<Vec<Vec3>>,
    pub uvs: Option<Vec<Vec2>>,
    /// Per-vertex tangents for normal maps (glTF `TANGENT`): xyz the unit direction of
    /// increasing u, w = ±1 the handedness, the bitangent being `w (normal x tangent)`.
    /// Loaders generate MikkTSpace ones ([`crate::tangents`]) where a normal-mapped mesh has none.
    pub tangents: Option<Vec<Vec4>>,
    pub triangles: Vec<[u32; 3]>,
    /// Index into `Scene::materials`.
    pub material: usize,
}

/// Why a triangle was left out of a mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TriangleDefect {
    /// A vertex index past the end of the vertex arrays.
    IndexOutOfRange,
    /// A position (or normal) that is NaN or infinite.
    NonFinite,
    /// A position coordinate beyond ±[`MAX_COORDINATE`].
    OutOfRange,
    /// Zero area (collinear or repeated vertices).
    Degenerate,
}

/// The largest position coordinate a triangle may have: 1e18. The renderer squares
/// distances and forms cross products of edges in `f32` (largest 3.4e38); beyond 1e18 those
/// overflow (an edge of 2e19 has an infinite squared length).
pub const MAX_COORDINATE: f32 = 1e18;

impl Mesh {
    /// The defect of a triangle, if any.
    pub fn triangle_defect(&self, tri: [u32; 3]) -> Option<TriangleDefect> {
        let n = self.positions.len();
        if tri.iter().any(|&i| i as usize >= n)
            || self
                .normals
                .as_ref()
                .is_some_and(|v| tri.iter().any(|&i| i as usize >= v.len()))
            || self
                .uvs
                .as_ref()
                .is_some_and(|v| tri.iter().any(|&i| i as usize >= v.len()))
            || self
                .tangents
                .as_ref()
                .is_some_and(|v| tri.iter().any(|&i| i as usize >= v.len()))
        {
            return Some(TriangleDefect::IndexOutOfRange);
        }
        let [a, b, c] = tri.map(|i| self.positions[i as usize]);
        if !(a.is_finite() && b.is_finite() && c.is_finite())
            || self
                .normals
                .as_ref()
                .is_some_and(|v| tri.iter().any(|&i| !v[i as usize].is_finite()))
        {
            return Some(TriangleDefect::NonFinite);
        }
        if [a, b, c]
            .iter()
            .any(|p| p.abs().max_element() > MAX_COORDINATE)
        {
            return Some(TriangleDefect::OutOfRange);
        }
        // In f64: the check itself must not overflow (f32 edges of 1e18 square to 1e36).
        let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
        let area2 = (b - a).cross(c - a).length();
        let scale = (b - a)
            .length_squared()
            .max((c - a).length_squared())
            .max(f64::from(f32::MIN_POSITIVE));
        (area2 <= 1e-12 * scale || area2 < f64::from(f32::MIN_POSITIVE))
            .then_some(TriangleDefect::Degenerate)
    }

    /// Removes defective triangles and returns how many of each kind were removed.
    pub fn remove_defective_triangles(&mut self) -> DefectCounts {
        let mut counts = DefectCounts::default();
        let tris = std::mem::take(&mut self.triangles);
        self.triangles = tris
            .into_iter()
            .filter(|&t| match self.triangle_defect(t) {
                None => true,
                Some(d) => {
                    counts.add(d);
                    false
                }
            })
            .collect();
        counts
    }
}

/// Triangles skipped on load, by defect.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DefectCounts {
    pub index_out_of_range: usize,
    pub non_finite: usize,
    pub out_of_range: usize,
    pub degenerate: usize,
}

impl DefectCounts {
    pub fn add(&mut self, d: TriangleDefect) {
        match d {
            TriangleDefect::IndexOutOfRange => self.index_out_of_range += 1,
            TriangleDefect::NonFinite => self.non_finite += 1,
            TriangleDefect::OutOfRange => self.out_of_range += 1,
            TriangleDefect::Degenerate => self.degenerate += 1,
        }
    }

    pub fn merge(&mut self, o: DefectCounts) {
        self.index_out_of_range += o.index_out_of_range;
        self.non_finite += o.non_finite;
        self.out_of_range += o.out_of_range;
        self.degenerate += o.degenerate;
    }

    pub fn total(&self) -> usize {
        self.index_out_of_range + self.non_finite + self.out_of_range + self.degenerate
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defects_are_found_and_counted() {
        let mut m = Mesh {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::NAN,
                Vec3::new(3e38, 0.0, 0.0),
                Vec3::new(1e18, 0.0, 0.0),
                Vec3::new(1e18, 1e18, 0.0),
            ],
            triangles: vec![
                [0, 1, 2],
                [0, 1, 3],
                [0, 1, 4],
                [0, 1, 9],
                [0, 5, 2],
                [0, 6, 7],
            ],
            ..Default::default()
        };
        let c = m.remove_defective_triangles();
        // Coordinates of 1e18 are fine (not "zero area"); 3e38 is out of range.
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 6, 7]]);
        assert_eq!(
            c,
            DefectCounts {
                index_out_of_range: 1,
                non_finite: 1,
                out_of_range: 1,
                degenerate: 1
            }
        );
    }
}
