//! Depth clusters of a tile: Modified HalfZ (Stewart, "Compute-based tiled culling", GPU
//! Pro 6; paper section 5.1) or exponential depth slices (clustered shading, paper section 7).
use crate::view::CullView;
use glam::Vec3;
use rayon::prelude::*;

/// Most clusters a tile can have: one per exponential depth slice.
pub(crate) const MAX_CLUSTERS: usize = 32;

/// A G-buffer sample of a tile: its pixel index, view depth and (once split) its cluster.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sample {
    pub pixel: u32,
    pub z: f64,
    pub cluster: u8,
}

/// How a tile's samples are split by depth. One per cull, read in place by every tile, so
/// the slices' starts are kept inline rather than boxed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub(crate) enum DepthSplit {
    /// Modified HalfZ: half_z = (z_min + z_max) / 2; samples with z < half_z form the near
    /// cluster [z_min, max z < half_z], the others the far cluster [min z >= half_z, z_max].
    HalfZ,
    /// [`MAX_CLUSTERS`] slices growing exponentially from `near` (slice k holds depths in
    /// near · ratio^(k/32) .. near · ratio^((k+1)/32)); `scale` = 32 / ln(ratio). The slice
    /// of a depth z is floor(ln(z / near) · scale), clamped to 0..=31; `starts[k]` is the
    /// smallest z / near of slice k (`starts[0]` = 0, +∞ for a slice no depth reaches), so
    /// that the slice is found by comparisons instead of a logarithm ([`Self::key`]).
    Slices {
        near: f64,
        scale: f64,
        starts: [f64; MAX_CLUSTERS],
    },
}

impl DepthSplit {
    /// Exponential slices spanning `[near, far]`, the depth range of the samples to split.
    /// Each slice's start is found by bisection over the f64 values with the slice formula
    /// itself ([`slice_of`]), so the comparisons of [`Self::key`] give the formula's slice.
    pub(crate) fn slices(near: f64, far: f64) -> Self {
        let log_ratio = (far / near).ln();
        let scale = if log_ratio > 0.0 {
            MAX_CLUSTERS as f64 / log_ratio
        } else {
            0.0
        };
        let mut starts = [0.0; MAX_CLUSTERS];
        for (k, start) in starts.iter_mut().enumerate().skip(1) {
            *start = if slice_of(f64::MAX, scale) < k {
                f64::INFINITY
            } else {
                // The smallest x >= 0 with slice_of(x) >= k: positive f64 ascend as their bits.
                let (mut lo, mut hi) = (0u64, f64::MAX.to_bits());
                while hi - lo > 1 {
                    let mid = lo + (hi - lo) / 2;
                    if slice_of(f64::from_bits(mid), scale) >= k {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                f64::from_bits(hi)
            };
        }
        Self::Slices {
            near,
            scale,
            starts,
        }
    }

    /// Assigns each sample its cluster and returns each cluster's depth range [lo, hi] (the
    /// extremes of its samples), in order of depth; empty clusters are dropped and the
    /// clusters numbered consecutively. `samples` must not be empty.
    pub(crate) fn split(&self, samples: &mut [Sample], ranges: &mut Vec<[f64; 2]>) {
        let (lo, hi) = samples
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                (lo.min(s.z), hi.max(s.z))
            });
        let mut slots = [[f64::INFINITY, f64::NEG_INFINITY]; MAX_CLUSTERS];
        for s in samples.iter_mut() {
            let key = self.key(s.z, lo, hi);
            s.cluster = key as u8;
            slots[key] = [slots[key][0].min(s.z), slots[key][1].max(s.z)];
        }
        // Renumber the occupied slots 0, 1, ... in depth order.
        let mut renumber = [0u8; MAX_CLUSTERS];
        ranges.clear();
        for (key, slot) in slots.iter().enumerate() {
            if slot[0] <= slot[1] {
                renumber[key] = ranges.len() as u8;
                ranges.push(*slot);
            }
        }
        for s in samples.iter_mut() {
            s.cluster = renumber[s.cluster as usize];
        }
    }

    /// The slot of depth `z` in a tile whose samples span [lo, hi]. For slices, the last
    /// start not above x = z / near, found by five branch-free comparisons; within 1e-12 of
    /// a start (relative), where a logarithm rounded to within an ulp could still fall on
    /// either side, and for an x that is not finite, the formula itself ([`slice_of`]).
    #[inline]
    fn key(&self, z: f64, lo: f64, hi: f64) -> usize {
        match *self {
            Self::HalfZ => usize::from(z >= 0.5 * (lo + hi)),
            Self::Slices {
                near,
                scale,
                ref starts,
            } => {
                let x = z / near;
                let mut k = 0;
                for step in [16, 8, 4, 2, 1] {
                    k += usize::from(starts[k + step] <= x) * step;
                }
                let next = starts.get(k + 1).copied().unwrap_or(f64::INFINITY);
                let edge = x <= starts[k] * (1.0 + 1e-12) || x >= next * (1.0 - 1e-12);
                if edge || !x.is_finite() {
                    slice_of(x, scale)
                } else {
                    k
                }
            }
        }
    }
}

/// The exponential slice of x = z / near: floor(ln(x) · scale), clamped to 0..=31 (depths
/// below `near` only by rounding go to slice 0, beyond `far` to 31).
#[inline]
fn slice_of(x: f64, scale: f64) -> usize {
    (x.ln() * scale)
        .floor()
        .clamp(0.0, (MAX_CLUSTERS - 1) as f64) as usize
}

