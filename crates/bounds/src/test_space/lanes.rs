//! [`TestSpace::new`](super::TestSpace::new)'s matrix BS of eq. (16)-(17) for eight spheroids
//! at a time: glam's f32 matrix arithmetic step for step in lanes ([`crate::lanes`]), so each
//! lane's BS is the one `TestSpace::new` forms, bit for bit. A culler that forms every VPL's
//! test space each frame (a million at RSM 1024) otherwise forms five 3×3 products (45
//! operations each), three normalisations and the checks one VPL at a time.
use crate::lanes::{all3, cross, dot, max, normalize, within, Real};

/// A 3×3 matrix in lanes, as glam's `Mat3` holds it: three columns.
pub type Mat3Lanes<L> = [[L; 3]; 3];

/// BS of `TestSpace::new(rotation, semi_axes, Vec3::ZERO)` in each lane where that returns a
/// non-empty test space, and those lanes. The others (refused, empty, or where the lanes'
/// checks are stricter: a NaN entry of RᵀR − I, which glam's `max` passes over) are the
/// caller's to form one at a time.
#[inline(always)]
pub fn test_matrices<L: Real>(
    rotation: Mat3Lanes<L>,
    semi_axes: [L; 3],
) -> (Mat3Lanes<L>, L::Mask) {
    let (zero, big) = (L::splat(0.0), L::splat(f32::MAX));
    let finite_rotation = all9(rotation, -big, big);
    // `is_rotation`: |RᵀR − I| at most ROTATION_TOLERANCE in every entry, det R > 0.
    let e = sub_identity(mat3_mul(transpose(rotation), rotation));
    let tolerance = L::splat(super::ROTATION_TOLERANCE);
    let orthonormal = all9(e, -tolerance, tolerance);
    let determinant = dot(rotation[0], cross(rotation[1], rotation[2]));
    let semi = all3([
        semi_axes[0].gt(zero) & semi_axes[0].le(big),
        semi_axes[1].gt(zero) & semi_axes[1].le(big),
        semi_axes[2].gt(zero) & semi_axes[2].le(big),
    ]);
    // `stretch`: R diag(1/r) Rᵀ, the products in glam's order.
    let one = L::splat(1.0);
    let inverse = [one / semi_axes[0], one / semi_axes[1], one / semi_axes[2]];
    let diagonal = [
        [inverse[0], zero, zero],
        [zero, inverse[1], zero],
        [zero, zero, inverse[2]],
    ];
    let s = mat3_mul(mat3_mul(rotation, diagonal), transpose(rotation));
    let matrix = mat3_mul(test_rotation(s), s);
    let ok = finite_rotation & orthonormal & determinant.gt(zero) & semi & all9(matrix, -big, big);
    (matrix, ok)
}

/// `test_rotation` of `super`: the rotation B of eq. (17) for the stretch `s`.
#[inline(always)]
fn test_rotation<L: Real>(s: Mat3Lanes<L>) -> Mat3Lanes<L> {
    // The largest |entry| as glam's `abs`, `max` and `max_element` find it (a zero's sign
    // aside, which only a zero matrix could keep, and that one is refused).
    let a = [abs3(s[0]), abs3(s[1]), abs3(s[2])];
    let m = [
        max(max(a[0][0], a[1][0]), a[2][0]),
        max(max(a[0][1], a[1][1]), a[2][1]),
        max(max(a[0][2], a[1][2]), a[2][2]),
    ];
    let scale = max(m[0], max(m[1], m[2]));
    let bx = [s[0][0] / scale, s[0][1] / scale, s[0][2] / scale];
    let by = [s[1][0] / scale, s[1][1] / scale, s[1][2] / scale];
    let (len_x, len_y) = (dot(bx, bx).sqrt(), dot(by, by).sqrt());
    let ux = [bx[0] / len_x, bx[1] / len_x, bx[2] / len_x];
    let uy = [by[0] / len_y, by[1] / len_y, by[2] / len_y];
    let z = normalize(cross(ux, uy));
    let first = len_x.gt(len_y);
    let (zx, yz) = (cross(z, ux), cross(uy, z));
    let x = [
        L::select(first, ux[0], yz[0]),
        L::select(first, ux[1], yz[1]),
        L::select(first, ux[2], yz[2]),
    ];
    let y = [
        L::select(first, zx[0], uy[0]),
        L::select(first, zx[1], uy[1]),
        L::select(first, zx[2], uy[2]),
    ];
    transpose([x, y, z])
}

/// `a * b` as glam's `Mat3 * Mat3`: column j is `a v` with v = b's column j. (No closures
/// here or below: in an AVX2 kernel each could be a function without AVX2.)
#[inline(always)]
pub fn mat3_mul<L: Real>(a: Mat3Lanes<L>, b: Mat3Lanes<L>) -> Mat3Lanes<L> {
    [mul_vec(a, b[0]), mul_vec(a, b[1]), mul_vec(a, b[2])]
}

/// `a v` as glam's `Mat3 * Vec3`: `(a.x v.x + a.y v.y) + a.z v.z`.
#[inline(always)]
fn mul_vec<L: Real>(a: Mat3Lanes<L>, v: [L; 3]) -> [L; 3] {
    [
        a[0][0] * v[0] + a[1][0] * v[1] + a[2][0] * v[2],
        a[0][1] * v[0] + a[1][1] * v[1] + a[2][1] * v[2],
        a[0][2] * v[0] + a[1][2] * v[1] + a[2][2] * v[2],
    ]
}

#[inline(always)]
fn transpose<L: Real>(m: Mat3Lanes<L>) -> Mat3Lanes<L> {
    [
        [m[0][0], m[1][0], m[2][0]],
        [m[0][1], m[1][1], m[2][1]],
        [m[0][2], m[1][2], m[2][2]],
    ]
}

/// `m − I` as glam subtracts `Mat3::IDENTITY` (each entry minus 1 or 0).
#[inline(always)]
fn sub_identity<L: Real>(m: Mat3Lanes<L>) -> Mat3Lanes<L> {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    [
        [m[0][0] - one, m[0][1] - zero, m[0][2] - zero],
        [m[1][0] - zero, m[1][1] - one, m[1][2] - zero],
        [m[2][0] - zero, m[2][1] - zero, m[2][2] - one],
    ]
}

/// |v| per component (a zero's sign kept: see [`test_rotation`]).
#[inline(always)]
fn abs3<L: Real>(v: [L; 3]) -> [L; 3] {
    let zero = L::splat(0.0);
    [
        L::select(zero.gt(v[0]), -v[0], v[0]),
        L::select(zero.gt(v[1]), -v[1], v[1]),
        L::select(zero.gt(v[2]), -v[2], v[2]),
    ]
}

/// Where every entry lies in `[lo, hi]` (false for NaN).
#[inline(always)]
fn all9<L: Real>(m: Mat3Lanes<L>, lo: L, hi: L) -> L::Mask {
    all3(within(m[0], lo, hi)) & all3(within(m[1], lo, hi)) & all3(within(m[2], lo, hi))
}

#[cfg(test)]
mod tests;
