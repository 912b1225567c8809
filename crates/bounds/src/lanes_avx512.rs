//! Sixteen `f32` lanes in one AVX-512 register ([`A16`]): the arithmetic of [`crate::lanes`]
//! with explicit 512-bit instructions, one per operation, for the kernels that run only after
//! `is_x86_feature_detected!("avx512f")` (inside `#[target_feature(enable = "avx512f")]`
//! functions). Each operation is the correctly rounded IEEE one, none fused, and the
//! comparisons are the ordered ones of `>` and `<=`, exactly as in `lanes_avx::A8`: a lane
//! agrees bit for bit with the scalar code and with the eight-lane types. On a CPU that
//! runs a 512-bit operation as two 256-bit halves (Zen 4) the arithmetic per cycle is the
//! AVX2 kernel's, but each instruction carries twice the lanes: a kernel whose long chains
//! of dependent operations fill the scheduler (the filter's exponential) keeps twice the
//! work in flight.
use crate::lanes::Real;
use core::arch::x86_64::{
    __m512, __mmask16, _mm512_add_epi32, _mm512_add_ps, _mm512_castps_si512, _mm512_castsi512_ps,
    _mm512_cmp_ps_mask, _mm512_cvttps_epi32, _mm512_div_ps, _mm512_loadu_ps, _mm512_mask_blend_ps,
    _mm512_mul_ps, _mm512_roundscale_ps, _mm512_set1_epi32, _mm512_set1_ps, _mm512_slli_epi32,
    _mm512_sqrt_ps, _mm512_storeu_ps, _mm512_sub_ps, _mm512_xor_si512, _CMP_GT_OQ, _CMP_LE_OQ,
    _MM_FROUND_NO_EXC, _MM_FROUND_TO_NEAREST_INT, _MM_FROUND_TO_NEG_INF,
};
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Sixteen `f32` lanes in an AVX-512 register.
#[derive(Clone, Copy)]
pub struct A16(__m512);

/// Sixteen comparison flags: bit k for lane k.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AM16(pub __mmask16);

// SAFETY (every `unsafe` block below): the intrinsics need AVX-512F. The methods are only
// called from kernels compiled with `#[target_feature(enable = "avx512f")]`, which run only
// where `is_x86_feature_detected!("avx512f")` holds. As with `lanes_avx::A8`, the methods
// are safe to name (the `Real` trait's are), so that contract is the caller's: an `A16` used
// outside such a kernel, on a CPU without AVX-512F, stops the process on an illegal
// instruction.

