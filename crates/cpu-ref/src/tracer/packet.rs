//! Eight coherent rays traced through the BVH together (a ray packet): every node's eight
//! child boxes are tested against the packet's rays taken as intervals in one pass of vector
//! operations (`children_in_reach`), the few children that pass against the eight rays
//! (`slot_hits`), and every triangle against the eight rays, instead of eight traversals each
//! decoding the same nodes and testing the same triangles.
//!
//! Each ray gets exactly the result it gets alone, bit for bit: its lane runs obvhs's box
//! test (`CwBvhNode::intersect_ray_simd`: the same products, sums, minima and maxima in the
//! same order) and the watertight triangle test of [`ShearedRay::hit`] with the same
//! operations, and the packet visits nodes and triangles in obvhs's order (a node's leaf
//! triangles first, highest offset first, then its inner children by the priority of the
//! rays' octant, depth first), each ray only where its own box test passed with its own
//! closest distance so far (the interval test leaves out only children no ray's own test
//! enters). So a ray tests the same triangles in the same order and keeps the
//! same closest one, ties included. The packet needs the rays to share the octant and the
//! dominant axis (coherent primary and shadow rays of neighbouring pixels almost always do);
//! other rays, rays against alpha-masked triangles and triangles a lane meets exactly on an
//! edge (the f64 decision) go through the scalar code.
use super::{Tracer, NOT_MASKED};
use crate::watertight::ShearedRay;
use core::mem::MaybeUninit;
use glam::Vec3;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::ray::safe_inverse;
use slc_bounds::lanes::{max, min, Lanes8, Real, F8};

/// obvhs's lower bound on a box's entry distance (`cwbvh::node::EPSILON`, crate-private).
const BOX_EPSILON: f32 = 0.0001;
/// Entries of the traversal stack; a deeper traversal finishes ray by ray.
const STACK: usize = 192;

/// Up to eight rays: lane i is in use where bit i of `used` is set.
#[derive(Clone, Copy, Debug)]
pub struct Rays8 {
    pub origin: [Vec3; 8],
    pub dir: [Vec3; 8],
    /// Each ray's hits lie in (tmin, tmax].
    pub tmin: [f32; 8],
    pub tmax: [f32; 8],
    pub used: u8,
}

impl Default for Rays8 {
    fn default() -> Self {
        Self {
            origin: [Vec3::ZERO; 8],
            dir: [Vec3::Z; 8],
            tmin: [0.0; 8],
            tmax: [f32::INFINITY; 8],
            used: 0,
        }
    }
}

/// The lanes of a packet whose rays share the octant and the shear axes.
struct Lanes<L: Real> {
    origin: [L; 3],
    inv: [L; 3],
    /// The shear constants (Sx, Sy, Sz) of the watertight test.
    shear: [L; 3],
    tmin: L,
    /// The closest hit so far (the query's tmax at first).
    tmax: L,
    /// Whether the direction is negative along x, y, z (obvhs's `rdx`, ...).
    negative: [bool; 3],
    /// obvhs's octant mask: the priority of inner child k is k ^ `octant`.
    octant: u8,
    /// The axes of the watertight test: kx, ky, kz.
    k: [usize; 3],
    /// The rays in use as intervals, for [`children_in_reach`].
    reach: Reach,
}

/// What the rays in use share, per axis: the interval of their origins and of their
/// inverse directions (mostly of one sign, as the rays share an octant; a −0 component's
/// inverse is −1/ε beside a +0 one's +1/ε), and the largest magnitude of each, from which
/// [`children_in_reach`] bounds its rounding (formed once per packet, read at every node).
/// A ray with a non-finite origin or inverse direction along an axis makes that axis's
/// magnitude infinite: the axis then bounds nothing.
#[derive(Clone, Copy, Debug)]
struct Reach {
    origin: [[f32; 2]; 3],
    inv: [[f32; 2]; 3],
    origin_abs: [f32; 3],
    inv_abs: [f32; 3],
}

