//! One glTF triangle primitive -> one world-space [`Mesh`], its accessors read by
//! [`crate::gltf_accessor`].
use crate::gltf_accessor::{read_floats, read_indices};
use crate::mesh::Mesh;
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
use gltf::accessor::DataType;
use gltf::Semantic;

/// Component types read for POSITION, NORMAL, TANGENT and TEXCOORD_0: floats, and the integer types of
/// `KHR_mesh_quantization` (normalized where the accessor says so).
const ATTRIBUTE_TYPES: [DataType; 5] = [
    DataType::F32,
    DataType::I8,
    DataType::U8,
    DataType::I16,
    DataType::U16,
];

/// Reads a triangle primitive placed by `world`. Positions go through `world`, normals through
/// its inverse transpose (renormalized later by the loader), tangents through its linear part
/// (renormalized), and the winding and the tangents' handedness are flipped where `world`
/// mirrors. Non-fatal problems are pushed to `warnings`; malformed accessors are errors.
pub(crate) fn primitive_mesh(
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    world: Mat4,
    name: String,
    material: usize,
    warnings: &mut Vec<String>,
) -> Result<Mesh, String> {
    let at =
        |what: &str, acc: &gltf::Accessor| format!("{name}: {what} (accessor {})", acc.index());
    let position = primitive
        .get(&Semantic::Positions)
        .ok_or_else(|| format!("{name}: no POSITION attribute"))?;
    let positions: Vec<Vec3> = read_floats::<3>(
        &position,
        buffers,
        &at("POSITION", &position),
        &ATTRIBUTE_TYPES,
    )?
    .into_iter()
    .map(|p| world.transform_point3(p.into()))
    .collect();

    let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
    let normals = match primitive.get(&Semantic::Normals) {
        Some(acc) => Some(
            read_floats::<3>(&acc, buffers, &at("NORMAL", &acc), &ATTRIBUTE_TYPES)?
                .into_iter()
                .map(|n| normal_matrix * Vec3::from(n))
                .collect(),
        ),
        None => None,
    };

    let linear = Mat3::from_mat4(world);
    let mirrored = linear.determinant() < 0.0;
    let tangents = match primitive.get(&Semantic::Tangents) {
        Some(acc) => Some(
            read_floats::<4>(&acc, buffers, &at("TANGENT", &acc), &ATTRIBUTE_TYPES)?
                .into_iter()
                .map(|[x, y, z, w]| {
                    let t = (linear * Vec3::new(x, y, z)).normalize_or_zero();
                    let w = if (w < 0.0) != mirrored { -1.0 } else { 1.0 };
                    t.extend(w)
                })
                .collect::<Vec<Vec4>>(),
        ),
        None => None,
    };

    let uvs = match primitive.get(&Semantic::TexCoords(0)) {
        Some(acc) => Some(
            read_floats::<2>(&acc, buffers, &at("TEXCOORD_0", &acc), &ATTRIBUTE_TYPES)?
                .into_iter()
                .map(Vec2::from)
                .collect(),
        ),
        None => None,
    };

    let indices: Vec<u32> = match primitive.indices() {
        Some(acc) => read_indices(&acc, buffers, &at("indices", &acc))?,
        None => (0..u32::try_from(positions.len())
            .map_err(|_| format!("{name}: too many vertices"))?)
            .collect(),
    };
    let leftover = indices.len() % 3;
    if leftover > 0 {
        warnings.push(format!(
            "{name}: {} indices is not a multiple of 3; the last {leftover} are ignored",
            indices.len()
        ));
    }
    let triangles = indices
        .chunks_exact(3)
        .map(|t| {
            if mirrored {
                [t[0], t[2], t[1]]
            } else {
                [t[0], t[1], t[2]]
            }
        })
        .collect();
    Ok(Mesh {
        name,
        positions,
        normals,
        uvs,
        tangents,
        triangles,
        material,
    })
}
