//! Building [`LightLists`]: lists gathered in chunks (one per piece of parallel work), then
//! numbered and concatenated into compressed rows.
use slc_core::{CullError, GBuffer, LightLists, NO_LIST};

/// Light lists of a run of tiles (or subregions), numbered from 0 within the chunk.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ListChunk {
    /// Length of each list, in order.
    pub lens: Vec<u32>,
    /// The lists' VPL indices, concatenated.
    pub indices: Vec<u32>,
    /// (pixel, list within the chunk or `NO_LIST`) for every pixel the chunk decided.
    pub pixels: Vec<(u32, u32)>,
}

impl ListChunk {
    /// Appends the merge of two ascending index lists as one list and returns its number in
    /// the chunk, or `NO_LIST` if both are empty (such a list is not stored).
    pub(crate) fn push_merged(&mut self, a: &[u32], b: &[u32]) -> u32 {
        if a.is_empty() && b.is_empty() {
            return NO_LIST;
        }
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            if a[i] < b[j] {
                self.indices.push(a[i]);
                i += 1;
            } else {
                self.indices.push(b[j]);
                j += 1;
            }
        }
        self.indices.extend_from_slice(&a[i..]);
        self.indices.extend_from_slice(&b[j..]);
        self.lens.push((a.len() + b.len()) as u32);
        (self.lens.len() - 1) as u32
    }
}

/// Numbers the chunks' lists consecutively (chunk by chunk) and builds the compressed rows;
/// pixels no chunk decided get `NO_LIST`.
pub(crate) fn assemble(
    chunks: Vec<ListChunk>,
    pixel_count: usize,
) -> Result<LightLists, CullError> {
    let list_count: usize = chunks.iter().map(|c| c.lens.len()).sum();
    let total: usize = chunks.iter().map(|c| c.indices.len()).sum();
    if u32::try_from(total).is_err() || u32::try_from(list_count).is_err() {
        return Err(CullError::Input(format!(
            "{total} light-list entries in {list_count} lists exceed 32-bit offsets"
        )));
    }
    let mut offsets = Vec::with_capacity(list_count + 1);
    offsets.push(0u32);
    let mut indices = Vec::with_capacity(total);
    let mut pixel_list = vec![NO_LIST; pixel_count];
    for chunk in chunks {
        let base = (offsets.len() - 1) as u32;
        for len in chunk.lens {
            offsets.push(offsets[offsets.len() - 1] + len);
        }
        indices.extend(chunk.indices);
        for (pixel, list) in chunk.pixels {
            if list != NO_LIST {
                pixel_list[pixel as usize] = base + list;
            }
        }
    }
    Ok(LightLists {
        offsets,
        indices,
        pixel_list,
        shared_list: Vec::new(),
    })
}

/// The number of pixels of a G-buffer whose sample count matches its size and whose pixel
/// indices fit in 32 bits.
pub(crate) fn pixel_count(gbuffer: &GBuffer) -> Result<usize, CullError> {
    let n = u64::from(gbuffer.width) * u64::from(gbuffer.height);
    if n != gbuffer.samples.len() as u64 || u32::try_from(n).is_err() {
        return Err(CullError::Input(format!(
            "G-buffer of {}x{} pixels has {} samples",
            gbuffer.width,
            gbuffer.height,
            gbuffer.samples.len()
        )));
    }
    Ok(n as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merged_lists_are_ascending_and_numbered_across_chunks() {
        let mut a = ListChunk::default();
        assert_eq!(a.push_merged(&[1, 4, 9], &[2, 3, 10, 11]), 0);
        assert_eq!(a.push_merged(&[], &[]), NO_LIST);
        assert_eq!(a.push_merged(&[], &[5]), 1);
        a.pixels = vec![(0, 0), (1, NO_LIST), (2, 1)];
        let mut b = ListChunk::default();
        assert_eq!(b.push_merged(&[7], &[]), 0);
        b.pixels = vec![(4, 0)];
        let lists = assemble(vec![a, b], 6).unwrap();
        assert_eq!(lists.len(), 3);
        assert_eq!(*lists.for_pixel(0), [1, 2, 3, 4, 9, 10, 11]);
        assert!(lists.for_pixel(1).is_empty());
        assert_eq!(*lists.for_pixel(2), [5]);
        assert!(lists.for_pixel(3).is_empty());
        assert_eq!(*lists.for_pixel(4), [7]);
        assert_eq!(lists.pixel_list[5], NO_LIST);
    }

    #[test]
    fn mismatched_gbuffer_is_an_error() {
        let g = GBuffer {
            width: 3,
            height: 2,
            samples: vec![None; 5],
        };
        assert!(pixel_count(&g).is_err());
        let empty = GBuffer {
            width: 0,
            height: 7,
            samples: Vec::new(),
        };
        assert_eq!(pixel_count(&empty).unwrap(), 0);
    }
}