/// What a traversal does at each triangle a lane meets.
trait Query {
    /// Whether `lanes` are done (an occlusion query stops at its first hit).
    fn done(&self) -> u8;
    /// Lanes `hit` met triangle `prim` at distances `t` (closer than their tmax).
    fn record<L: Lanes8>(&mut self, lanes: &mut Lanes<L>, prim: u32, hit: u8, t: L);
}

/// Closest hits: per lane the distance and BVH primitive, as `ray_traverse` keeps them.
struct Closest {
    hits: [Option<(f32, u32)>; 8],
}

impl Query for Closest {
    fn done(&self) -> u8 {
        0
    }
    #[inline(always)]
    fn record<L: Lanes8>(&mut self, lanes: &mut Lanes<L>, prim: u32, hit: u8, t: L) {
        let mask = mask_of::<L>(hit);
        lanes.tmax = L::select(mask, t, lanes.tmax);
        let t = t.store();
        for i in 0..8 {
            if hit & (1 << i) != 0 {
                self.hits[i] = Some((t.0[i], prim));
            }
        }
    }
}

/// Occlusion: the lanes that met anything.
struct Blocked(u8);

impl Query for Blocked {
    fn done(&self) -> u8 {
        self.0
    }
    fn record<L: Lanes8>(&mut self, _: &mut Lanes<L>, _: u32, hit: u8, _: L) {
        self.0 |= hit;
    }
}

/// The lane mask with lane i set where bit i of `bits` is.
#[inline(always)]
fn mask_of<L: Lanes8>(bits: u8) -> L::Mask {
    let mut m = F8([0.0; 8]);
    for (i, v) in m.0.iter_mut().enumerate() {
        *v = if bits & (1 << i) != 0 { 1.0 } else { 0.0 };
    }
    L::load(&m).gt(L::splat(0.5))
}

/// Eight floats as lanes.
#[inline(always)]
fn lanes_of<L: Lanes8>(v: [f32; 8]) -> L {
    L::load(&F8(v))
}

impl Tracer {
    /// The closest hit of each ray in use within (tmin, tmax): its distance and BVH
    /// primitive (what [`Tracer::closest`] finds for the ray alone).
    pub fn closest8(&self, rays: &Rays8) -> [Option<(f32, u32)>; 8] {
        let mut q = Closest { hits: [None; 8] };
        if !self.traverse8(rays, &mut q) {
            q.hits = [None; 8];
            for i in set_lanes(rays.used) {
                q.hits[i] = self.closest(rays.origin[i], rays.dir[i], rays.tmin[i], rays.tmax[i]);
            }
        }
        q.hits
    }

    /// The rays in use that meet a triangle within (tmin, tmax] (what
    /// `Tracer::segment_is_free` says for each ray alone, negated).
    pub(crate) fn blocked8(&self, rays: &Rays8) -> u8 {
        let mut q = Blocked(0);
        if !self.traverse8(rays, &mut q) {
            q.0 = 0;
            for i in set_lanes(rays.used) {
                if !self.segment_is_free(rays.origin[i], rays.dir[i], rays.tmin[i], rays.tmax[i]) {
                    q.0 |= 1 << i;
                }
            }
        }
        q.0
    }

    /// Runs `query` on the packet; false (nothing done) where the rays are not coherent.
    fn traverse8(&self, rays: &Rays8, query: &mut impl Query) -> bool {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            return unsafe { self.traverse8_avx2(rays, query) };
        }
        self.traverse8_in::<F8>(rays, query)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn traverse8_avx2(&self, rays: &Rays8, query: &mut impl Query) -> bool {
        self.traverse8_in::<slc_bounds::lanes_avx::A8>(rays, query)
    }

