//! Eight `f32` lanes in one AVX register ([`A8`]): the arithmetic of [`crate::lanes`] with
//! explicit 256-bit instructions, one per operation, for the kernels that run only after
//! `is_x86_feature_detected!("avx2")` (inside `#[target_feature(enable = "avx2")]`
//! functions, where these `#[inline(always)]` methods and the intrinsics they call are
//! inlined). The plain-array [`F8`] relies on the compiler's vectorizer, which keeps every
//! lane in a register only in simple kernels; with the lane type explicit, each kernel
//! compiles to the instructions it names. Each operation is the correctly rounded IEEE one
//! (`vaddps`, `vsubps`, `vmulps`, `vdivps`, `vsqrtps`; negation flips the sign bit, as
//! `-x` does), none fused, and the comparisons are the ordered ones of `>` and `<=` (false
//! where either side is NaN), so a lane agrees bit for bit with the scalar code.
use crate::lanes::{Lanes8, Real, F8, M8};
use core::arch::x86_64::{
    __m256, _mm256_add_epi32, _mm256_add_ps, _mm256_and_ps, _mm256_blendv_ps, _mm256_castsi256_ps,
    _mm256_cmp_ps, _mm256_cvttps_epi32, _mm256_div_ps, _mm256_floor_ps, _mm256_load_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_ps, _mm256_round_ps, _mm256_set1_epi32,
    _mm256_set1_ps, _mm256_slli_epi32, _mm256_sqrt_ps, _mm256_store_ps, _mm256_sub_ps,
    _mm256_xor_ps, _CMP_GT_OQ, _CMP_LE_OQ, _MM_FROUND_NO_EXC, _MM_FROUND_TO_NEAREST_INT,
};
use core::fmt::{self, Debug};
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Eight `f32` lanes in an AVX register.
#[derive(Clone, Copy)]
pub struct A8(__m256);

/// Eight comparison flags in an AVX register (all bits set or clear per lane).
#[derive(Clone, Copy)]
pub struct AM8(__m256);

// SAFETY (every `unsafe` block below): the intrinsics need AVX. The methods are only called
// from kernels compiled with `#[target_feature(enable = "avx2")]`, which run only where
// `is_x86_feature_detected!("avx2")` holds (AVX2 implies AVX).

macro_rules! binary {
    ($trait:ident, $method:ident, $intrinsic:ident, $ty:ident) => {
        impl $trait for $ty {
            type Output = $ty;
            #[inline(always)]
            fn $method(self, o: $ty) -> $ty {
                $ty(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}

binary!(Add, add, _mm256_add_ps, A8);
binary!(Sub, sub, _mm256_sub_ps, A8);
binary!(Mul, mul, _mm256_mul_ps, A8);
binary!(Div, div, _mm256_div_ps, A8);
binary!(BitAnd, bitand, _mm256_and_ps, AM8);
binary!(BitOr, bitor, _mm256_or_ps, AM8);

/// Every bit of a lane set: the sign bit alone for `Neg`, all of them for `Not`.
#[inline(always)]
fn bits_of(v: i32) -> __m256 {
    unsafe { _mm256_castsi256_ps(_mm256_set1_epi32(v)) }
}

impl Neg for A8 {
    type Output = A8;
    #[inline(always)]
    fn neg(self) -> A8 {
        A8(unsafe { _mm256_xor_ps(self.0, bits_of(i32::MIN)) })
    }
}

impl Not for AM8 {
    type Output = AM8;
    #[inline(always)]
    fn not(self) -> AM8 {
        AM8(unsafe { _mm256_xor_ps(self.0, bits_of(-1)) })
    }
}

impl PartialEq for AM8 {
    fn eq(&self, other: &Self) -> bool {
        <A8 as Lanes8>::bits(*self) == <A8 as Lanes8>::bits(*other)
    }
}

impl Debug for AM8 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "AM8({:08b})", <A8 as Lanes8>::bits(*self))
    }
}

impl Real for A8 {
    type Mask = AM8;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        A8(unsafe { _mm256_set1_ps(v) })
    }
    #[inline(always)]
    fn flag(set: bool) -> AM8 {
        AM8(bits_of(-i32::from(set)))
    }
    #[inline(always)]
    fn gt(self, other: Self) -> AM8 {
        AM8(unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(self.0, other.0) })
    }
    #[inline(always)]
    fn le(self, other: Self) -> AM8 {
        AM8(unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(self.0, other.0) })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        A8(unsafe { _mm256_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn select(mask: AM8, a: Self, b: Self) -> Self {
        A8(unsafe { _mm256_blendv_ps(b.0, a.0, mask.0) })
    }
    #[inline(always)]
    fn round(self) -> Self {
        A8(unsafe { _mm256_round_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(self.0) })
    }
    #[inline(always)]
    fn floor(self) -> Self {
        A8(unsafe { _mm256_floor_ps(self.0) })
    }
    #[inline(always)]
    fn exp2i(self) -> Self {
        // The integral values convert exactly; AVX2 for the 256-bit integer add and shift.
        A8(unsafe {
            let n = _mm256_add_epi32(_mm256_cvttps_epi32(self.0), _mm256_set1_epi32(127));
            _mm256_castsi256_ps(_mm256_slli_epi32::<23>(n))
        })
    }
    #[inline(always)]
    fn all(mask: AM8) -> bool {
        <A8 as Lanes8>::bits(mask) == u8::MAX
    }
    #[inline(always)]
    fn any(mask: AM8) -> bool {
        <A8 as Lanes8>::bits(mask) != 0
    }
}

impl Lanes8 for A8 {
    #[inline(always)]
    fn load(v: &F8) -> Self {
        // F8 is 32-byte aligned.
        A8(unsafe { _mm256_load_ps(v.0.as_ptr()) })
    }
    #[inline(always)]
    fn store(self) -> F8 {
        let mut out = F8([0.0; 8]);
        // F8 is 32-byte aligned.
        unsafe { _mm256_store_ps(out.0.as_mut_ptr(), self.0) };
        out
    }
    #[inline(always)]
    fn load_mask(m: &M8) -> AM8 {
        AM8(unsafe { _mm256_load_ps(m.0.as_ptr().cast()) })
    }
    #[inline(always)]
    fn bits(m: AM8) -> u8 {
        unsafe { _mm256_movemask_ps(m.0) as u8 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{flags8, lane_operations, LaneResults};

    #[target_feature(enable = "avx2")]
    fn avx(a: &F8, b: &F8) -> LaneResults {
        let values = |v: A8| v.store().0.to_vec();
        lane_operations(A8::load(a), A8::load(b), values, flags8::<A8>)
    }

    #[test]
    fn avx_lanes_equal_the_array_lanes_bit_for_bit() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = crate::test_util::Rng::new(0x9E37_79B9_7F4A_7C15);
        for _ in 0..20_000 {
            let a = F8(core::array::from_fn(|_| rng.lane_input()));
            let b = F8(core::array::from_fn(|_| rng.lane_input()));
            // SAFETY: AVX2 was detected above.
            let wide = unsafe { avx(&a, &b) };
            let plain = lane_operations(a, b, |v| v.0.to_vec(), flags8::<F8>);
            assert_eq!(wide, plain, "a {a:?} b {b:?}");
        }
    }
}
