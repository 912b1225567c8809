//! The early exits of one VPL against a group of receivers (the pixels of a tile that share
//! light lists in the shading, every pixel of a tile in the metrics), eight receivers per
//! test: the transpose of [`crate::ReachChunks`]. The VPL's constants are broadcast to every
//! lane once and each lane is a pixel, so a VPL whose bound covers a patch of the tile fills
//! whole chunks with passing receivers, and the roulette (the `acceptance` module) runs on far
//! fewer chunks than when the lanes are VPLs. Each lane performs the same IEEE operations as
//! [`VplReach::may_contribute`], so the same pairs pass.
//!
//! Before any pair, each VPL is tested against the box of the receivers with its bound of p
//! over boxes (`slc_bounds::BoxBound` in f32, eight VPLs per test: [`VplReach::box_may_exceed_xi`]):
//! it bounds every factor of the intensity over the box at once (the Fresnel factor and D over
//! the cone of directions to the box, G1(ωo) and the cosine by the tangent plane), so it drops
//! many VPLs whose spheroid reaches the box but whose roulette accepts no receiver in it
//! (at 1920x1080 on Sponza about half the VPL-window pairs, and with them 38% of the chunk
//! tests and 52% of the roulettes).
//!
//! The receivers may belong to up to 32 sets (the light lists of a tile's depth clusters),
//! each VPL tested only against the sets it is listed for: the lists of a tile share their
//! chunks, which stay full however short each list is.
use crate::acceptance::Acceptance;
use crate::reach::{Reach, VplReach};
use glam::Vec3;
use slc_bounds::lanes::{load_all, splat_all, store_all, Lanes8, Real, F8};
use slc_bounds::BoxBoundLanes;

/// Most receiver sets a [`ReceiverChunks`] holds: the bits of a `u32` membership mask.
pub const MAX_SETS: usize = 32;

/// Eight receivers: their positions x and unit normals, which lanes hold one, each lane's
/// set and the sets present.
#[derive(Clone, Copy, Debug)]
struct Receivers {
    position: [F8; 3],
    normal: [F8; 3],
    valid: u8,
    set: [u8; 8],
    sets: u32,
}

impl Receivers {
    /// The lanes holding a receiver of one of the sets in `sets` (bit s: set s).
    #[inline(always)]
    fn members(&self, sets: u32) -> u8 {
        if self.sets & !sets == 0 {
            return self.valid;
        }
        (0..8).fold(0, |bits, lane| {
            bits | (u8::from(sets >> self.set[lane] & 1 == 1) << lane)
        }) & self.valid
    }
}

/// A group of receivers as chunks of eight, in the order given; receiver i is lane i mod 8
/// of chunk i / 8.
#[derive(Clone, Debug)]
pub struct ReceiverChunks {
    chunks: Vec<Receivers>,
    /// The box of the receivers' positions.
    lo: Vec3,
    hi: Vec3,
    /// Per set, the chunks `[first, end)` that hold its receivers (empty: `[u32::MAX, 0]`),
    /// and the sets that have receivers.
    spans: [[u32; 2]; MAX_SETS],
    present: u32,
}

impl Default for ReceiverChunks {
    fn default() -> Self {
        Self {
            chunks: Vec::new(),
            lo: Vec3::INFINITY,
            hi: Vec3::NEG_INFINITY,
            spans: [[u32::MAX, 0]; MAX_SETS],
            present: 0,
        }
    }
}

impl ReceiverChunks {
    /// Replaces the receivers by `receivers` (position x, unit normal), all in set 0, keeping
    /// the allocation.
    pub fn refill(&mut self, receivers: impl IntoIterator<Item = (Vec3, Vec3)>) {
        self.refill_sets(receivers.into_iter().map(|(x, n)| (x, n, 0)));
    }