    #[inline(always)]
    fn traverse8_in<L: Lanes8>(&self, rays: &Rays8, query: &mut impl Query) -> bool {
        let Some(mut lanes) = packet_lanes::<L>(rays) else {
            return false;
        };
        if self.bvh.nodes.is_empty() {
            return true;
        }
        // Not cleared: zeroing its 1.5 KB took a quarter of an empty traversal's time.
        let mut stack = [MaybeUninit::<(u32, u8)>::uninit(); STACK];
        let mut top = 1;
        stack[0].write((0, rays.used));
        while top > 0 {
            top -= 1;
            // SAFETY: every entry below `top` was written (pushes write at `top` first).
            let (index, entered) = unsafe { stack[top].assume_init() };
            let live = entered & !query.done();
            if live == 0 {
                continue;
            }
            let node = &self.bvh.nodes[index as usize];
            let slots = slot_hits(node, &lanes, live, children_in_reach(node, &lanes));
            self.leaf_triangles(node, &slots, rays, &mut lanes, query);
            // Inner children, pushed lowest priority first so the highest is taken next.
            let mut inner = [(0u8, 0u32, 0u8); 8];
            let mut count = 0;
            for (j, &hit) in slots.iter().enumerate() {
                let meta = node.child_meta[j];
                if hit == 0 || !is_inner(meta) {
                    continue;
                }
                let k = (meta & 0x1f) - 24;
                let child =
                    node.child_base_idx + (node.imask as u32 & ((1u32 << k) - 1)).count_ones();
                inner[count] = (k ^ lanes.octant, child, hit);
                count += 1;
            }
            let inner = &mut inner[..count];
            inner.sort_unstable_by_key(|c| c.0);
            if top + count > STACK {
                // Deeper than any BVH slc builds: the caller traces the rays one by one.
                return false;
            }
            for &(_, child, hit) in inner.iter() {
                stack[top].write((child, hit));
                top += 1;
            }
        }
        true
    }

    /// The packet's leaf triangles at `node` for the lanes of their slots, in obvhs's order.
    #[inline(always)]
    fn leaf_triangles<L: Lanes8>(
        &self,
        node: &CwBvhNode,
        slots: &[u8; 8],
        rays: &Rays8,
        lanes: &mut Lanes<L>,
        query: &mut impl Query,
    ) {
        // Lanes per triangle offset (slots hold disjoint ranges of offsets 0..24).
        let mut by_offset = [0u8; 24];
        let mut any = 0u32;
        for (j, &hit) in slots.iter().enumerate() {
            let meta = node.child_meta[j];
            if hit == 0 || is_inner(meta) {
                continue;
            }
            let first = (meta & 0x1f) as usize;
            for i in 0..(meta >> 5).count_ones() as usize {
                by_offset[first + i] = hit;
                any |= 1 << (first + i);
            }
        }
        while any != 0 {
            let offset = 31 - any.leading_zeros();
            any &= !(1 << offset);
            let hit = by_offset[offset as usize] & !query.done();
            if hit == 0 {
                continue;
            }
            let prim = node.primitive_base_idx + offset;
            self.triangle(prim, hit, rays, lanes, query);
        }
    }

    /// Triangle `prim` against lanes `active`.
    #[inline(always)]
    fn triangle<L: Lanes8>(
        &self,
        prim: u32,
        active: u8,
        rays: &Rays8,
        lanes: &mut Lanes<L>,
        query: &mut impl Query,
    ) {
        let id = prim as usize;
        if self.prims[id].cutout != NOT_MASKED {
            return self.triangle_alone(prim, active, rays, lanes, query);
        }
        let tri = &self.tris[id];
        let (a, b, c) = (
            relative(tri.v0, lanes),
            relative(tri.v1, lanes),
            relative(tri.v2, lanes),
        );
        let [sx, sy, sz] = lanes.shear;
        let (ax, ay) = (a[0] - sx * a[2], a[1] - sy * a[2]);
        let (bx, by) = (b[0] - sx * b[2], b[1] - sy * b[2]);
        let (cx, cy) = (c[0] - sx * c[2], c[1] - sy * c[2]);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = L::splat(0.0);
        let edge = L::bits(is_zero(u) | is_zero(v) | is_zero(w)) & active;
        if edge != 0 {
            self.triangle_alone(prim, edge, rays, lanes, query);
        }
        let active = active & !edge & !query.done();
        let negative = zero.gt(u) | zero.gt(v) | zero.gt(w);
        let positive = u.gt(zero) | v.gt(zero) | w.gt(zero);
        let det = u + v + w;
        let t = (u * (sz * a[2]) + v * (sz * b[2]) + w * (sz * c[2])) / det;
        let hit = !(negative & positive)
            & (det.gt(zero) | zero.gt(det))
            & t.gt(lanes.tmin)
            & lanes.tmax.gt(t);
        let hit = L::bits(hit) & active;
        if hit != 0 {
            query.record(lanes, prim, hit, t);
        }
    }

