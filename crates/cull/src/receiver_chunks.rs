//! The early exits of one VPL against a group of receivers (the pixels of a tile that share a
//! light list), eight receivers per test: the transpose of [`crate::ReachChunks`]. The VPL's
//! constants are broadcast to every lane once and each lane is a pixel, so a VPL whose bound
//! covers a patch of the tile fills whole chunks with passing receivers, and the roulette
//! ([`crate::acceptance`]) runs on far fewer chunks than when the lanes are VPLs. Each lane
//! performs the same IEEE operations as [`VplReach::may_contribute`], so the same pairs pass.
use crate::acceptance::Acceptance;
use crate::lanes::{Lanes8, Real, F8};
use crate::reach::{Reach, VplReach};
use glam::Vec3;

/// Eight receivers: their positions x and unit normals, and which lanes hold one.
#[derive(Clone, Copy, Debug)]
struct Receivers {
    position: [F8; 3],
    normal: [F8; 3],
    valid: u8,
}

/// A group of receivers as chunks of eight, in the order given; receiver i is lane i mod 8
/// of chunk i / 8.
#[derive(Clone, Debug, Default)]
pub struct ReceiverChunks {
    chunks: Vec<Receivers>,
}

impl ReceiverChunks {
    /// Replaces the receivers by `receivers` (position x, unit normal), keeping the allocation.
    pub fn refill(&mut self, receivers: impl IntoIterator<Item = (Vec3, Vec3)>) {
        self.chunks.clear();
        let mut lane = 8;
        for (x, n) in receivers {
            if lane == 8 {
                // Lanes past the end repeat the chunk's first receiver (finite arithmetic),
                // and `valid` masks them out.
                self.chunks.push(Receivers {
                    position: [x.x, x.y, x.z].map(F8::splat),
                    normal: [n.x, n.y, n.z].map(F8::splat),
                    valid: 0,
                });
                lane = 0;
            }
            let c = self.chunks.last_mut().expect("pushed above");
            for (axis, (p, m)) in [x.x, x.y, x.z].into_iter().zip([n.x, n.y, n.z]).enumerate() {
                c.position[axis].0[lane] = p;
                c.normal[axis].0[lane] = m;
            }
            c.valid |= 1 << lane;
            lane += 1;
        }
    }
}

impl VplReach {
    /// For the VPL at `q` with these exits, writes to `bits` one byte per chunk of
    /// `receivers`: bit k set where receiver k of the chunk passes
    /// [`VplReach::may_contribute`] (the bound, the signs at both ends and the roulette), or
    /// with `normals` false [`VplReach::may_accept`] (the receivers' normals ignored).
    /// Returns whether any receiver passes.
    pub fn receivers_passing(
        &self,
        q: Vec3,
        receivers: &ReceiverChunks,
        normals: bool,
        bits: &mut Vec<u8>,
    ) -> bool {
        bits.clear();
        bits.resize(receivers.chunks.len(), 0);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            return unsafe { passing_avx2(self, q, &receivers.chunks, normals, bits) };
        }
        passing_lanes::<F8>(self, q, &receivers.chunks, normals, bits)
    }
}

/// [`passing_lanes`] in AVX registers (the same IEEE operations).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn passing_avx2(
    reach: &VplReach,
    q: Vec3,
    chunks: &[Receivers],
    normals: bool,
    bits: &mut [u8],
) -> bool {
    passing_lanes::<crate::lanes_avx::A8>(reach, q, chunks, normals, bits)
}

#[inline(always)]
fn passing_lanes<L: Lanes8>(
    reach: &VplReach,
    q: Vec3,
    chunks: &[Receivers],
    normals: bool,
    bits: &mut [u8],
) -> bool {
    let lanes = Reach::<L>::splat(&reach.reach);
    let acceptance = Acceptance::<L>::splat(&reach.acceptance);
    let q = [L::splat(q.x), L::splat(q.y), L::splat(q.z)];
    let mut any = 0;
    for (c, out) in chunks.iter().zip(bits) {
        // d = x − q, each lane exactly as the shader forms `g.position − vpl.position`.
        let d = [
            L::load(&c.position[0]) - q[0],
            L::load(&c.position[1]) - q[1],
            L::load(&c.position[2]) - q[2],
        ];
        let passes = if normals {
            let normal = c.normal.each_ref().map(L::load);
            lanes.may_contribute(d, normal)
        } else {
            lanes.may_accept(d)
        };
        let b = L::bits(passes) & c.valid;
        if b != 0 {
            *out = b & L::bits(acceptance.may_accept(lanes.normal, d));
            any |= *out;
        }
    }
    any != 0
}
