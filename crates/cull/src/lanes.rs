//! The arithmetic of the early exits written once for one `f32` and for eight lanes
//! ([`F8`]): every lane performs the same IEEE operations in the same order as the scalar
//! code, so the two agree bit for bit. [`F8`] is a plain array whose element-wise loops the
//! compiler turns into 256-bit instructions where AVX is enabled (see `reach_chunks`).
use core::ops::{Add, BitAnd, Mul, Neg, Not, Sub};

/// A number type of the early-exit arithmetic: `f32`, or eight of them.
pub trait Real:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    /// The result of a comparison: `bool`, or one flag per lane.
    type Mask: Copy + BitAnd<Output = Self::Mask> + Not<Output = Self::Mask>;
    fn splat(v: f32) -> Self;
    fn gt(self, other: Self) -> Self::Mask;
    fn le(self, other: Self) -> Self::Mask;
}

impl Real for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        v
    }
    #[inline(always)]
    fn gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn le(self, other: Self) -> bool {
        self <= other
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
    fn gt(self, other: Self) -> M8 {
        flags(self, other, |a, b| a > b)
    }
    #[inline(always)]
    fn le(self, other: Self) -> M8 {
        flags(self, other, |a, b| a <= b)
    }
}

/// `a·b` as glam forms `Vec3::dot`: `(a.x b.x + a.y b.y) + a.z b.z`.
#[inline(always)]
pub fn dot<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