    /// Triangle `prim` for lanes `which` by the scalar test (masks, edges).
    fn triangle_alone<L: Lanes8>(
        &self,
        prim: u32,
        which: u8,
        rays: &Rays8,
        lanes: &mut Lanes<L>,
        query: &mut impl Query,
    ) {
        let tmax = lanes.tmax.store();
        let mut t = [f32::INFINITY; 8];
        let mut hit = 0u8;
        for i in set_lanes(which) {
            let sheared = ShearedRay::new(rays.origin[i], rays.dir[i]);
            let d = self.hit_distance(&sheared, prim as usize, rays.tmin[i], tmax.0[i]);
            if d < tmax.0[i] {
                t[i] = d;
                hit |= 1 << i;
            }
        }
        if hit != 0 {
            query.record(lanes, prim, hit, lanes_of(t));
        }
    }
}

/// A child box's near and far planes along an axis (lo, hi swapped for a negative direction).
#[inline(always)]
fn near_far(lo: u8, hi: u8, negative: bool) -> (f32, f32) {
    if negative {
        (hi as f32, lo as f32)
    } else {
        (lo as f32, hi as f32)
    }
}

/// Vertex `v` relative to the lanes' origins along the shear axes (kx, ky, kz).
#[inline(always)]
fn relative<L: Lanes8>(v: glam::Vec3A, lanes: &Lanes<L>) -> [L; 3] {
    let [kx, ky, kz] = lanes.k;
    [
        L::splat(v[kx]) - lanes.origin[kx],
        L::splat(v[ky]) - lanes.origin[ky],
        L::splat(v[kz]) - lanes.origin[kz],
    ]
}

/// Lanes where `x` is 0 (either sign; not NaN).
#[inline(always)]
fn is_zero<L: Lanes8>(x: L) -> L::Mask {
    let zero = L::splat(0.0);
    x.le(zero) & !zero.gt(x)
}

/// Whether child meta `meta` is an inner node (obvhs: its low five bits are 24..32).
#[inline(always)]
fn is_inner(meta: u8) -> bool {
    (meta & (meta << 1)) & 0x10 != 0
}

/// The child slots of `node` that some ray of the packet may enter: a superset of those
/// whose box any lane's own test (`slot_hits`) passes, found for the eight children at once
/// so that the lanes test only these (in Sponza's primary rays about one child in six
/// passes a ray, and nine in ten of those pass every ray).
///
/// Per axis, each child's near and far planes p + q e (q e is exact: e is a power of two)
/// less the interval of the origins, times the interval of the inverse directions, bound
/// every ray's slab distances from below (near) and above (far), each moved outwards by its
/// axis's slack; a child is left out where the largest lower bound (and the box epsilon)
/// exceeds the smallest upper bound (and the largest tmax). Each ray's own distances along
/// an axis differ from the exact ones by a few f32 roundings of the terms they are formed
/// from, at most a few 1e-7 of (|p| + 255 e + |o|)|1/d| for that axis, as do these bounds:
/// the slack is 1e-5 of that magnitude (with 256 e for 255 e), per axis, so that an axis
/// along which the rays barely move (|1/d| up to 1/ε) weakens only its own bounds. The four
/// products of each interval bound the exact value whatever the signs. An axis with a
/// non-finite ray ([`Reach`]) or an overflowing term bounds nothing (its slack is infinite,
/// or its bound NaN, which the maximum and minimum pass over or which leaves every child in).
#[inline(always)]
fn children_in_reach<L: Lanes8>(node: &CwBvhNode, lanes: &Lanes<L>) -> u8 {
    let e = node.compute_extent();
    let r = &lanes.reach;
    let mut tmax = f32::NEG_INFINITY;
    for t in lanes.tmax.store().0 {
        tmax = tmax.max(t);
    }
    let planes = [
        (&node.child_min_x, &node.child_max_x),
        (&node.child_min_y, &node.child_max_y),
        (&node.child_min_z, &node.child_max_z),
    ];
    let (mut lower, mut upper) = (L::splat(BOX_EPSILON), L::splat(tmax));
    for (a, (lo, hi)) in planes.into_iter().enumerate() {
        let (p, ea) = (L::splat(node.p[a]), L::splat(e[a]));
        let (lo, hi) = (
            p + bytes_as_lanes::<L>(lo) * ea,
            p + bytes_as_lanes::<L>(hi) * ea,
        );
        let (near, far) = if lanes.negative[a] {
            (hi, lo)
        } else {
            (lo, hi)
        };
        let (o0, o1) = (L::splat(r.origin[a][0]), L::splat(r.origin[a][1]));
        let (i0, i1) = (L::splat(r.inv[a][0]), L::splat(r.inv[a][1]));
        let slack =
            L::splat(1e-5 * (node.p[a].abs() + 256.0 * e[a] + r.origin_abs[a]) * r.inv_abs[a]);
        let (n0, n1) = (near - o1, near - o0);
        let below = min(min(n0 * i0, n0 * i1), min(n1 * i0, n1 * i1));
        lower = max(lower, below - slack);
        let (f0, f1) = (far - o1, far - o0);
        let above = max(max(f0 * i0, f0 * i1), max(f1 * i0, f1 * i1));
        upper = min(upper, above + slack);
    }
    !L::bits(lower.gt(upper))
}

