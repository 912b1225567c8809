//! The filter's taps, a vector of centre pixels at a time (eight or sixteen lanes): each lane
//! runs the operations of the scalar filter in the same order (the relative depth difference
//! divided, the normal weight squared `normal_squarings` times, the spatial weight times the
//! normal weight times the depth weight, the sums in tap order), so a lane's result differs
//! from the scalar filter's only by the exponential, here `slc_bounds::lanes::exp` (within 2
//! ulp) instead of the platform's `expf`, and every lane type gives the same bits.
use super::guide::{DEPTH, NORMAL};
use slc_bounds::lanes::{dot, exp, max, Lanes8, Real, F8};

/// Lanes the filter runs in, loaded from and stored to its planes of `f32`: the plain arrays
/// of [`F8`] (CPUs without AVX2), `A8` (AVX2) or `A16` (AVX-512).
pub(super) trait Row: Real {
    /// Lanes per vector.
    const N: usize;
    /// The `N` floats from `v[0]` on.
    fn load(v: &[f32]) -> Self;
    /// The lanes into `out[..N]`.
    fn store(self, out: &mut [f32]);
}

/// Eight lanes of any [`Lanes8`] type, through the [`F8`] layout.
macro_rules! row_of_eight {
    ($ty:ty) => {
        impl Row for $ty {
            const N: usize = 8;
            #[inline(always)]
            fn load(v: &[f32]) -> Self {
                let mut f = F8([0.0; 8]);
                f.0.copy_from_slice(&v[..8]);
                <$ty as Lanes8>::load(&f)
            }
            #[inline(always)]
            fn store(self, out: &mut [f32]) {
                out[..8].copy_from_slice(&<$ty as Lanes8>::store(self).0);
            }
        }
    };
}

row_of_eight!(F8);
#[cfg(target_arch = "x86_64")]
row_of_eight!(slc_bounds::lanes_avx::A8);

#[cfg(target_arch = "x86_64")]
impl Row for slc_bounds::lanes_avx512::A16 {
    const N: usize = 16;
    #[inline(always)]
    fn load(v: &[f32]) -> Self {
        Self::load(v)
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        Self::store(self, out)
    }
}

/// What the taps of one filter pass share.
#[derive(Clone, Debug)]
pub(super) struct Kernel {
    /// The spatial Gaussian of each tap, from −radius to radius.
    pub spatial: Vec<f32>,
    /// 1 / (2 σ_depth²).
    pub inv_2sd: f32,
    pub normal_squarings: u32,
}

/// A vector of floats of `plane` from `at`.
#[inline(always)]
pub(super) fn load<L: Row>(plane: &[f32], at: usize) -> L {
    L::load(&plane[at..])
}

/// A vector of floats at `at` of each of the three planes from `first` on.
#[inline(always)]
fn load3<L: Row>(row: &[f32], first: usize, stride: usize, at: usize) -> [L; 3] {
    [
        load(&row[first * stride..], at),
        load(&row[(first + 1) * stride..], at),
        load(&row[(first + 2) * stride..], at),
    ]
}

/// The guide of a vector of centre pixels.
#[derive(Clone, Copy)]
pub(super) struct Centre<L: Real> {
    pub depth: L,
    /// max(depth, 1e-6): what the depth difference is divided by.
    pub scale: L,
    pub normal: [L; 3],
}

impl<L: Row> Centre<L> {
    /// The centres at `at` of the padded row `row` (planes of `stride` floats).
    #[inline(always)]
    pub fn load(row: &[f32], stride: usize, at: usize) -> Self {
        let depth: L = load(&row[DEPTH * stride..], at);
        Self {
            depth,
            scale: max(depth, L::splat(1e-6)),
            normal: load3(row, NORMAL, stride, at),
        }
    }
}

