//! The storage layout of a mip pyramid per RSM face: the quadtree over which VPLs are clustered
//! (VSGL section 4.1) and importance is warped (section 4.2).

/// One pyramid per face of a square map of resolution `N`: level 0 is `N` texels square and
/// level `l` is `⌈N/2^l⌉` square, down to the 1×1 level `⌈log2 N⌉`. Texel `(x, y)` of level
/// `l` is the parent of texels `(2x + i, 2y + j)`, `i, j ∈ {0, 1}`, of level `l − 1` (children
/// beyond the edge of a level with odd size do not exist), so it covers the level-0 texels
/// `[2^l x, 2^l (x + 1)) × [2^l y, 2^l (y + 1))`. Storage is face-major, then level, then
/// row-major like the RSM (row `y`, column `x`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Quadtree {
    resolution: u32,
    faces: u32,
    /// Offset of each level within a face's block.
    level_offsets: Vec<usize>,
    /// Texels per face, all levels.
    face_len: usize,
}

impl Quadtree {
    /// The layout for `faces` maps of `resolution`² texels (a resolution of 0 counts as 1).
    pub fn new(resolution: u32, faces: u32) -> Self {
        let n = resolution.max(1);
        let mut level_offsets = vec![0];
        let mut size = n;
        let mut face_len = (n * n) as usize;
        while size > 1 {
            size = size.div_ceil(2);
            level_offsets.push(face_len);
            face_len += (size * size) as usize;
        }
        Self {
            resolution: n,
            faces,
            level_offsets,
            face_len,
        }
    }

    /// The resolution `N` of level 0.
    pub fn resolution(&self) -> u32 {
        self.resolution
    }

    /// The number of faces (pyramids).
    pub fn faces(&self) -> u32 {
        self.faces
    }

    /// The number of levels, `⌈log2 N⌉ + 1`; the last, `l_max`, is 1×1.
    pub fn levels(&self) -> u32 {
        self.level_offsets.len() as u32
    }

    /// The side `⌈N/2^level⌉` of a level.
    pub fn size(&self, level: u32) -> u32 {
        let mut size = self.resolution;
        for _ in 0..level {
            size = size.div_ceil(2);
        }
        size
    }

    /// Texels of every level of every face.
    pub fn len(&self) -> usize {
        self.face_len * self.faces as usize
    }

    /// Whether there are no faces.
    pub fn is_empty(&self) -> bool {
        self.faces == 0
    }

    /// The storage index of texel `(x, y)` of `level` of `face`. Panics out of range.
    pub fn index(&self, face: u32, level: u32, x: u32, y: u32) -> usize {
        let size = self.size(level);
        assert!(
            face < self.faces && x < size && y < size,
            "mip texel out of range"
        );
        face as usize * self.face_len + self.level_offsets[level as usize] + (y * size + x) as usize
    }

    /// The children `(x, y)` (at `level − 1`, `level ≥ 1`) of texel `(x, y)` of `level` that
    /// exist, in the order (0, 0), (1, 0), (0, 1), (1, 1).
    pub fn children(&self, level: u32, x: u32, y: u32) -> impl Iterator<Item = (u32, u32)> {
        let child_size = self.size(level - 1);
        [(0, 0), (1, 0), (0, 1), (1, 1)]
            .into_iter()
            .map(move |(i, j)| (2 * x + i, 2 * y + j))
            .filter(move |&(cx, cy)| cx < child_size && cy < child_size)
    }

    /// Fills levels 1.. of every face of `texels` (laid out by this quadtree, level 0 already
    /// set) by summing each texel's children with `add` onto `zero`.
    pub fn fill_levels<T: Clone>(&self, texels: &mut [T], zero: &T, add: impl Fn(&mut T, &T)) {
        for face in 0..self.faces {
            for level in 1..self.levels() {
                let size = self.size(level);
                for y in 0..size {
                    for x in 0..size {
                        let mut sum = zero.clone();
                        for (cx, cy) in self.children(level, x, y) {
                            add(&mut sum, &texels[self.index(face, level - 1, cx, cy)]);
                        }
                        texels[self.index(face, level, x, y)] = sum;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_sizes_and_children() {
        let q = Quadtree::new(5, 2);
        assert_eq!(q.levels(), 4);
        assert_eq!((0..4).map(|l| q.size(l)).collect::<Vec<_>>(), [5, 3, 2, 1]);
        assert_eq!(q.len(), 2 * (25 + 9 + 4 + 1));
        assert_eq!(q.index(1, 0, 0, 0), 39);
        assert_eq!(q.index(1, 3, 0, 0), 2 * 39 - 1);
        // The corner texel of level 1 of a 5-wide map has one child, the edge ones two.
        assert_eq!(q.children(1, 2, 2).collect::<Vec<_>>(), [(4, 4)]);
        assert_eq!(q.children(1, 2, 0).count(), 2);
        assert_eq!(q.children(1, 0, 0).count(), 4);
        // Counting level-0 texels up the pyramid: the top of each face holds all 25.
        let mut counts = vec![0u32; q.len()];
        for face in 0..2 {
            for y in 0..5 {
                for x in 0..5 {
                    counts[q.index(face, 0, x, y)] = 1;
                }
            }
        }
        q.fill_levels(&mut counts, &0, |a, b| *a += b);
        assert_eq!(counts[q.index(0, 3, 0, 0)], 25);
        assert_eq!(counts[q.index(1, 2, 0, 0)], 16);
        assert_eq!(counts[q.index(1, 2, 1, 1)], 1);
        assert_eq!(counts[q.index(1, 1, 2, 1)], 2);
        assert_eq!(Quadtree::new(1, 6).levels(), 1);
    }
}