/// Eight quantized planes as lanes.
#[inline(always)]
fn bytes_as_lanes<L: Lanes8>(q: &[u8; 8]) -> L {
    let mut v = [0.0f32; 8];
    for (v, &q) in v.iter_mut().zip(q) {
        *v = f32::from(q);
    }
    lanes_of(v)
}

/// For each child slot of `node` in `reach`, the lanes of `live` whose ray meets its box,
/// as obvhs's `intersect_ray_simd` tests it for each ray (0 for the other slots, whose boxes
/// no ray meets).
#[inline(always)]
fn slot_hits<L: Lanes8>(node: &CwBvhNode, lanes: &Lanes<L>, live: u8, reach: u8) -> [u8; 8] {
    let e = node.compute_extent();
    let p = node.p;
    // Per axis: the extent times 1/d, and (p − o) times 1/d (obvhs's adjusted ray).
    let (ix, iy, iz) = (
        L::splat(e.x) * lanes.inv[0],
        L::splat(e.y) * lanes.inv[1],
        L::splat(e.z) * lanes.inv[2],
    );
    let (ox, oy, oz) = (
        (L::splat(p.x) - lanes.origin[0]) * lanes.inv[0],
        (L::splat(p.y) - lanes.origin[1]) * lanes.inv[1],
        (L::splat(p.z) - lanes.origin[2]) * lanes.inv[2],
    );
    let eps = L::splat(BOX_EPSILON);
    let [nx, ny, nz] = lanes.negative;
    let mut out = [0u8; 8];
    for (j, o) in out.iter_mut().enumerate() {
        if node.child_meta[j] == 0 || reach & (1 << j) == 0 {
            continue;
        }
        let (x0, x1) = near_far(node.child_min_x[j], node.child_max_x[j], nx);
        let (y0, y1) = near_far(node.child_min_y[j], node.child_max_y[j], ny);
        let (z0, z1) = near_far(node.child_min_z[j], node.child_max_z[j], nz);
        let (tx0, tx1) = (L::splat(x0) * ix + ox, L::splat(x1) * ix + ox);
        let (ty0, ty1) = (L::splat(y0) * iy + oy, L::splat(y1) * iy + oy);
        let (tz0, tz1) = (L::splat(z0) * iz + oz, L::splat(z1) * iz + oz);
        let tmin = max(max(tx0, max(ty0, tz0)), eps);
        let tmax = min(min(tx1, min(ty1, tz1)), lanes.tmax);
        *o = L::bits(tmin.le(tmax)) & live;
    }
    out
}