/// The smallest and largest view depth z of `positions` with 0 < z < ∞, `None` if there are
/// none: in parallel over chunks, each folded in a plain loop (rayon's per-item reduce and
/// the f64 `min`'s NaN handling cost more than the transform).
pub(crate) fn depth_range(positions: &[Option<Vec3>], view: &CullView) -> Option<(f64, f64)> {
    let (lo, hi) = positions
        .par_chunks(1 << 12)
        .map(|chunk| {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for z in chunk.iter().flatten().map(|p| view.to_view(*p).z) {
                if z > 0.0 && z.is_finite() {
                    lo = if z < lo { z } else { lo };
                    hi = if z > hi { z } else { hi };
                }
            }
            (lo, hi)
        })
        .reduce(
            || (f64::INFINITY, f64::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use slc_core::Camera;

    #[test]
    fn depth_range_spans_the_samples_in_front() {
        let camera = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 1.0).unwrap();
        let view = CullView::new(&camera, 64, 64).unwrap();
        let mut rng = Rng(17);
        let mut positions: Vec<Option<Vec3>> = (0..20_000)
            .map(|i| {
                (i % 7 != 0).then(|| {
                    Vec3::new(
                        rng.range(-50.0, 50.0),
                        rng.range(-50.0, 50.0),
                        rng.range(-50.0, 50.0),
                    )
                })
            })
            .collect();
        positions[5] = Some(Vec3::INFINITY);
        positions[9] = Some(Vec3::NAN);
        let front: Vec<f64> = positions
            .iter()
            .flatten()
            .map(|p| view.to_view(*p).z)
            .filter(|&z| z > 0.0 && z.is_finite())
            .collect();
        let lo = front.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = front.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(front.len() > 1000 && front.len() < 17_000);
        assert_eq!(depth_range(&positions, &view), Some((lo, hi)));
        let behind: Vec<Option<Vec3>> = positions
            .iter()
            .map(|p| p.filter(|p| view.to_view(*p).z <= 0.0))
            .collect();
        assert_eq!(depth_range(&behind, &view), None);
        assert_eq!(depth_range(&[], &view), None);
    }

    fn samples(z: &[f64]) -> Vec<Sample> {
        z.iter()
            .enumerate()
            .map(|(i, &z)| Sample {
                pixel: i as u32,
                z,
                cluster: 0,
            })
            .collect()
    }

    #[test]
    fn half_z_splits_at_the_middle_of_the_range() {
        let mut s = samples(&[1.0, 1.5, 2.9, 3.0, 9.0, 10.0]);
        let mut ranges = Vec::new();
        DepthSplit::HalfZ.split(&mut s, &mut ranges);
        // half_z = 5.5: near [1, 3], far [9, 10].
        assert_eq!(ranges, vec![[1.0, 3.0], [9.0, 10.0]]);
        let clusters: Vec<u8> = s.iter().map(|s| s.cluster).collect();
        assert_eq!(clusters, vec![0, 0, 0, 0, 1, 1]);
    }

    #[test]
    fn half_z_of_a_flat_tile_is_one_cluster() {
        let mut s = samples(&[4.0, 4.0, 4.0]);
        let mut ranges = Vec::new();
        DepthSplit::HalfZ.split(&mut s, &mut ranges);
        assert_eq!(ranges, vec![[4.0, 4.0]]);
        assert!(s.iter().all(|s| s.cluster == 0));
    }

    #[test]
    fn slices_are_exponential_and_every_sample_is_in_its_range() {
        let split = DepthSplit::slices(0.5, 500.0);
        let z: Vec<f64> = (0..400)
            .map(|i| 0.5 * 1000f64.powf(i as f64 / 399.0))
            .collect();
        let mut s = samples(&z);
        let mut ranges = Vec::new();
        split.split(&mut s, &mut ranges);
        assert_eq!(ranges.len(), MAX_CLUSTERS);
        for w in ranges.windows(2) {
            assert!(w[0][1] < w[1][0], "ordered, disjoint");
            // Each slice spans a factor 1000^(1/32) ≈ 1.24.
            assert!(w[1][1] / w[1][0] < 1.25);
        }
        for s in &s {
            let [lo, hi] = ranges[s.cluster as usize];
            assert!(lo <= s.z && s.z <= hi);
        }
        let flat = DepthSplit::slices(2.0, 2.0);
        let mut one = samples(&[2.0, 2.0]);
        flat.split(&mut one, &mut ranges);
        assert_eq!(ranges, vec![[2.0, 2.0]]);
    }

    /// The comparisons give the logarithm's slice for every depth: random depths over
    /// ranges from flat to 1e300 wide, and the depths at and around every slice start.
    #[test]
    fn slice_keys_by_comparison_equal_the_formula() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut unit = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut checked = 0;
        for (near, far) in [
            (1.0, 1.0),
            (0.5, 0.5 + 1e-12),
            (0.1, 1.0),
            (0.5, 500.0),
            (1e-3, 1e6),
            (1e-300, 1e300),
            (3.7, 3.7 * (1.0 + 1e-9)),
        ] {
            let split = DepthSplit::slices(near, far);
            let DepthSplit::Slices { scale, starts, .. } = split else {
                unreachable!()
            };
            let mut depths: Vec<f64> = (0..20_000)
                .map(|_| near * (far / near).powf(unit()))
                .collect();
            for &start in starts.iter().filter(|s| s.is_finite() && **s > 0.0) {
                let mut z = start * near;
                for _ in 0..4 {
                    z = z.next_down();
                }
                for _ in 0..9 {
                    depths.push(z);
                    z = z.next_up();
                }
            }
            depths.extend([near, far, near.next_down(), far.next_up()]);
            for z in depths {
                assert_eq!(
                    split.key(z, near, far),
                    slice_of(z / near, scale),
                    "z {z} in [{near}, {far}]"
                );
                checked += 1;
            }
        }
        assert!(checked > 140_000);
    }
}
