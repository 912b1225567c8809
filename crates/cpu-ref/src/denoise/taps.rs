//! The filter's taps, eight centre pixels at a time: each lane runs the operations of the
//! scalar filter in the same order (the relative depth difference divided, the normal
//! weight squared `normal_squarings` times, the spatial weight times the normal weight
//! times the depth weight, the sums in tap order), so a lane's result differs from the
//! scalar filter's only by the exponential, here `slc_bounds::lanes::exp` (within 2 ulp)
//! instead of the platform's `expf`.
use super::guide::{DEPTH, NORMAL};
use slc_bounds::lanes::{dot, exp, max, Lanes8, Real, F8};

/// What the taps of one filter pass share.
#[derive(Clone, Debug)]
pub(super) struct Kernel {
    /// The spatial Gaussian of each tap, from −radius to radius.
    pub spatial: Vec<f32>,
    /// 1 / (2 σ_depth²).
    pub inv_2sd: f32,
    pub normal_squarings: u32,
}

/// Eight floats of `plane` from `at`.
#[inline(always)]
pub(super) fn load<L: Lanes8>(plane: &[f32], at: usize) -> L {
    let mut v = F8([0.0; 8]);
    v.0.copy_from_slice(&plane[at..at + 8]);
    L::load(&v)
}

/// Eight floats at `at` of each of the three planes from `first` on.
#[inline(always)]
fn load3<L: Lanes8>(row: &[f32], first: usize, stride: usize, at: usize) -> [L; 3] {
    [
        load(&row[first * stride..], at),
        load(&row[(first + 1) * stride..], at),
        load(&row[(first + 2) * stride..], at),
    ]
}

/// The guide of eight centre pixels.
#[derive(Clone, Copy)]
pub(super) struct Centre<L: Real> {
    pub depth: L,
    /// max(depth, 1e-6): what the depth difference is divided by.
    pub scale: L,
    pub normal: [L; 3],
}

impl<L: Lanes8> Centre<L> {
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

/// The weighted sum and the sum of weights over the taps of eight centres. `tap(k)` gives
/// tap k's (row, index) in the padded rows: its depth, normal and the values of the
/// `values` planes there.
#[inline(always)]
pub(super) fn filter<'a, L: Lanes8>(
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
    use slc_core::rng::uniform;

    #[target_feature(enable = "avx2")]
    fn avx(kernel: &Kernel, row: &[f32], stride: usize, at: usize) -> [F8; 3] {
        let centre = Centre::<A8>::load(row, stride, at);
        filter(kernel, &centre, 4, stride, |k| (row, at - 3 + k)).map(A8::store)
    }

    /// The AVX2 lanes and the plain arrays (CPUs without AVX2) agree bit for bit.
    #[test]
    fn avx_lanes_equal_the_array_lanes() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let stride = 32;
        let kernel = Kernel {
            spatial: vec![0.3, 0.7, 0.9, 1.0, 0.9, 0.7, 0.3],
            inv_2sd: 200.0,
            normal_squarings: 5,
        };
        let mut row: Vec<f32> = (0..7 * stride as u32)
            .map(|i| uniform(3, i, 0, 0))
            .collect();
        row[5] = f32::NAN;
        for at in 3..stride - 11 {
            let centre = Centre::<F8>::load(&row, stride, at);
            let arrays = filter(&kernel, &centre, 4, stride, |k| (&row[..], at - 3 + k));
            // SAFETY: the CPU supports AVX2, checked above.
            let lanes = unsafe { avx(&kernel, &row, stride, at) };
            let bits = |v: [F8; 3]| v.map(|c| c.0.map(f32::to_bits));
            assert_eq!(bits(arrays), bits(lanes), "at {at}");
        }
    }
}
