//! Arithmetic written once for one `f32` and for eight lanes ([`F8`]) or sixteen: the early
//! exits of the VPL shading, the SG shading of VSGLs (`sg/single.rs`) and the CPU filter. Every lane performs the same IEEE
//! operations in the same order as the scalar code, so the two agree bit for bit, including
//! [`exp`], which is built from those operations rather than taken from the platform's `libm`.
//! [`F8`] is a plain array (the layout chunks are stored in, and the lanes of CPUs without
//! AVX2); the AVX2 kernels compute in `lanes_avx::A8`, one 256-bit instruction per operation,
//! loaded from that layout through [`Lanes8`], and the AVX-512 ones in `lanes_avx512::A16`,
//! sixteen lanes. No operation is fused (Rust never contracts
//! `a * b + c` into an FMA), so the lanes round exactly as the scalar code does.
use core::fmt::Debug;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A number type of the lanes' arithmetic: `f32`, or eight or sixteen of them.
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
    /// The nearest integer, ties to even (`f32::round_ties_even`).
    fn round(self) -> Self;
    /// The largest integer not above (`f32::floor`).
    fn floor(self) -> Self;
    /// `2^n` for an integral `n` in [−126, 127] (the exponent field set directly: exact).
    fn exp2i(self) -> Self;
    /// Whether every lane of `mask` is set.
    fn all(mask: Self::Mask) -> bool;
    /// Whether any lane of `mask` is set.
    fn any(mask: Self::Mask) -> bool;
}

/// A value made of lanes that [`branch!`](crate::branch) can blend: one [`Real`] or a pair of them.
pub trait Blend<R: Real>: Copy {
    fn blend(mask: R::Mask, a: Self, b: Self) -> Self;
}

impl<R: Real> Blend<R> for R {
    #[inline(always)]
    fn blend(mask: R::Mask, a: Self, b: Self) -> Self {
        R::select(mask, a, b)
    }
}

impl<R: Real> Blend<R> for (R, R) {
    #[inline(always)]
    fn blend(mask: R::Mask, a: Self, b: Self) -> Self {
        (R::select(mask, a.0, b.0), R::select(mask, a.1, b.1))
    }
}

/// `$a` where `$mask` is set, else `$b`, per lane of the [`Real`] type `$r`: only the side
/// every lane takes is evaluated when the lanes agree (always, for one `f32`), both and
/// blended ([`Blend`]) when they differ. Each lane gets what the scalar branch gives it. A
/// macro rather than a function of closures: a closure is a function of its own, compiled
/// without the AVX2 kernel's target features, and the intrinsics in a closure that is not
/// inlined become calls.
#[macro_export]
macro_rules! branch {
    ($r:ty, $mask:expr, $a:expr, $b:expr $(,)?) => {{
        let mask = $mask;
        let a = if <$r as $crate::lanes::Real>::any(mask) {
            Some($a)
        } else {
            None
        };
        match a {
            Some(a) if <$r as $crate::lanes::Real>::all(mask) => a,
            _ => {
                let b = $b;
                match a {
                    Some(a) => $crate::lanes::Blend::<$r>::blend(mask, a, b),
                    None => b,
                }
            }
        }
    }};
}

