//! The arithmetic of the early exits written once for one `f32` and for eight lanes
//! ([`F8`]): every lane performs the same IEEE operations in the same order as the scalar
//! code, so the two agree bit for bit. [`F8`] is a plain array (the layout chunks are stored
//! in, and the lanes of CPUs without AVX2); the AVX2 kernels compute in `lanes_avx::A8`, one
//! 256-bit instruction per operation, loaded from that layout through [`Lanes8`]. No
//! operation is fused (Rust never contracts `a * b + c` into an FMA), so the lanes round
//! exactly as the scalar shader does.
use core::fmt::Debug;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A number type of the early-exit arithmetic: `f32`, or eight of them.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The result of a comparison: `bool`, or one flag per lane.
    type Mask: Copy
        + Debug
        + PartialEq
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;
    fn splat(v: f32) -> Self;
    /// `set` in every lane.
    fn flag(set: bool) -> Self::Mask;
    fn gt(self, other: Self) -> Self::Mask;
    fn le(self, other: Self) -> Self::Mask;
    /// The IEEE square root (correctly rounded, as `f32::sqrt`).
    fn sqrt(self) -> Self;
    /// `a` where `mask` is set, else `b`.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
}

/// The larger of `a` and `b` as glam's `Vec3::max_element` picks it: `a` if `a > b`, else `b`.
#[inline(always)]
pub fn max<R: Real>(a: R, b: R) -> R {
    R::select(a.gt(b), a, b)
}

/// The smaller of `a` and `b`: `a` if `a < b`, else `b`.
#[inline(always)]
pub fn min<R: Real>(a: R, b: R) -> R {
    R::select(b.gt(a), a, b)
}

/// `v` clamped to [0, 1] as `f32::clamp(0.0, 1.0)` does it (NaN stays NaN).
#[inline(always)]
pub fn clamp01<R: Real>(v: R) -> R {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let v = R::select(zero.gt(v), zero, v);
    R::select(v.gt(one), one, v)
}

impl Real for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        v
    }
    #[inline(always)]
    fn flag(set: bool) -> bool {
        set
    }
    #[inline(always)]
    fn gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn le(self, other: Self) -> bool {
        self <= other
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn select(mask: bool, a: Self, b: Self) -> Self {
        if mask {
            a
        } else {
            b
        }
    }
}

/// Eight `f32` lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(align(32))]
pub struct F8(pub [f32; 8]);

/// Eight comparison flags (all bits set or clear per lane).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(align(32))]
pub struct M8(pub [u32; 8]);

impl M8 {
    /// Bit k set where lane k is set.
    #[inline(always)]
    pub fn bits(self) -> u8 {
        let mut b = 0u8;
        for (k, m) in self.0.iter().enumerate() {
            b |= ((m >> 31) as u8) << k;
        }
        b
    }
}

#[inline(always)]
fn zip(a: F8, b: F8, f: impl Fn(f32, f32) -> f32) -> F8 {
    F8(core::array::from_fn(|k| f(a.0[k], b.0[k])))
}

#[inline(always)]
fn flags(a: F8, b: F8, f: impl Fn(f32, f32) -> bool) -> M8 {
    M8(core::array::from_fn(|k| {
        if f(a.0[k], b.0[k]) {
            u32::MAX
        } else {
            0
        }
    }))
}

impl Add for F8 {
    type Output = F8;
    #[inline(always)]
    fn add(self, o: F8) -> F8 {
        zip(self, o, |a, b| a + b)
    }
}

impl Sub for F8 {
    type Output = F8;
    #[inline(always)]
    fn sub(self, o: F8) -> F8 {
        zip(self, o, |a, b| a - b)
    }
}

impl Mul for F8 {
    type Output = F8;
    #[inline(always)]
    fn mul(self, o: F8) -> F8 {
        zip(self, o, |a, b| a * b)
    }
}

impl Div for F8 {
    type Output = F8;
    #[inline(always)]
    fn div(self, o: F8) -> F8 {
        zip(self, o, |a, b| a / b)
    }
}

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        F8(self.0.map(|a| -a))
    }
}

impl BitAnd for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitand(self, o: M8) -> M8 {
        M8(core::array::from_fn(|k| self.0[k] & o.0[k]))
    }
}

impl BitOr for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitor(self, o: M8) -> M8 {
        M8(core::array::from_fn(|k| self.0[k] | o.0[k]))
    }
}

impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        M8(self.0.map(|m| !m))
    }
}

impl Real for F8 {
    type Mask = M8;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        F8([v; 8])
    }
    #[inline(always)]
    fn flag(set: bool) -> M8 {
        M8([u32::from(set).wrapping_neg(); 8])
    }
    #[inline(always)]
    fn gt(self, other: Self) -> M8 {
        flags(self, other, |a, b| a > b)
    }
    #[inline(always)]
    fn le(self, other: Self) -> M8 {
        flags(self, other, |a, b| a <= b)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F8(self.0.map(f32::sqrt))
    }
    #[inline(always)]
    fn select(mask: M8, a: Self, b: Self) -> Self {
        F8(core::array::from_fn(|k| {
            if mask.0[k] != 0 {
                a.0[k]
            } else {
                b.0[k]
            }
        }))
    }
}

/// Eight lanes of [`Real`] that load from the memory layout [`F8`] / [`M8`] (chunks are
/// stored as plain arrays) and give their flags as a bit pattern: [`F8`] itself, or
/// `lanes_avx::A8` in AVX registers inside the AVX2 kernels.
pub trait Lanes8: Real {
    fn load(v: &F8) -> Self;
    fn store(self) -> F8;
    fn load_mask(m: &M8) -> Self::Mask;
    /// Bit k set where lane k of `m` is set.
    fn bits(m: Self::Mask) -> u8;
}

impl Lanes8 for F8 {
    #[inline(always)]
    fn load(v: &F8) -> Self {
        *v
    }
    #[inline(always)]
    fn store(self) -> F8 {
        self
    }
    #[inline(always)]
    fn load_mask(m: &M8) -> M8 {
        *m
    }
    #[inline(always)]
    fn bits(m: M8) -> u8 {
        m.bits()
    }
}

/// `a·b` as glam forms `Vec3::dot`: `(a.x b.x + a.y b.y) + a.z b.z`.
#[inline(always)]
pub fn dot<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a×b` as glam forms `Vec3::cross`.
#[inline(always)]
pub fn cross<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    [
        a[1] * b[2] - b[1] * a[2],
        a[2] * b[0] - b[2] * a[0],
        a[0] * b[1] - b[0] * a[1],
    ]
}