    /// Replaces the receivers by `receivers` (position x, unit normal, set), keeping the
    /// allocation. A VPL is tested only against the chunks from the first to the last that
    /// hold one of its sets, so receivers grouped by set keep that range short.
    ///
    /// # Panics
    /// If a set is not below [`MAX_SETS`].
    pub fn refill_sets(&mut self, receivers: impl IntoIterator<Item = (Vec3, Vec3, u8)>) {
        self.chunks.clear();
        (self.lo, self.hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        self.spans = [[u32::MAX, 0]; MAX_SETS];
        self.present = 0;
        let mut lane = 8;
        for (x, n, set) in receivers {
            assert!(
                usize::from(set) < MAX_SETS,
                "receiver set {set} of at most 32"
            );
            (self.lo, self.hi) = (self.lo.min(x), self.hi.max(x));
            if lane == 8 {
                // Lanes past the end repeat the chunk's first receiver (finite arithmetic),
                // and `valid` masks them out.
                self.chunks.push(Receivers {
                    position: [x.x, x.y, x.z].map(F8::splat),
                    normal: [n.x, n.y, n.z].map(F8::splat),
                    valid: 0,
                    set: [set; 8],
                    sets: 0,
                });
                lane = 0;
            }
            let chunk = self.chunks.len() as u32 - 1;
            let c = self.chunks.last_mut().expect("pushed above");
            for (axis, (p, m)) in [x.x, x.y, x.z].into_iter().zip([n.x, n.y, n.z]).enumerate() {
                c.position[axis].0[lane] = p;
                c.normal[axis].0[lane] = m;
            }
            c.valid |= 1 << lane;
            c.set[lane] = set;
            c.sets |= 1 << set;
            self.present |= 1 << set;
            let span = &mut self.spans[usize::from(set)];
            *span = [span[0].min(chunk), span[1].max(chunk + 1)];
            lane += 1;
        }
    }

    /// The chunks `[first, end)` holding the receivers of the sets in `sets`.
    #[inline(always)]
    fn span(&self, sets: u32) -> (usize, usize) {
        let (mut first, mut end) = (u32::MAX, 0);
        let mut sets = sets & self.present;
        while sets != 0 {
            let [a, b] = self.spans[sets.trailing_zeros() as usize];
            (first, end) = (first.min(a), end.max(b));
            sets &= sets - 1;
        }
        (first as usize, end as usize)
    }
}

/// A chunk of receivers where pairs with a VPL pass, with the roulette's values there.
#[derive(Clone, Copy, Debug)]
pub struct Passing {
    /// The VPL's index.
    pub vpl: u32,
    /// Which chunk of the receivers: receiver i is lane i mod 8 of chunk i / 8.
    pub chunk: usize,
    /// Bit k set where receiver k of the chunk passes.
    pub bits: u8,
    /// Bit k set where lane k's values are the shader's own (see [`Self::exact`]).
    exact: u8,
    l2: F8,
    omega: [F8; 3],
    intensity: [F8; 3],
}

impl Passing {
    /// For a passing receiver k of the chunk: the unit direction ωo from the VPL to it, the
    /// squared distance l² and the VPL's intensity I(ωo) per channel (eq. 4), exactly as the
    /// shader's `vpl_contribution` and `Vpl::intensity` form them (the same IEEE operations
    /// in the same order), where the roulette accepted the pair with those values: a diffuse
    /// VPL, or a glossy one with Schlick's Fresnel and a half vector formed in f32, neither on
    /// a tilted shading normal nor anisotropic. `None` elsewhere: the shader forms them
    /// itself.
    #[inline]
    pub fn exact(&self, k: usize) -> Option<(Vec3, f32, Vec3)> {
        (self.exact & (1 << k) != 0).then(|| {
            let lane = |v: &[F8; 3]| Vec3::new(v[0].0[k], v[1].0[k], v[2].0[k]);
            (lane(&self.omega), self.l2.0[k], lane(&self.intensity))
        })
    }

    /// Bit k set where [`Self::exact`] gives lane k's values.
    #[inline]
    pub fn exact_bits(&self) -> u8 {
        self.exact
    }

    /// ωo, l² and I(ωo) of every lane, the lanes of [`Self::exact`] (the shader's own values
    /// where [`Self::exact_bits`] is set, meaningless elsewhere).
    #[inline]
    pub fn lanes(&self) -> (&[F8; 3], &F8, &[F8; 3]) {
        (&self.omega, &self.l2, &self.intensity)
    }
}

impl ReceiverChunks {
    /// For every VPL of `group` in turn (indices into `reach`, one [`VplReach`] per VPL),
    /// appends to `passing` (cleared first) every chunk of these receivers where a receiver
    /// passes [`VplReach::may_contribute`] with it (the bound, the signs at both ends and the
    /// roulette), or with `normals` false [`VplReach::may_accept`] (the receivers' normals
    /// ignored): VPL by VPL in the group's order, chunk by chunk. A VPL whose bound over boxes
    /// rejects the box of the receivers ([`VplReach::box_may_exceed_xi`]), or whose own bound
    /// or tangent plane leaves the box out (`Reach::box_may_reach`), is passed over after those
    /// tests: the shader accepts no receiver of the box with it (so the lanes of an unmodelled
    /// or ill-conditioned lobe, which the roulette passes on to the shader, go with it).
    pub fn passing(
        &self,
        reach: &[VplReach],
        group: &[u32],
        normals: bool,
        passing: &mut Vec<Passing>,
    ) {
        self.passing_members(
            reach,
            group.iter().map(|&i| (i, u32::MAX)),
            normals,
            passing,
        );
    }

    /// [`Self::passing`] for `members`, each a VPL index with the receiver sets it is tested
    /// against (bit s: set s of [`Self::refill_sets`]): a receiver passes only with the VPLs
    /// listed for its set.
    pub fn passing_sets(
        &self,
        reach: &[VplReach],
        members: &[(u32, u32)],
        normals: bool,
        passing: &mut Vec<Passing>,
    ) {
        self.passing_members(reach, members.iter().copied(), normals, passing);
    }