macro_rules! binary {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for A16 {
            type Output = A16;
            #[inline(always)]
            fn $method(self, o: A16) -> A16 {
                A16(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}

binary!(Add, add, _mm512_add_ps);
binary!(Sub, sub, _mm512_sub_ps);
binary!(Mul, mul, _mm512_mul_ps);
binary!(Div, div, _mm512_div_ps);

impl Neg for A16 {
    type Output = A16;
    /// The sign bit flipped, as `-x` does (an integer xor: AVX-512F has no float one).
    #[inline(always)]
    fn neg(self) -> A16 {
        A16(unsafe {
            _mm512_castsi512_ps(_mm512_xor_si512(
                _mm512_castps_si512(self.0),
                _mm512_set1_epi32(i32::MIN),
            ))
        })
    }
}

impl BitAnd for AM16 {
    type Output = AM16;
    #[inline(always)]
    fn bitand(self, o: AM16) -> AM16 {
        AM16(self.0 & o.0)
    }
}

impl BitOr for AM16 {
    type Output = AM16;
    #[inline(always)]
    fn bitor(self, o: AM16) -> AM16 {
        AM16(self.0 | o.0)
    }
}

impl Not for AM16 {
    type Output = AM16;
    #[inline(always)]
    fn not(self) -> AM16 {
        AM16(!self.0)
    }
}

impl Real for A16 {
    type Mask = AM16;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        A16(unsafe { _mm512_set1_ps(v) })
    }
    #[inline(always)]
    fn flag(set: bool) -> AM16 {
        AM16(if set { u16::MAX } else { 0 })
    }
    #[inline(always)]
    fn gt(self, other: Self) -> AM16 {
        AM16(unsafe { _mm512_cmp_ps_mask::<_CMP_GT_OQ>(self.0, other.0) })
    }
    #[inline(always)]
    fn le(self, other: Self) -> AM16 {
        AM16(unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(self.0, other.0) })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        A16(unsafe { _mm512_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn select(mask: AM16, a: Self, b: Self) -> Self {
        // The blend takes its second operand where the mask is set.
        A16(unsafe { _mm512_mask_blend_ps(mask.0, b.0, a.0) })
    }
    #[inline(always)]
    fn round(self) -> Self {
        A16(unsafe {
            _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(self.0)
        })
    }
    #[inline(always)]
    fn floor(self) -> Self {
        A16(unsafe {
            _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(self.0)
        })
    }
    #[inline(always)]
    fn exp2i(self) -> Self {
        // The integral values convert exactly.
        A16(unsafe {
            let n = _mm512_add_epi32(_mm512_cvttps_epi32(self.0), _mm512_set1_epi32(127));
            _mm512_castsi512_ps(_mm512_slli_epi32::<23>(n))
        })
    }
    #[inline(always)]
    fn all(mask: AM16) -> bool {
        mask.0 == u16::MAX
    }
    #[inline(always)]
    fn any(mask: AM16) -> bool {
        mask.0 != 0
    }
}

impl A16 {
    /// The sixteen floats from `v[0]` on (no alignment needed). Panics if `v` is shorter.
    #[inline(always)]
    pub fn load(v: &[f32]) -> Self {
        let v = &v[..16];
        A16(unsafe { _mm512_loadu_ps(v.as_ptr()) })
    }

    /// Writes the sixteen lanes to `out[0..16]`. Panics if `out` is shorter.
    #[inline(always)]
    pub fn store(self, out: &mut [f32]) {
        let out = &mut out[..16];
        unsafe { _mm512_storeu_ps(out.as_mut_ptr(), self.0) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::F8;
    use crate::test_util::{flags8, lane_operations, LaneResults};

    #[target_feature(enable = "avx512f")]
    fn wide(a: &[f32; 16], b: &[f32; 16]) -> LaneResults {
        let values = |v: A16| {
            let mut lanes = vec![0.0; 16];
            v.store(&mut lanes);
            lanes
        };
        let flags = |m: AM16| (0..16).map(|k| m.0 >> k & 1 == 1).collect();
        lane_operations(A16::load(a), A16::load(b), values, flags)
    }

    /// The two halves in plain arrays: each operation's sixteen values (or flags) in lane
    /// order, and whether all and any of each mask's sixteen flags are set.
    fn plain(a: &[f32; 16], b: &[f32; 16]) -> LaneResults {
        let half = |v: &[f32; 16], h: usize| F8(core::array::from_fn(|i| v[8 * h + i]));
        let [lo, hi] =
            [0, 1].map(|h| lane_operations(half(a, h), half(b, h), |v| v.0.to_vec(), flags8::<F8>));
        let flags = interleave(&lo.1, &hi.1);
        let reductions = flags
            .chunks(16)
            .map(|m| [m.iter().all(|&f| f), m.iter().any(|&f| f)])
            .collect();
        (interleave(&lo.0, &hi.0), flags, reductions)
    }

    /// The halves' values per operation (eight of each half in turn) in lane order.
    fn interleave<T: Copy>(lo: &[T], hi: &[T]) -> Vec<T> {
        let halves = lo.chunks(8).zip(hi.chunks(8));
        halves
            .flat_map(|(l, h)| l.iter().chain(h).copied())
            .collect()
    }

    #[test]
    fn avx512_lanes_equal_the_array_lanes_bit_for_bit() {
        if !std::arch::is_x86_feature_detected!("avx512f") {
            return;
        }
        let mut rng = crate::test_util::Rng::new(0x5EED_A512);
        for _ in 0..10_000 {
            let a: [f32; 16] = core::array::from_fn(|_| rng.lane_input());
            let b: [f32; 16] = core::array::from_fn(|_| rng.lane_input());
            // SAFETY: AVX-512F was detected above.
            let got = unsafe { wide(&a, &b) };
            assert_eq!(got, plain(&a, &b), "a {a:?} b {b:?}");
        }
    }
}
