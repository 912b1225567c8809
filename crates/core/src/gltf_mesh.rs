//! One glTF triangle primitive -> one world-space [`Mesh`], with every accessor checked first
//! (the `gltf` crate's readers assume well-formed accessors).
use crate::mesh::Mesh;
use glam::{Mat3, Mat4, Vec2, Vec3};
use gltf::accessor::{Accessor, DataType, Dimensions};
use gltf::Semantic;

/// Reads a triangle primitive placed by `world`. Positions go through `world`, normals through
/// its inverse transpose (renormalized later by the loader), and the winding is flipped where
/// `world` mirrors. Non-fatal problems are pushed to `warnings`; malformed accessors are errors.
pub(crate) fn primitive_mesh(
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    world: Mat4,
    name: String,
    material: usize,
    warnings: &mut Vec<String>,
) -> Result<Mesh, String> {
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    let unreadable = |what: &str| format!("{name}: {what} cannot be read");

    let position = primitive
        .get(&Semantic::Positions)
        .ok_or_else(|| format!("{name}: no POSITION attribute"))?;
    check(
        &position,
        &name,
        "POSITION",
        &[DataType::F32],
        Dimensions::Vec3,
        buffers,
    )?;
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| unreadable("POSITION"))?
        .map(|p| world.transform_point3(p.into()))
        .collect();

    let normals = match primitive.get(&Semantic::Normals) {
        Some(acc) => {
            check(
                &acc,
                &name,
                "NORMAL",
                &[DataType::F32],
                Dimensions::Vec3,
                buffers,
            )?;
            let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
            Some(
                reader
                    .read_normals()
                    .ok_or_else(|| unreadable("NORMAL"))?
                    .map(|n| normal_matrix * Vec3::from(n))
                    .collect(),
            )
        }
        None => None,
    };

    let uvs = match primitive.get(&Semantic::TexCoords(0)) {
        Some(acc) => {
            let types = [DataType::F32, DataType::U8, DataType::U16];
            check(&acc, &name, "TEXCOORD_0", &types, Dimensions::Vec2, buffers)?;
            Some(
                reader
                    .read_tex_coords(0)
                    .ok_or_else(|| unreadable("TEXCOORD_0"))?
                    .into_f32()
                    .map(Vec2::from)
                    .collect(),
            )
        }
        None => None,
    };

    let indices: Vec<u32> = match primitive.indices() {
        Some(acc) => {
            check(
                &acc,
                &name,
                "indices",
                &[DataType::U8, DataType::U16, DataType::U32],
                Dimensions::Scalar,
                buffers,
            )?;
            reader
                .read_indices()
                .ok_or_else(|| unreadable("indices"))?
                .into_u32()
                .collect()
        }
        None => (0..u32::try_from(positions.len())
            .map_err(|_| format!("{name}: too many vertices"))?)
            .collect(),
    };
    // (`usize::is_multiple_of` needs Rust 1.87; the workspace supports 1.85.)
    let leftover = indices.len() % 3;
    if leftover > 0 {
        warnings.push(format!(
            "{name}: {} indices is not a multiple of 3; the last {leftover} are ignored",
            indices.len()
        ));
    }
    let mirrored = Mat3::from_mat4(world).determinant() < 0.0;
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
        triangles,
        material,
    })
}

/// Checks an accessor's type and that all its elements lie inside its buffer view and buffer.
fn check(
    acc: &Accessor,
    prim: &str,
    what: &str,
    types: &[DataType],
    dims: Dimensions,
    buffers: &[Vec<u8>],
) -> Result<(), String> {
    let at = format!("{prim}: {what} (accessor {})", acc.index());
    if !types.contains(&acc.data_type()) || acc.dimensions() != dims {
        return Err(format!(
            "{at} is {:?} {:?}; expected {dims:?} of {types:?}",
            acc.dimensions(),
            acc.data_type()
        ));
    }
    if acc.sparse().is_some() {
        return Err(format!(
            "{at} is sparse; sparse accessors are not supported"
        ));
    }
    let view = acc
        .view()
        .ok_or_else(|| format!("{at} has no buffer view"))?;
    if acc.count() == 0 {
        return Err(format!("{at} has no elements"));
    }
    let (size, stride) = (acc.size(), view.stride().unwrap_or(acc.size()));
    let buffer_len = buffers.get(view.buffer().index()).map_or(0, Vec::len);
    let view_fits = view
        .offset()
        .checked_add(view.length())
        .is_some_and(|end| end <= buffer_len);
    let data_end = (acc.count() - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(acc.offset()))
        .and_then(|n| n.checked_add(size));
    if stride < size || !view_fits || data_end.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "{at}: {} elements of {size} bytes (stride {stride}, offset {}) do not fit buffer view {} ({} bytes at {}) of a {buffer_len}-byte buffer",
            acc.count(),
            acc.offset(),
            view.index(),
            view.length(),
            view.offset()
        ));
    }
    Ok(())
}