    #[inline(always)]
    fn passing_members(
        &self,
        reach: &[VplReach],
        members: impl Iterator<Item = (u32, u32)>,
        normals: bool,
        passing: &mut Vec<Passing>,
    ) {
        passing.clear();
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            return unsafe { passing_avx2(self, reach, members, normals, passing) };
        }
        passing_in::<F8>(self, reach, members, normals, passing);
    }
}

/// [`passing_in`] in AVX registers (the same IEEE operations).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn passing_avx2(
    receivers: &ReceiverChunks,
    reach: &[VplReach],
    members: impl Iterator<Item = (u32, u32)>,
    normals: bool,
    passing: &mut Vec<Passing>,
) {
    passing_in::<slc_bounds::lanes_avx::A8>(receivers, reach, members, normals, passing);
}

/// [`ReceiverChunks::passing_sets`] in lanes of `L`: the VPLs eight at a time against the
/// box of the receivers (their `BoxBound`), then each that passes against the box again (its
/// own bound and tangent plane), then chunk by chunk.
#[inline(always)]
fn passing_in<L: Lanes8>(
    receivers: &ReceiverChunks,
    reach: &[VplReach],
    members: impl Iterator<Item = (u32, u32)>,
    normals: bool,
    passing: &mut Vec<Passing>,
) {
    // The next eight members' exits are asked for while these eight are tested: a window's
    // VPLs lie scattered over the table (170 MB at a million listed VPLs), and each group's
    // gather of their bounds waited on those reads.
    let mut members = members;
    let mut next_group = |group: &mut [(u32, u32); 8]| {
        let mut len = 0;
        for (slot, member) in group.iter_mut().zip(&mut members) {
            crate::prefetch::prefetch(&reach[member.0 as usize]);
            *slot = member;
            len += 1;
        }
        len
    };
    let (mut group, mut next) = ([(0, 0); 8], [(0, 0); 8]);
    let mut len = next_group(&mut group);
    while len > 0 {
        let next_len = next_group(&mut next);
        passing_group::<L>(receivers, reach, &group[..len], normals, passing);
        (group, len) = (next, next_len);
    }
}

/// [`passing_in`] for up to eight members (VPL index, sets), in their order.
#[inline(always)]
fn passing_group<L: Lanes8>(
    receivers: &ReceiverChunks,
    reach: &[VplReach],
    group: &[(u32, u32)],
    normals: bool,
    passing: &mut Vec<Passing>,
) {
    let last = group.len() - 1;
    let bounds = BoxBoundLanes::gather(core::array::from_fn(|k| {
        &reach[group[k.min(last)].0 as usize].box_bound
    }));
    let (lo, hi) = (receivers.lo, receivers.hi);
    let lo = [L::splat(lo.x), L::splat(lo.y), L::splat(lo.z)];
    let hi = [L::splat(hi.x), L::splat(hi.y), L::splat(hi.z)];
    let keep = L::bits(bounds.load::<L>().may_exceed_xi(lo, hi));
    for (k, &(i, sets)) in group.iter().enumerate() {
        let r = &reach[i as usize];
        if keep >> k & 1 == 1
            && r.reach
                .box_may_reach(r.position, receivers.lo, receivers.hi)
        {
            passing_lanes::<L>(r, i, sets, receivers, normals, passing);
        }
    }
}

/// The chunks of `receivers` where a receiver of one of the sets in `sets` passes with VPL
/// `vpl`, appended to `passing`.
#[inline(always)]
fn passing_lanes<L: Lanes8>(
    reach: &VplReach,
    vpl: u32,
    sets: u32,
    receivers: &ReceiverChunks,
    normals: bool,
    passing: &mut Vec<Passing>,
) {
    let lanes = Reach::<L>::splat(&reach.reach);
    let acceptance = Acceptance::<L>::splat(&reach.acceptance);
    let q: [L; 3] = splat_all(&reach.position.to_array());
    let (first, end) = receivers.span(sets);
    for (chunk, c) in receivers.chunks.iter().enumerate().take(end).skip(first) {
        let members = c.members(sets);
        if members == 0 {
            continue;
        }
        // d = x − q, each lane exactly as the shader forms `g.position − vpl.position`.
        let d = [
            L::load(&c.position[0]) - q[0],
            L::load(&c.position[1]) - q[1],
            L::load(&c.position[2]) - q[2],
        ];
        let passes = if normals {
            let normal = load_all(&c.normal);
            lanes.may_contribute(d, normal)
        } else {
            lanes.may_accept(d)
        };
        let b = L::bits(passes) & members;
        if b == 0 {
            continue;
        }
        let roulette = acceptance.evaluate(lanes.normal, d);
        let bits = b & L::bits(roulette.may_accept);
        if bits != 0 {
            passing.push(Passing {
                vpl,
                chunk,
                bits,
                exact: bits & L::bits(roulette.exact),
                l2: roulette.l2.store(),
                omega: store_all(&roulette.omega),
                intensity: store_all(&roulette.intensity),
            });
        }
    }
}