/// The lanes of `rays`, or `None` where the rays in use differ in octant or shear axes (or
/// none is in use). Each lane's inverse direction is obvhs's (`Ray::new`: `safe_inverse` of
/// each component) and its shear constants [`ShearedRay::new`]'s, formed for the eight lanes
/// at once with the same divisions; a lane not in use copies the first one in use, with an
/// empty range (tmax −∞), so that it never records a hit and widens no interval.
#[inline(always)]
fn packet_lanes<L: Lanes8>(rays: &Rays8) -> Option<Lanes<L>> {
    if rays.used == 0 {
        return None;
    }
    let lead = rays.used.trailing_zeros() as usize;
    let key = packet_key(rays.dir[lead]);
    let mut origin = [[0.0f32; 8]; 3];
    let mut dir = [[0.0f32; 8]; 3];
    let mut tmin = [0.0f32; 8];
    let mut tmax = [f32::NEG_INFINITY; 8];
    let mut coherent = true;
    for i in 0..8 {
        let used = rays.used & (1 << i) != 0;
        let j = if used { i } else { lead };
        let (o, d) = (rays.origin[j], rays.dir[j]);
        coherent &= packet_key(d) == key;
        for a in 0..3 {
            origin[a][i] = o[a];
            dir[a][i] = d[a];
        }
        if used {
            tmin[i] = rays.tmin[i];
            tmax[i] = rays.tmax[i];
        }
    }
    if !coherent {
        return None;
    }
    let d = rays.dir[lead];
    let (negative, k) = ([d.x < 0.0, d.y < 0.0, d.z < 0.0], ShearedRay::axes_of(d));
    let d: [L; 3] = [lanes_of(dir[0]), lanes_of(dir[1]), lanes_of(dir[2])];
    let one = L::splat(1.0);
    let mut inv = [
        (one / d[0]).store().0,
        (one / d[1]).store().0,
        (one / d[2]).store().0,
    ];
    for (inv, d) in inv.iter_mut().zip(&dir) {
        for (v, &d) in inv.iter_mut().zip(d) {
            if d.abs() <= f32::EPSILON {
                *v = safe_inverse(d);
            }
        }
    }
    let [kx, ky, kz] = k;
    let shear = [d[kx] / d[kz], d[ky] / d[kz], one / d[kz]];
    let mut reach = Reach {
        origin: [[f32::INFINITY, f32::NEG_INFINITY]; 3],
        inv: [[f32::INFINITY, f32::NEG_INFINITY]; 3],
        origin_abs: [0.0; 3],
        inv_abs: [0.0; 3],
    };
    for a in 0..3 {
        for i in 0..8 {
            let (o, v) = (origin[a][i], inv[a][i]);
            reach.origin[a] = [reach.origin[a][0].min(o), reach.origin[a][1].max(o)];
            reach.inv[a] = [reach.inv[a][0].min(v), reach.inv[a][1].max(v)];
            reach.origin_abs[a] = reach.origin_abs[a].max(o.abs());
            reach.inv_abs[a] = reach.inv_abs[a].max(v.abs());
            if !(o.is_finite() && v.is_finite()) {
                // f32::min and max above pass over a NaN, whose lane's own test may pass.
                reach.inv_abs[a] = f32::INFINITY;
            }
        }
    }
    let octant =
        (u8::from(!negative[0]) << 2) | (u8::from(!negative[1]) << 1) | u8::from(!negative[2]);
    Some(Lanes {
        origin: [
            lanes_of(origin[0]),
            lanes_of(origin[1]),
            lanes_of(origin[2]),
        ],
        inv: [lanes_of(inv[0]), lanes_of(inv[1]), lanes_of(inv[2])],
        shear,
        tmin: lanes_of(tmin),
        tmax: lanes_of(tmax),
        negative,
        octant,
        k,
        reach,
    })
}

