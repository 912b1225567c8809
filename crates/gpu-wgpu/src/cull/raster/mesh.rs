//! The bounding meshes the raster baselines draw around each VPL's bound (the paper's
//! Table 2): an icosahedron (20 triangles, \[OP16\]'s light shape) or its first subdivision
//! (80 triangles, the splatted ellipsoid of \[DS06\]), scaled so that it contains the unit
//! sphere: every face plane lies at distance ≥ 1 from the centre, with a small margin for the
//! rasterizer's sub-pixel snapping. `bound_mesh.wesl` maps the unit sphere onto a
//! VPL's spheroid or sphere, so the mapped mesh contains the bound (an affine map keeps
//! containment).
use crate::device::buffers::upload;
use crate::device::context::{GpuContext, GpuError};
use glam::Vec3;

/// Relative growth beyond the exact circumscribing scale: covers f32 rounding of the
/// vertex transform and the rasterizer's snapping of vertices to sub-pixels.
const MARGIN: f32 = 1e-3;

/// The mesh's triangles (non-indexed, counter-clockwise seen from outside), 3 vertices per
/// triangle, scaled to contain the unit sphere.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundMesh {
    pub vertices: Vec<Vec3>,
}

impl BoundMesh {
    /// The icosahedron subdivided `levels` times (20 × 4^levels triangles), vertices pushed
    /// to the unit sphere, then scaled out to circumscribe it.
    pub fn icosphere(levels: u32) -> Self {
        let t = (1.0 + 5f32.sqrt()) / 2.0;
        let corners = [
            (-1.0, t, 0.0),
            (1.0, t, 0.0),
            (-1.0, -t, 0.0),
            (1.0, -t, 0.0),
            (0.0, -1.0, t),
            (0.0, 1.0, t),
            (0.0, -1.0, -t),
            (0.0, 1.0, -t),
            (t, 0.0, -1.0),
            (t, 0.0, 1.0),
            (-t, 0.0, -1.0),
            (-t, 0.0, 1.0),
        ]
        .map(|(x, y, z)| Vec3::new(x, y, z).normalize());
        const FACES: [[usize; 3]; 20] = [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        let mut triangles: Vec<[Vec3; 3]> = FACES
            .iter()
            .map(|f| f.map(|i| corners[i]))
            .map(outward)
            .collect();
        for _ in 0..levels {
            triangles = triangles
                .into_iter()
                .flat_map(|[a, b, c]| {
                    let (ab, bc, ca) = (
                        (a + b).normalize(),
                        (b + c).normalize(),
                        (c + a).normalize(),
                    );
                    [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
                })
                .collect();
        }
        let inradius = triangles
            .iter()
            .map(|&[a, b, c]| (b - a).cross(c - a).normalize().dot(a))
            .fold(f32::INFINITY, f32::min);
        let scale = (1.0 + MARGIN) / inradius;
        Self {
            vertices: triangles.iter().flatten().map(|&v| v * scale).collect(),
        }
    }

    pub fn triangle_count(&self) -> u32 {
        self.vertices.len() as u32 / 3
    }

    /// The vertices as `[x, y, z, 0]` in a storage buffer.
    pub fn upload(&self, ctx: &GpuContext) -> Result<wgpu::Buffer, GpuError> {
        let data: Vec<[f32; 4]> = self.vertices.iter().map(|v| v.extend(0.0).into()).collect();
        upload(ctx, "bound mesh", &data)
    }
}

/// The triangle wound counter-clockwise seen from outside (its normal points away from the
/// centre).
fn outward([a, b, c]: [Vec3; 3]) -> [Vec3; 3] {
    if (b - a).cross(c - a).dot(a + b + c) < 0.0 {
        [a, c, b]
    } else {
        [a, b, c]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face plane at distance ≥ 1 (so the unit sphere is inside), none far beyond, and
    /// the faces wound outward: the mesh circumscribes the sphere as the culling needs.
    #[test]
    fn meshes_circumscribe_the_unit_sphere() {
        for (levels, faces) in [(0, 20), (1, 80)] {
            let mesh = BoundMesh::icosphere(levels);
            assert_eq!(mesh.triangle_count(), faces);
            let distances: Vec<f32> = mesh
                .vertices
                .chunks(3)
                .map(|t| {
                    let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
                    n.dot(t[0])
                })
                .collect();
            let min = distances.iter().copied().fold(f32::INFINITY, f32::min);
            let max = distances.iter().copied().fold(0.0, f32::max);
            assert!(min >= 1.0 + 0.5 * MARGIN, "level {levels}: {min}");
            assert!(max < 1.1, "level {levels}: {max}");
            // Dense sampling of the sphere: every direction is inside every face plane.
            for i in 0..2000 {
                let z = 1.0 - 2.0 * (i as f32 + 0.5) / 2000.0;
                let phi = i as f32 * 2.399_963;
                let r = (1.0 - z * z).sqrt();
                let p = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                for t in mesh.vertices.chunks(3) {
                    let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
                    assert!(n.dot(p - t[0]) < 0.0, "{p} outside a face");
                }
            }
        }
    }
}
