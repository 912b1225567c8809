// The quadtree of crates/cpu-ref/src/vsgl/quadtree.rs: `faces` pyramids of resolution n, level
// l of side ceil(n / 2^l) down to the 1 x 1 level `levels - 1`, stored face-major, then by
// level, then row-major. Every map of a frame has the same resolution, so the faces of all
// maps are numbered one after another (map by map) in one tree.
struct Tree {
    n: u32,
    faces: u32,
    levels: u32,
    // Texels per face, all levels.
    face_len: u32,
}

// The side ceil(n / 2^level) of a level.
fn tree_size(t: Tree, level: u32) -> u32 {
    var s = t.n;
    for (var l = 0u; l < level; l++) {
        s = (s + 1u) / 2u;
    }
    return s;
}

// The storage index of texel (x, y) of `level` of `face` (Quadtree::index).
fn tree_index(t: Tree, face: u32, level: u32, x: u32, y: u32) -> u32 {
    var offset = 0u;
    var s = t.n;
    for (var l = 0u; l < level; l++) {
        offset += s * s;
        s = (s + 1u) / 2u;
    }
    return face * t.face_len + offset + y * s + x;
}
