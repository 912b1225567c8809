//! The early exits of whole groups of VPLs as structure-of-arrays chunks of eight, tested
//! against one pixel at a time (the yardstick of `slc bench`'s ceiling; the shading and the
//! metrics test one VPL against eight pixels instead, [`crate::ReceiverChunks`]): eight pairs per
//! test in 256-bit lanes where the CPU has AVX2, the same arithmetic as [`VplReach`] lane for
//! lane (so the same pairs pass), and only the VPLs that pass are handed on. The roulette
//! (p > ξ, the `acceptance` module) is evaluated for a chunk only when one of its lanes
//! passes the bound and sign tests.
use crate::acceptance::Acceptance;
use crate::reach::{Reach, VplReach};
use glam::Vec3;
use slc_bounds::lanes::{Lanes8, Real, F8};
use slc_core::Vpl;

/// Eight VPLs: their positions q, their early exits and their indices. Lanes past the end of
/// a group have limit −1 and never pass.
#[derive(Clone, Copy, Debug)]
struct Chunk {
    position: [F8; 3],
    reach: Reach<F8>,
    acceptance: Acceptance<F8>,
    index: [u32; 8],
}

/// Groups of VPLs (each a slice of VPL indices) as chunks of eight.
#[derive(Clone, Debug, Default)]
pub struct ReachChunks {
    chunks: Vec<Chunk>,
    /// Group g is `chunks[offsets[g]..offsets[g + 1]]`.
    offsets: Vec<usize>,
}

impl ReachChunks {
    /// The chunks of `groups`, indices into `vpls` and `reach` (one [`VplReach`] per VPL).
    pub fn new<'a>(
        vpls: &[Vpl],
        reach: &[VplReach],
        groups: impl IntoIterator<Item = &'a [u32]>,
    ) -> Self {
        let mut out = Self::default();
        out.refill(vpls, reach, groups);
        out
    }

    /// Replaces the groups by `groups`, as [`Self::new`], keeping the allocations.
    pub fn refill<'a>(
        &mut self,
        vpls: &[Vpl],
        reach: &[VplReach],
        groups: impl IntoIterator<Item = &'a [u32]>,
    ) {
        self.chunks.clear();
        self.offsets.clear();
        self.offsets.push(0);
        for group in groups {
            for eight in group.chunks(8) {
                self.chunks.push(chunk(vpls, reach, eight));
            }
            self.offsets.push(self.chunks.len());
        }
    }

    /// Calls `pass` with the index of every VPL of group `group` that may contribute at the
    /// receiver at `x` with unit normal `normal` ([`VplReach::may_contribute`]), in the
    /// group's order; with `normal` `None`, every one the roulette may accept
    /// ([`VplReach::may_accept`]).
    #[inline]
    pub fn for_each_passing(
        &self,
        group: usize,
        x: Vec3,
        normal: Option<Vec3>,
        mut pass: impl FnMut(u32),
    ) {
        for c in &self.chunks[self.offsets[group]..self.offsets[group + 1]] {
            let mut bits = passing(c, x, normal);
            while bits != 0 {
                pass(c.index[bits.trailing_zeros() as usize]);
                bits &= bits - 1;
            }
        }
    }
}

/// The chunk of up to eight VPLs `indices`.
fn chunk(vpls: &[Vpl], reach: &[VplReach], indices: &[u32]) -> Chunk {
    let never = Reach {
        normal: [0.0; 3],
        stretch: [0.0; 9],
        center: [0.0; 3],
        limit: -1.0,
    };
    let mut c = Chunk {
        position: [F8::splat(0.0); 3],
        reach: Reach {
            normal: [F8::splat(0.0); 3],
            stretch: [F8::splat(0.0); 9],
            center: [F8::splat(0.0); 3],
            limit: F8::splat(-1.0),
        },
        acceptance: Acceptance::lanes(core::array::from_fn(|lane| {
            indices.get(lane).map_or(&Acceptance::<f32>::NEVER, |&i| {
                &reach[i as usize].acceptance
            })
        })),
        index: [0; 8],
    };
    for lane in 0..8 {
        let (q, r, i) = match indices.get(lane) {
            Some(&i) => (
                vpls[i as usize].position.to_array(),
                &reach[i as usize].reach,
                i,
            ),
            None => ([0.0; 3], &never, 0),
        };
        let fields = (c.position.iter_mut().zip(q))
            .chain(c.reach.normal.iter_mut().zip(r.normal))
            .chain(c.reach.center.iter_mut().zip(r.center))
            .chain(c.reach.stretch.iter_mut().zip(r.stretch));
        for (lanes, v) in fields {
            lanes.0[lane] = v;
        }
        c.reach.limit.0[lane] = r.limit;
        c.index[lane] = i;
    }
    c
}

/// The lanes of `c` that pass at `x` (bit k for lane k), in AVX registers where the CPU has
/// AVX2.
#[inline]
fn passing(c: &Chunk, x: Vec3, normal: Option<Vec3>) -> u8 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { passing_avx2(c, x, normal) };
    }
    passing_lanes::<F8>(c, x, normal)
}

/// [`passing_lanes`] in AVX registers (the same IEEE operations).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn passing_avx2(c: &Chunk, x: Vec3, normal: Option<Vec3>) -> u8 {
    passing_lanes::<slc_bounds::lanes_avx::A8>(c, x, normal)
}

#[inline(always)]
fn passing_lanes<L: Lanes8>(c: &Chunk, x: Vec3, normal: Option<Vec3>) -> u8 {
    let reach = c.reach.load::<L>();
    // d = x − q, each lane exactly as the shader forms `g.position − vpl.position`.
    let d = [
        L::splat(x.x) - L::load(&c.position[0]),
        L::splat(x.y) - L::load(&c.position[1]),
        L::splat(x.z) - L::load(&c.position[2]),
    ];
    let bits = L::bits(match normal {
        Some(n) => reach.may_contribute(d, [L::splat(n.x), L::splat(n.y), L::splat(n.z)]),
        None => reach.may_accept(d),
    });
    if bits == 0 {
        return 0;
    }
    bits & L::bits(c.acceptance.load::<L>().may_accept(reach.normal, d))
}
