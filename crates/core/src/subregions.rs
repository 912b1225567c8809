//! [`Interleaving`]'s subregion arithmetic for one image, without a division per VPL: a
//! scatter that places a million VPLs a frame (`slc_cull`'s `binned`) waited on the
//! divisions by K and K² of [`Interleaving::vpl_subregion`] and
//! [`Interleaving::subregion_size`] for every VPL it placed.
use crate::culling::Interleaving;
use crate::rng::{hash4, stream};

/// The subregions of an interleaving for a `width` x `height` image: the same values as
/// [`Interleaving::vpl_subregion`] and [`Interleaving::subregion_size`], with the divisions
/// by K and K² done as multiplications by their precomputed reciprocals (`Divisor`) and
/// each image side split once into K q + r; and x / K in f64 ([`Subregions::per_k`]).
#[derive(Clone, Copy, Debug)]
pub struct Subregions {
    seed: u32,
    k: Divisor,
    /// 1 / K where K is a power of two: a division by K is then this product, bit for bit.
    inv_k: Option<f64>,
    subregions: Divisor,
    /// Width and height as K q + r, [q, r]: subregion s's side is q + 1 for s < r, else q.
    sides: [[u32; 2]; 2],
}

impl Subregions {
    /// The subregions of `interleaving` for a `width` x `height` image; `None` for K = 0 or
    /// K² beyond u32.
    pub fn new(interleaving: Interleaving, width: u32, height: u32) -> Option<Self> {
        let k = Divisor::new(interleaving.k)?;
        let subregions = Divisor::new(interleaving.k.checked_mul(interleaving.k)?)?;
        let side = |n: u32| [k.div(n), k.rem(n)];
        Some(Self {
            seed: interleaving.seed,
            k,
            inv_k: k.d.is_power_of_two().then(|| 1.0 / f64::from(k.d)),
            subregions,
            sides: [side(width), side(height)],
        })
    }

    /// The subregion `[sx, sy]` of VPL `vpl_id` ([`Interleaving::vpl_subregion`] is
    /// sy K + sx).
    #[inline]
    pub fn of_vpl(&self, vpl_id: u32) -> [u32; 2] {
        // With K = 1 the remainder by K² = 1 is 0, as `vpl_subregion`'s is.
        let sub = self
            .subregions
            .rem(hash4(self.seed, vpl_id, stream::INTERLEAVE, 0));
        [self.k.rem(sub), self.k.div(sub)]
    }

    /// The size of subregion `[sx, sy]`'s image ([`Interleaving::subregion_size`]), for
    /// sx, sy below K.
    #[inline]
    pub fn size(&self, subregion: [u32; 2]) -> [u32; 2] {
        // n − s = K q + (r − s): for s < r one pixel more than q, for r ≤ s < K exactly q.
        let side = |[q, r]: [u32; 2], s: u32| q + u32::from(s < r);
        [
            side(self.sides[0], subregion[0]),
            side(self.sides[1], subregion[1]),
        ]
    }

    /// x / K in f64, bit for bit: x times 1 / K where K is a power of two (K = 8 by default;
    /// both are exact products of x and 2⁻ʲ, rounded once), else the division.
    #[inline]
    pub fn per_k(&self, x: f64) -> f64 {
        match self.per_k_operation() {
            PerK::Times(inv) => x * inv,
            PerK::Over(k) => x / k,
        }
    }

    /// The one operation [`Self::per_k`] makes, for code that repeats it in lanes.
    #[inline]
    pub fn per_k_operation(&self) -> PerK {
        match self.inv_k {
            Some(inv) => PerK::Times(inv),
            None => PerK::Over(f64::from(self.k.d)),
        }
    }
}

/// How [`Subregions::per_k`] divides x by K: times 1 / K (K a power of two) or over K.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PerK {
    Times(f64),
    Over(f64),
}

/// Division and remainder by a fixed u32 d ≥ 1 as multiplications: with M = ⌈2⁶⁴ / d⌉
/// (mod 2⁶⁴), n / d = ⌊M n / 2⁶⁴⌋ and n mod d = ⌊(M n mod 2⁶⁴) d / 2⁶⁴⌋ for every u32 n
/// (Lemire, Kaser and Kurz, "Faster remainder by direct computation", 2019, eq. 1 and
/// Theorem 1 with N = 32, F = 64). For d = 1, M wraps to 0: the remainder is still right
/// (0) and the quotient is n.
#[derive(Clone, Copy, Debug)]
struct Divisor {
    d: u32,
    m: u64,
}

