//! Reading glTF accessors as the specification allows them (glTF 2.0 section 3.6.2), checked
//! before any byte is read (the `gltf` crate's readers assume well-formed accessors and read
//! only float attributes):
//! - any component type, integers normalized where the accessor says so (section 3.11:
//!   `max(c / 127, -1)` for bytes, `c / 255`, `max(c / 32767, -1)`, `c / 65535`), which covers
//!   `KHR_mesh_quantization`;
//! - accessors without a buffer view are zeros;
//! - sparse accessors: the base (a buffer view, or zeros) with the listed elements replaced.
use gltf::accessor::sparse::IndexType;
use gltf::accessor::{Accessor, DataType, Dimensions};

/// The accessor's elements as `N` floats each. `types` lists the component types allowed.
pub(crate) fn read_floats<const N: usize>(
    acc: &Accessor,
    buffers: &[Vec<u8>],
    at: &str,
    types: &[DataType],
) -> Result<Vec<[f32; N]>, String> {
    let values = components(acc, buffers, at, types, N)?;
    let normalized = acc.normalized();
    let scale = |c: f64| -> f32 {
        if !normalized {
            return c as f32;
        }
        match acc.data_type() {
            DataType::I8 => (c / 127.0).max(-1.0) as f32,
            DataType::U8 => (c / 255.0) as f32,
            DataType::I16 => (c / 32767.0).max(-1.0) as f32,
            DataType::U16 => (c / 65535.0) as f32,
            DataType::U32 => (c / 4294967295.0) as f32,
            DataType::F32 => c as f32,
        }
    };
    Ok(values
        .chunks_exact(N)
        .map(|c| std::array::from_fn(|i| scale(c[i])))
        .collect())
}

/// A scalar index accessor (unsigned bytes, shorts or ints).
pub(crate) fn read_indices(
    acc: &Accessor,
    buffers: &[Vec<u8>],
    at: &str,
) -> Result<Vec<u32>, String> {
    let types = [DataType::U8, DataType::U16, DataType::U32];
    // Unsigned integers up to 2^32 are exact in f64.
    Ok(components(acc, buffers, at, &types, 1)?
        .into_iter()
        .map(|c| c as u32)
        .collect())
}

fn dimensions(n: usize) -> Dimensions {
    match n {
        1 => Dimensions::Scalar,
        2 => Dimensions::Vec2,
        3 => Dimensions::Vec3,
        _ => Dimensions::Vec4,
    }
}

/// Every component of every element, in order, as f64 (exact for every component type).
fn components(
    acc: &Accessor,
    buffers: &[Vec<u8>],
    at: &str,
    types: &[DataType],
    n: usize,
) -> Result<Vec<f64>, String> {
    let dims = dimensions(n);
    if !types.contains(&acc.data_type()) || acc.dimensions() != dims {
        return Err(format!(
            "{at} is {:?} {:?}; expected {dims:?} of {types:?}",
            acc.dimensions(),
            acc.data_type()
        ));
    }
    if acc.count() == 0 {
        return Err(format!("{at} has no elements"));
    }
    let size = acc.size();
    let mut out = match acc.view() {
        None => vec![0.0; acc.count() * n],
        Some(view) => {
            let stride = view.stride().unwrap_or(size);
            let bytes = view_bytes(&view, buffers, at)?;
            let end = (acc.count() - 1)
                .checked_mul(stride)
                .and_then(|x| x.checked_add(acc.offset()))
                .and_then(|x| x.checked_add(size));
            if stride < size || end.is_none_or(|e| e > bytes.len()) {
                return Err(format!(
                    "{at}: {} elements of {size} bytes (stride {stride}, offset {}) do not fit buffer view {} ({} bytes)",
                    acc.count(),
                    acc.offset(),
                    view.index(),
                    bytes.len()
                ));
            }
            let data_type = acc.data_type();
            (0..acc.count())
                .flat_map(|i| {
                    let start = acc.offset() + i * stride;
                    (0..n).map(move |c| decode(data_type, &bytes[start + c * size / n..]))
                })
                .collect()
        }
    };
    if let Some(sparse) = acc.sparse() {
        apply_sparse(acc, &sparse, buffers, at, n, &mut out)?;
    }
    Ok(out)
}

/// Replaces the elements a sparse accessor lists (glTF 2.0 section 3.6.2.3).
fn apply_sparse(
    acc: &Accessor,
    sparse: &gltf::accessor::sparse::Sparse,
    buffers: &[Vec<u8>],
    at: &str,
    n: usize,
    out: &mut [f64],
) -> Result<(), String> {
    let count = sparse.count();
    let indices = sparse.indices();
    let (index_type, index_size) = match indices.index_type() {
        IndexType::U8 => (DataType::U8, 1),
        IndexType::U16 => (DataType::U16, 2),
        IndexType::U32 => (DataType::U32, 4),
    };
    let index_bytes = view_bytes(&indices.view(), buffers, at)?;
    let values = sparse.values();
    let value_bytes = view_bytes(&values.view(), buffers, at)?;
    let size = acc.size();
    let fits = |bytes: &[u8], offset: usize, each: usize| {
        count
            .checked_mul(each)
            .and_then(|x| x.checked_add(offset))
            .is_some_and(|end| end <= bytes.len())
    };
    if !fits(index_bytes, indices.offset(), index_size) || !fits(value_bytes, values.offset(), size)
    {
        return Err(format!(
            "{at}: its {count} sparse indices or values do not fit their buffer views"
        ));
    }
    for k in 0..count {
        let i = decode(
            index_type,
            &index_bytes[indices.offset() + k * index_size..],
        ) as usize;
        if i >= acc.count() {
            return Err(format!(
                "{at}: sparse index {i} is past its {} elements",
                acc.count()
            ));
        }
        let start = values.offset() + k * size;
        for c in 0..n {
            out[i * n + c] = decode(acc.data_type(), &value_bytes[start + c * size / n..]);
        }
    }
    Ok(())
}

/// The bytes of a buffer view, checked against its buffer.
fn view_bytes<'b>(
    view: &gltf::buffer::View,
    buffers: &'b [Vec<u8>],
    at: &str,
) -> Result<&'b [u8], String> {
    let buffer = buffers
        .get(view.buffer().index())
        .map_or(&[][..], Vec::as_slice);
    view.offset()
        .checked_add(view.length())
        .and_then(|end| buffer.get(view.offset()..end))
        .ok_or_else(|| {
            format!(
                "{at}: buffer view {} ({} bytes at {}) lies outside its {}-byte buffer",
                view.index(),
                view.length(),
                view.offset(),
                buffer.len()
            )
        })
}

/// One little-endian component at the start of `b` (which holds at least its size).
fn decode(t: DataType, b: &[u8]) -> f64 {
    match t {
        DataType::I8 => f64::from(b[0] as i8),
        DataType::U8 => f64::from(b[0]),
        DataType::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
        DataType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
        DataType::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        DataType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
    }
}