/// What a packet's rays must share, as one number: whether the direction is negative along
/// x, y, z (bits 0-2) and its dominant axis kz (bits 3-4), which with the sign along it
/// gives the watertight test's axes ([`ShearedRay::axes_of`]).
#[inline(always)]
fn packet_key(d: Vec3) -> u8 {
    let kz = ShearedRay::axes_of(d)[2] as u8;
    u8::from(d.x < 0.0) | (u8::from(d.y < 0.0) << 1) | (u8::from(d.z < 0.0) << 2) | (kz << 3)
}

/// The indices of the set bits of `used`, lowest first.
fn set_lanes(used: u8) -> impl Iterator<Item = usize> {
    (0..8).filter(move |i| used & (1 << i) != 0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_core::builtin;

    /// Sponza-like coherence on the built-in scene: packets of neighbouring camera rays and
    /// of shadow rays towards one point take the packet path and give each ray its own
    /// answer (closest hit and primitive; occlusion), in lanes and in plain arrays; mixed
    /// octants fall back to the rays alone.
    #[test]
    fn packets_give_each_ray_its_own_answer() {
        let scene = builtin("default").unwrap();
        let tracer = Tracer::new(&scene);
        let camera = scene.camera_or_default();
        let (w, h) = (64u32, 48u32);
        let (mut packets, mut shadow_packets) = (0, 0);
        for j0 in (0..h).step_by(2) {
            for i0 in (0..w).step_by(4) {
                let mut rays = Rays8 {
                    used: 0xff,
                    ..Rays8::default()
                };
                for l in 0..8 {
                    let (i, j) = (i0 + l as u32 % 4, j0 + l as u32 / 4);
                    rays.origin[l] = camera.position;
                    rays.dir[l] = camera.ray_direction(i, j, 0.5, 0.5, w, h);
                }
                let mut lanes = Closest { hits: [None; 8] };
                packets += usize::from(tracer.traverse8(&rays, &mut lanes));
                let mut arrays = Closest { hits: [None; 8] };
                let coherent = tracer.traverse8_in::<F8>(&rays, &mut arrays);
                for l in 0..8 {
                    let alone = tracer.closest(rays.origin[l], rays.dir[l], 0.0, f32::INFINITY);
                    assert_eq!(tracer.closest8(&rays)[l], alone);
                    if coherent {
                        assert_eq!((lanes.hits[l], arrays.hits[l]), (alone, alone));
                    }
                }
                // Shadow rays from the hits towards a point under the ceiling.
                let light = glam::Vec3::new(0.1, 1.9, 0.1);
                let mut shadow = Rays8::default();
                for (l, hit) in lanes.hits.iter().enumerate() {
                    let Some((t, _)) = hit else {
                        continue;
                    };
                    let from = rays.origin[l] + rays.dir[l] * *t;
                    if let Some((dir, tmin, tmax)) = tracer.segment_ray(from, light) {
                        shadow.origin[l] = from;
                        shadow.dir[l] = dir;
                        shadow.tmin[l] = tmin;
                        shadow.tmax[l] = tmax;
                        shadow.used |= 1 << l;
                    }
                }
                let mut q = Blocked(0);
                shadow_packets += usize::from(tracer.traverse8(&shadow, &mut q));
                let blocked = tracer.occluded8(&shadow);
                for l in set_lanes(shadow.used) {
                    let alone = !tracer.segment_is_free(
                        shadow.origin[l],
                        shadow.dir[l],
                        shadow.tmin[l],
                        shadow.tmax[l],
                    );
                    assert_eq!(blocked & (1 << l) != 0, alone, "lane {l}");
                }
            }
        }
        // Every camera block is coherent here; shadow rays towards a point inside the room
        // change octant across the room, two blocks in three are coherent.
        assert_eq!(packets, 16 * 24);
        assert!(shadow_packets > 200, "{shadow_packets}");
        let mut mixed = Rays8 {
            used: 0b11,
            ..Rays8::default()
        };
        mixed.dir[0] = glam::Vec3::new(0.1, 0.2, -1.0).normalize();
        mixed.dir[1] = glam::Vec3::new(-0.1, 0.2, -1.0).normalize();
        assert!(!tracer.traverse8(&mixed, &mut Closest { hits: [None; 8] }));
    }

    /// `children_in_reach` in AVX2 lanes, for comparison with the plain arrays.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn reach_avx2(node: &CwBvhNode, rays: &Rays8) -> u8 {
        let lanes = packet_lanes::<slc_bounds::lanes_avx::A8>(rays).unwrap();
        children_in_reach(node, &lanes)
    }

    /// `children_in_reach` leaves out no child whose box a lane's own test enters, at every
    /// node of the built-in scene's BVH, for five kinds of packets, each of which enters
    /// children: camera blocks; rays from scattered origins with finite ranges; rays straight
    /// down from points under the ceiling whose x components are +0, −0, 1e-8 and 0.05
    /// (inverse directions of both signs, up to 1/ε); rays from 6e4 away through the camera;
    /// and camera blocks with one NaN origin. It leaves out most children of the camera
    /// blocks (else the test would hold for a function that leaves out nothing), and the
    /// AVX2 lanes agree with the plain arrays.
    #[test]
    fn children_in_reach_keep_every_child_a_lane_enters() {
        let scene = builtin("default").unwrap();
        let tracer = Tracer::new(&scene);
        let camera = scene.camera_or_default();
        let mut counter = 0;
        let mut next = move || {
            counter += 1;
            slc_core::rng::uniform(7, counter, 0, 0)
        };
        let (mut entered, mut kept, mut children) = ([0usize; 5], [0usize; 5], [0usize; 5]);
        for case in 0..2000 {
            let kind = case % 5;
            let mut rays = Rays8 {
                used: 0xff,
                ..Rays8::default()
            };
            let (i0, j0) = ((next() * 60.0) as u32, (next() * 46.0) as u32);
            for l in 0..8 {
                let (i, j) = (i0 + l as u32 % 4, j0 + l as u32 / 4);
                rays.dir[l] = camera.ray_direction(i, j, 0.5, 0.5, 64, 48);
                rays.origin[l] = camera.position;
                match kind {
                    1 => {
                        rays.origin[l] +=
                            glam::Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 1.5;
                        rays.tmax[l] = next() * 4.0;
                        rays.tmin[l] = 1e-3;
                    }
                    2 => {
                        let x = [0.0, -0.0, 1e-8, 0.05][l % 4];
                        rays.dir[l] = glam::Vec3::new(x, -1.0, 0.0).normalize();
                        rays.origin[l] =
                            glam::Vec3::new(next() * 1.8 - 0.9, 1.9, next() * 1.8 - 0.9);
                    }
                    3 => rays.origin[l] = camera.position - rays.dir[l] * 6e4,
                    4 if l == 2 => rays.origin[l].y = f32::NAN,
                    _ => {}
                }
            }
            rays.used = if case % 3 == 0 { 0b1011_0110 } else { 0xff };
            // Blocks across the image's centre change octant: the traversal takes them ray
            // by ray.
            let Some(lanes) = packet_lanes::<F8>(&rays) else {
                continue;
            };
            for node in &tracer.bvh.nodes {
                let reach = children_in_reach(node, &lanes);
                #[cfg(target_arch = "x86_64")]
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU has AVX2, checked above.
                    assert_eq!(unsafe { reach_avx2(node, &rays) }, reach);
                }
                let slots = slot_hits(node, &lanes, rays.used, 0xff);
                for (j, &hit) in slots.iter().enumerate() {
                    if node.child_meta[j] == 0 {
                        continue;
                    }
                    children[kind] += 1;
                    kept[kind] += usize::from(reach & (1 << j) != 0);
                    if hit != 0 {
                        entered[kind] += 1;
                        assert!(reach & (1 << j) != 0, "case {case}: child {j} left out");
                    }
                }
            }
        }
        assert!(entered.iter().all(|&n| n > 100), "{entered:?}");
        // The camera blocks' intervals are narrow: most children are left out, also with a
        // NaN origin (the axis it is on bounds nothing, the others as before).
        assert!(
            kept[0] < children[0] / 4,
            "{kept:?} of {children:?} children kept"
        );
        assert!(
            kept[4] < children[4] / 2,
            "{kept:?} of {children:?} children kept"
        );
    }
}