impl Divisor {
    fn new(d: u32) -> Option<Self> {
        (d > 0).then(|| Self {
            d,
            m: (u64::MAX / u64::from(d)).wrapping_add(1),
        })
    }

    #[inline]
    fn div(self, n: u32) -> u32 {
        if self.m == 0 {
            return n;
        }
        ((u128::from(self.m) * u128::from(n)) >> 64) as u32
    }

    #[inline]
    fn rem(self, n: u32) -> u32 {
        let low = self.m.wrapping_mul(u64::from(n));
        ((u128::from(low) * u128::from(self.d)) >> 64) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Quotients and remainders equal the hardware's for divisors 1 to 2000 and the largest
    /// ones, at dividends near 0, near multiples of the divisor, near powers of two, near
    /// u32::MAX and spread pseudo-randomly over all of u32.
    #[test]
    fn divisions_are_exact() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u32
        };
        let divisors = (1..=2000).chain([
            1 << 20,
            (1 << 20) + 1,
            (1 << 31) - 1,
            1 << 31,
            (1 << 31) + 1,
            u32::MAX - 1,
            u32::MAX,
        ]);
        for d in divisors {
            let div = Divisor::new(d).unwrap();
            let near = |n: u32| (0..3).flat_map(move |e| [n.wrapping_sub(e), n.wrapping_add(e)]);
            let dividends = (0..64)
                .chain((1..40).flat_map(|m| near(d.wrapping_mul(m))))
                .chain((0..32).flat_map(|p| near(1 << p)))
                .chain(near(u32::MAX))
                .chain((0..200).map(|_| next()))
                .collect::<Vec<_>>();
            for n in dividends {
                assert_eq!((div.div(n), div.rem(n)), (n / d, n % d), "{n} / {d}");
            }
        }
        assert!(Divisor::new(0).is_none());
    }

    /// The subregions of VPLs and the sizes of subregion images are
    /// [`Interleaving::vpl_subregion`]'s and [`Interleaving::subregion_size`]'s, for K from
    /// 1 to the culling's largest (1024), images smaller and larger than K; x / K is the
    /// division's, bit for bit.
    #[test]
    fn subregions_are_the_interleavings() {
        for k in [1, 2, 3, 7, 8, 13, 16, 64, 100, 1023, 1024] {
            for seed in [0, 7, 0xDEAD_BEEF] {
                let il = Interleaving { k, seed };
                for (w, h) in [(1, 1), (5, 3), (480, 270), (1920, 1080), (4097, 33)] {
                    let s = Subregions::new(il, w, h).unwrap();
                    for id in (0..2000).chain([u32::MAX - 1, u32::MAX]) {
                        let sub = il.vpl_subregion(id);
                        assert_eq!(s.of_vpl(id), [sub % k, sub / k], "K {k}, id {id}");
                    }
                    let step = (k / 37).max(1);
                    for sx in (0..k).step_by(step as usize).chain([k - 1]) {
                        for sy in [0, k / 2, k - 1] {
                            assert_eq!(
                                s.size([sx, sy]),
                                il.subregion_size(w, h, [sx, sy]),
                                "K {k}, {w}x{h}, [{sx}, {sy}]"
                            );
                        }
                    }
                }
            }
        }
        assert!(Subregions::new(Interleaving { k: 0, seed: 0 }, 4, 4).is_none());
        // x / K bit for bit, for K powers of two and not, at values from subnormal to huge.
        let mut x = 1e-310f64;
        while x < 1e300 {
            for k in [1, 2, 3, 8, 64, 100, 1024] {
                let s = Subregions::new(Interleaving { k, seed: 0 }, 4, 4).unwrap();
                for v in [x, -x, x * 1.2345, 0.5 * x + 0.25] {
                    assert_eq!(
                        s.per_k(v).to_bits(),
                        (v / f64::from(k)).to_bits(),
                        "{v} / {k}"
                    );
                }
            }
            x *= 3.7;
        }
        assert!(Subregions::new(
            Interleaving {
                k: 1 << 16,
                seed: 0
            },
            4,
            4
        )
        .is_none());
    }
}
