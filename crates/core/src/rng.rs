//! Counter-based random numbers: a pure hash of (seed, index, stream), so that any backend
//! (CPU threads in any order, WGSL shaders) reproduces every number bit for bit.
//!
//! Only wrapping 32-bit multiplies, additions, xors and shifts are used; the WGSL twin lives in
//! the GPU backend and must stay in sync with this file.

/// Streams keep the numbers of different uses independent for the same (seed, index).
pub mod stream {
    /// The Russian-roulette number xi of a VPL (paper eq. 3), index = VPL index.
    pub const XI: u32 = 0;
    /// Sub-texel jitter of reflective-shadow-map rays, index = texel index.
    pub const RSM_JITTER: u32 = 1;
    /// Per-pixel samples (camera jitter, path sampling), index = pixel index.
    pub const PIXEL: u32 = 2;
    /// The interleaved-sampling subregion of a VPL, index = VPL id.
    pub const INTERLEAVE: u32 = 3;
    /// The random shift of a set of VSGL or resampled-VPL sample points (VSGL section 4.2),
    /// index = the set (lights, or the camera side of the bidirectional importance).
    pub const VSGL_POINTS: u32 = 4;
    /// The caster points of imperfect shadow maps (triangle choice and barycentrics), index =
    /// point.
    pub const ISM_CASTERS: u32 = 5;
}

/// The PCG hash of Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020.
#[inline]
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// Hash of (seed, index, stream, counter): the `counter`-th number of `stream` for item `index`.
#[inline]
pub fn hash4(seed: u32, index: u32, stream: u32, counter: u32) -> u32 {
    let a = pcg_hash(seed ^ pcg_hash(stream.wrapping_mul(0x9E37_79B9) ^ counter));
    pcg_hash(a ^ pcg_hash(index))
}

/// Maps a hash to a float strictly inside (0, 1): the 23 high bits plus one half, times 2^-23,
/// so the smallest value is 2^-24 and the largest 1 - 2^-24, both exact in f32 (with 24 bits
/// the largest value would round up to 1).
#[inline]
pub fn to_unit_open(h: u32) -> f32 {
    ((h >> 9) as f32 + 0.5) * (1.0 / 8_388_608.0)
}

/// The uniform number in (0, 1) for (seed, index, stream, counter).
#[inline]
pub fn uniform(seed: u32, index: u32, stream: u32, counter: u32) -> f32 {
    to_unit_open(hash4(seed, index, stream, counter))
}

/// The Russian-roulette number xi of VPL `index` (paper eq. 3): one per light, shared by
/// every shading point.
#[inline]
pub fn vpl_xi(seed: u32, index: u32) -> f32 {
    uniform(seed, index, stream::XI, 0)
}

/// A sequence of uniform numbers for one item (a pixel, a texel): successive calls advance the
/// counter, so the sequence is the same whatever thread draws it.
#[derive(Clone, Debug)]
pub struct Sequence {
    seed: u32,
    index: u32,
    stream: u32,
    counter: u32,
}

impl Sequence {
    pub fn new(seed: u32, index: u32, stream: u32, first: u32) -> Self {
        Self {
            seed,
            index,
            stream,
            counter: first,
        }
    }

    /// The next number in (0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        let u = uniform(self.seed, self.index, self.stream, self.counter);
        self.counter = self.counter.wrapping_add(1);
        u
    }

    /// The next two numbers.
    #[inline]
    pub fn next_2d(&mut self) -> (f32, f32) {
        (self.next_f32(), self.next_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg_hash_known_values() {
        // Values computed by hand from the published algorithm; the WGSL twin is tested
        // against the same numbers.
        assert_eq!(pcg_hash(0), 129_708_002);
        assert_eq!(pcg_hash(1), 2_831_084_092);
    }

    #[test]
    fn uniform_is_open_interval_and_roughly_uniform() {
        let n = 200_000u32;
        let mut buckets = [0u32; 10];
        let mut sum = 0.0f64;
        for i in 0..n {
            let u = vpl_xi(7, i);
            assert!(u > 0.0 && u < 1.0);
            buckets[(u * 10.0) as usize] += 1;
            sum += u as f64;
        }
        let mean = sum / n as f64;
        // Standard error of the mean of U(0,1) is 1/sqrt(12 n) ~ 6.5e-4: 5 sigma.
        assert!((mean - 0.5).abs() < 3.3e-3, "mean {mean}");
        // Chi-square with 9 degrees of freedom: 27.9 is the 0.999 quantile.
        let expected = n as f64 / 10.0;
        let chi2: f64 = buckets
            .iter()
            .map(|&b| (b as f64 - expected).powi(2) / expected)
            .sum();
        assert!(chi2 < 27.9, "chi2 {chi2}");
    }

    #[test]
    fn extremes_of_the_mapping() {
        assert_eq!(to_unit_open(0), 0.5 / 8_388_608.0);
        assert_eq!(to_unit_open(u32::MAX), 1.0 - 0.5 / 8_388_608.0);
    }

    #[test]
    fn seeds_and_streams_differ() {
        assert_ne!(vpl_xi(1, 5), vpl_xi(2, 5));
        assert_ne!(
            uniform(1, 5, stream::XI, 0),
            uniform(1, 5, stream::PIXEL, 0)
        );
        let mut s = Sequence::new(3, 9, stream::PIXEL, 0);
        let a = s.next_f32();
        assert_eq!(a, uniform(3, 9, stream::PIXEL, 0));
        assert_eq!(s.next_f32(), uniform(3, 9, stream::PIXEL, 1));
    }
}