/// `e^x`: Cody and Waite's reduction `x = n ln 2 + r` (`|r| ≤ ln 2 / 2`, `ln 2` split in two so
/// that `n ln 2` is exact) and Cephes' `expf` polynomial for `e^r`, scaled by `2^n` in two exact
/// halves. Within 2 ulp of `e^x` (the tests compare with `f64::exp` over the range); 0 at and
/// below −86 (and for NaN), where `e^x` is below 4.5e-38, and infinite above about 88.72. No
/// operation produces a subnormal: on x86 each instruction that does takes a microcode assist
/// of about a hundred cycles, which made the SG shading 1.6-2.1x slower on Sponza.
#[inline(always)]
pub fn exp<R: Real>(x: R) -> R {
    let zero = !x.gt(R::splat(-86.0));
    let x = min(max(x, R::splat(-86.0)), R::splat(89.0));
    let n = (x * R::splat(core::f32::consts::LOG2_E)).round();
    // ln 2 = 0.693_359_375 (355/512, whose product with n is exact) − 2.121_944_4e-4.
    let r = (x - n * R::splat(0.693_359_4)) - n * R::splat(-2.121_944_4e-4);
    let mut p = R::splat(1.987_569_1e-4);
    for c in [
        1.398_199_9e-3,
        8.333_452e-3,
        4.166_579_6e-2,
        1.666_666_5e-1,
        0.5,
    ] {
        p = p * r + R::splat(c);
    }
    let y = (p * (r * r) + r) + R::splat(1.0);
    let half = (n * R::splat(0.5)).floor();
    R::select(zero, R::splat(0.0), y * half.exp2i() * (n - half).exp2i())
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
    #[inline(always)]
    fn round(self) -> Self {
        self.round_ties_even()
    }
    #[inline(always)]
    fn floor(self) -> Self {
        f32::floor(self)
    }
    #[inline(always)]
    fn exp2i(self) -> Self {
        f32::from_bits(((self as i32 + 127) as u32) << 23)
    }
    #[inline(always)]
    fn all(mask: bool) -> bool {
        mask
    }
    #[inline(always)]
    fn any(mask: bool) -> bool {
        mask
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
    #[inline(always)]
    fn round(self) -> Self {
        F8(self.0.map(Real::round))
    }
    #[inline(always)]
    fn floor(self) -> Self {
        F8(self.0.map(f32::floor))
    }
    #[inline(always)]
    fn exp2i(self) -> Self {
        F8(self.0.map(Real::exp2i))
    }
    #[inline(always)]
    fn all(mask: M8) -> bool {
        mask.bits() == u8::MAX
    }
    #[inline(always)]
    fn any(mask: M8) -> bool {
        mask.bits() != 0
    }
}

/// One `f32` field of eight records as lanes: lane k is `get(of[k])` (the transposition of
/// eight per-item records, such as eight VPLs' constants, into a structure of lanes).
#[inline]
pub fn gather<T>(of: &[&T; 8], get: impl Fn(&T) -> f32) -> F8 {
    F8(core::array::from_fn(|k| get(of[k])))
}

/// [`gather`] for a field of three `f32`: one [`F8`] per component.
#[inline]
pub fn gather3<T>(of: &[&T; 8], get: impl Fn(&T) -> [f32; 3]) -> [F8; 3] {
    core::array::from_fn(|c| F8(core::array::from_fn(|k| get(of[k])[c])))
}

/// [`gather`] for a flag: lane k set where `get(of[k])` holds.
#[inline]
pub fn gather_flags<T>(of: &[&T; 8], get: impl Fn(&T) -> bool) -> M8 {
    M8(core::array::from_fn(|k| {
        u32::from(get(of[k])).wrapping_neg()
    }))
}

/// `N` values, each in every lane. This and [`load_all`] and [`store_all`] are loops, not
/// `array::map`: inside an AVX2 kernel the closure of a `map` is a function of its own,
/// compiled without the kernel's target features, so each operation would be a call.
#[inline(always)]
pub fn splat_all<R: Real, const N: usize>(v: &[f32; N]) -> [R; N] {
    let mut out = [R::splat(0.0); N];
    for (o, &v) in out.iter_mut().zip(v) {
        *o = R::splat(v);
    }
    out
}

/// `N` lanes loaded from their memory layout (see [`splat_all`]).
#[inline(always)]
pub fn load_all<L: Lanes8, const N: usize>(v: &[F8; N]) -> [L; N] {
    let mut out = [L::splat(0.0); N];
    for (o, v) in out.iter_mut().zip(v) {
        *o = L::load(v);
    }
    out
}

/// `N` lanes stored to their memory layout (see [`splat_all`]).
#[inline(always)]
pub fn store_all<L: Lanes8, const N: usize>(v: &[L; N]) -> [F8; N] {
    let mut out = [F8([0.0; 8]); N];
    for (o, v) in out.iter_mut().zip(v) {
        *o = v.store();
    }
    out
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

/// Where `lo <= v <= hi` (false for NaN).
#[inline(always)]
pub fn within1<L: Real>(v: L, lo: L, hi: L) -> L::Mask {
    !lo.gt(v) & v.le(hi)
}

/// [`within1`] per component.
#[inline(always)]
pub fn within<L: Real>(v: [L; 3], lo: L, hi: L) -> [L::Mask; 3] {
    [
        within1(v[0], lo, hi),
        within1(v[1], lo, hi),
        within1(v[2], lo, hi),
    ]
}

/// Where all three hold.
#[inline(always)]
pub fn all3<M: core::ops::BitAnd<Output = M> + Copy>(m: [M; 3]) -> M {
    m[0] & m[1] & m[2]
}

/// `a·b` as glam forms `Vec3::dot`: `(a.x b.x + a.y b.y) + a.z b.z`.
#[inline(always)]
pub fn dot<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `v` as glam's `Vec3::normalize` forms it: each component times 1/|v| (not over |v|: the
/// two differ by an ulp).
#[inline(always)]
pub fn normalize<R: Real>(v: [R; 3]) -> [R; 3] {
    let inverse = R::splat(1.0) / dot(v, v).sqrt();
    [v[0] * inverse, v[1] * inverse, v[2] * inverse]
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `exp` against `f64::exp` over its whole range, every 1/4096 and at the edges: within
    /// 2 ulp above −86, 0 at and below, infinity beyond the range, exact at 0; the eight lanes
    /// of `F8` equal to the scalar.
    #[test]
    fn exp_is_within_two_ulp_of_the_true_value() {
        let mut worst = 0.0f64;
        let mut k = -104 * 4096;
        while k <= 89 * 4096 {
            let x = k as f32 / 4096.0;
            let got = exp(x);
            let want = f64::from(x).exp();
            if x > -86.0 && want <= f64::from(f32::MAX) {
                let ulp = f64::from(f32::EPSILON) * (want.log2().floor()).exp2();
                let err = (f64::from(got) - want).abs() / ulp;
                worst = worst.max(err);
                assert!(err <= 2.0, "e^{x}: {got} vs {want} ({err} ulp)");
            } else if x <= -86.0 {
                assert_eq!(got, 0.0, "e^{x}");
            } else {
                assert_eq!(got, f32::INFINITY, "e^{x}");
            }
            let lanes = exp(F8(core::array::from_fn(|i| x + i as f32 * 1e-3)));
            for (i, v) in lanes.0.iter().enumerate() {
                assert_eq!(v.to_bits(), exp(x + i as f32 * 1e-3).to_bits());
            }
            k += 1;
        }
        println!("exp: worst error {worst:.2} ulp");
        assert_eq!(exp(0.0f32), 1.0);
        assert_eq!(exp(-200.0f32), 0.0);
        assert_eq!(exp(f32::NEG_INFINITY), 0.0);
        assert_eq!(exp(200.0f32), f32::INFINITY);
        assert_eq!(exp(f32::INFINITY), f32::INFINITY);
        assert_eq!(exp(f32::NAN), 0.0);
    }

    /// `branch` takes each lane's side, and evaluates only one side where the lanes agree.
    #[test]
    fn branch_takes_each_lanes_side() {
        let x = F8([-2.0, -1.0, 0.0, 1.0, 2.0, 3.0, -4.0, 5.0]);
        let got = crate::branch!(F8, x.gt(F8::splat(0.0)), x * x, -x);
        assert_eq!(got.0, [2.0, 1.0, -0.0, 1.0, 4.0, 9.0, 4.0, 25.0]);
        let calls = core::cell::Cell::new(0);
        let side = |v: f32| {
            calls.set(calls.get() + 1);
            F8::splat(v)
        };
        let all = crate::branch!(F8, F8::flag(true), side(1.0), side(2.0));
        assert_eq!((all, calls.get()), (F8::splat(1.0), 1));
        let none = crate::branch!(F8, F8::flag(false), side(1.0), side(2.0));
        assert_eq!((none, calls.get()), (F8::splat(2.0), 2));
        let pair = crate::branch!(F8, F8::flag(false), (x, x), (-x, x));
        assert_eq!(pair, (-x, x));
    }
}