/// The weighted sum and the sum of weights over the taps of a vector of centres. `tap(k)` gives
/// tap k's (row, index) in the padded rows: its depth, normal and the values of the
/// `values` planes there.
#[inline(always)]
pub(super) fn filter<'a, L: Row>(
    kernel: &Kernel,
    centre: &Centre<L>,
    values: usize,
    stride: usize,
    tap: impl Fn(usize) -> (&'a [f32], usize),
) -> [L; 3] {
    let mut sum = [L::splat(0.0); 3];
    let mut weight = L::splat(0.0);
    let inv_2sd = L::splat(kernel.inv_2sd);
    for (k, &spatial) in kernel.spatial.iter().enumerate() {
        let (row, at) = tap(k);
        let depth: L = load(&row[DEPTH * stride..], at);
        let normal = load3::<L>(row, NORMAL, stride, at);
        // NaN where the tap has no surface (or lies in the padding): weight 0.
        let surface = depth.le(L::splat(f32::INFINITY));
        let dz = (depth - centre.depth) / centre.scale;
        let mut wn = max(dot(centre.normal, normal), L::splat(0.0));
        for _ in 0..kernel.normal_squarings {
            wn = wn * wn;
        }
        let wq = L::splat(spatial) * wn * exp(-dz * dz * inv_2sd);
        let wq = L::select(surface, wq, L::splat(0.0));
        let v = load3::<L>(row, values, stride, at);
        sum = [sum[0] + v[0] * wq, sum[1] + v[1] * wq, sum[2] + v[2] * wq];
        weight = weight + wq;
    }
    [sum[0] / weight, sum[1] / weight, sum[2] / weight]
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use slc_bounds::lanes_avx::A8;
    use slc_bounds::lanes_avx512::A16;
    use slc_core::rng::uniform;

    /// The filtered values of the `L::N` centres from `at` (the three planes, one after the
    /// other), taps from `at - 3` on.
    #[inline(always)]
    fn run<L: Row>(kernel: &Kernel, row: &[f32], stride: usize, at: usize) -> Vec<f32> {
        let centre = Centre::<L>::load(row, stride, at);
        let mut out = vec![0.0; 3 * L::N];
        for (c, v) in filter(kernel, &centre, 4, stride, |k| (row, at - 3 + k))
            .into_iter()
            .enumerate()
        {
            v.store(&mut out[c * L::N..]);
        }
        out
    }

    #[target_feature(enable = "avx2")]
    fn avx2(kernel: &Kernel, row: &[f32], stride: usize, at: usize) -> Vec<f32> {
        run::<A8>(kernel, row, stride, at)
    }

    #[target_feature(enable = "avx512f")]
    fn avx512(kernel: &Kernel, row: &[f32], stride: usize, at: usize) -> Vec<f32> {
        run::<A16>(kernel, row, stride, at)
    }

    /// The AVX2 and AVX-512 lanes and the plain arrays (CPUs without AVX2) agree bit for bit,
    /// NaN centres and taps included.
    #[test]
    fn every_lane_type_gives_the_same_bits() {
        let stride = 48;
        let kernel = Kernel {
            spatial: vec![0.3, 0.7, 0.9, 1.0, 0.9, 0.7, 0.3],
            inv_2sd: 200.0,
            normal_squarings: 5,
        };
        let mut row: Vec<f32> = (0..7 * stride as u32)
            .map(|i| uniform(3, i, 0, 0))
            .collect();
        row[5] = f32::NAN;
        row[20] = f32::NAN;
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let (has_avx2, has_avx512) = (
            std::arch::is_x86_feature_detected!("avx2"),
            std::arch::is_x86_feature_detected!("avx512f"),
        );
        for at in 3..stride - 11 {
            let arrays = run::<F8>(&kernel, &row, stride, at);
            if has_avx2 {
                // SAFETY: the CPU supports AVX2, checked above.
                let lanes = unsafe { avx2(&kernel, &row, stride, at) };
                assert_eq!(bits(&arrays), bits(&lanes), "AVX2 at {at}");
            }
            if has_avx512 && at + 8 < stride - 11 {
                // SAFETY: the CPU supports AVX-512F, checked above.
                let lanes = unsafe { avx512(&kernel, &row, stride, at) };
                let next = run::<F8>(&kernel, &row, stride, at + 8);
                for c in 0..3 {
                    let want = [&arrays[8 * c..8 * c + 8], &next[8 * c..8 * c + 8]].concat();
                    assert_eq!(
                        bits(&want),
                        bits(&lanes[16 * c..16 * c + 16]),
                        "AVX-512 at {at}"
                    );
                }
            }
        }
    }
}
