//! Early exits for (pixel, VPL) pairs whose contribution is exactly zero, tested before the
//! receiver's BRDF: the VPL's own bound (outside it p <= ξ, so eq. (3) weights the pair 0)
//! and the sign of the cosine at either end (eq. 1 and the max(ωo·n, 0) of eq. 4), each with
//! a margin well above float rounding; then, for the pairs those pass, the roulette itself
//! (p(ωo, l) > ξ of eq. 2-3, the `acceptance` module) formed as the shader forms it. No exit
//! rejects a pair that the full evaluation accepts: the estimate stays bit for bit the same,
//! only cheaper.
use crate::acceptance::Acceptance;
use crate::vpl_bounds::{lobe_box_bound, GlossyBound, LocalBound};
use crate::vpl_lanes::{box_bounds, own_bounds, LaneBound};
use glam::{DMat3, DVec3, Vec3};
use rayon::prelude::*;
use slc_bounds::lanes::{dot, load_all, splat_all, Lanes8, Real, F8};
use slc_bounds::{BoxBound, BoxBoundLanes, StochasticParams};
use slc_core::{CullError, Vpl, VplLobe};

/// Relative margin of the sign tests: a pair is rejected only when the cosine at one end,
/// formed from the unnormalised offset, is below −1e-5. The shader's cosine of the same
/// direction (normalised first, then dotted) differs from it by a few ulps (about 1e-6 with
/// unit normals), so the sign cannot flip within the margin.
pub const SIGN_MARGIN: f32 = 1e-5;

/// One VPL's early exits in lanes of `R` (see [`slc_bounds::lanes`]): its normal n, and its own
/// bound as a stretch S and centre S·(c − q) with the bound the unit ball of S d − S·(c − q)
/// (the spheroid of eq. 12-15: S = diag(1/r) Rᵀ; the section-6 sphere: S = I/r, or Rᵀ/r for
/// a sphere from the lanes, `crate::vpl_lanes`, with any rotation R), and the limit
/// that |S d − S·(c − q)|² may reach: 1 plus a margin above the f32 rounding of the test.
/// A VPL that reflects nothing has limit −1 (no pair), one without a usable bound S = 0 and
/// limit +∞ (only the sign tests).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Reach<R> {
    pub normal: [R; 3],
    pub stretch: [R; 9],
    pub center: [R; 3],
    pub limit: R,
}

impl<R: Real> Reach<R> {
    /// One VPL's exits in every lane (the lanes are then receivers).
    #[inline(always)]
    pub(crate) fn splat(of: &Reach<f32>) -> Self {
        Self {
            normal: splat_all(&of.normal),
            stretch: splat_all(&of.stretch),
            center: splat_all(&of.center),
            limit: R::splat(of.limit),
        }
    }

    /// Whether the pair at offset `d = x − q` passes the bound and the sign at the VPL: not
    /// behind the VPL (beyond the margin) and inside its bound ([`VplReach::may_accept`] adds
    /// the roulette).
    #[inline(always)]
    pub(crate) fn may_accept(&self, d: [R; 3]) -> R::Mask {
        let margin_sq = R::splat(SIGN_MARGIN * SIGN_MARGIN) * dot(d, d);
        let s = &self.stretch;
        let c = &self.center;
        let u = [
            s[0] * d[0] + s[1] * d[1] + s[2] * d[2] - c[0],
            s[3] * d[0] + s[4] * d[1] + s[5] * d[2] - c[1],
            s[6] * d[0] + s[7] * d[1] + s[8] * d[2] - c[2],
        ];
        !behind(-dot(self.normal, d), margin_sq) & dot(u, u).le(self.limit)
    }

    /// [`Self::may_accept`], and the receiver with normal `receiver` not facing away.
    #[inline(always)]
    pub(crate) fn may_contribute(&self, d: [R; 3], receiver: [R; 3]) -> R::Mask {
        let margin_sq = R::splat(SIGN_MARGIN * SIGN_MARGIN) * dot(d, d);
        !behind(dot(receiver, d), margin_sq) & self.may_accept(d)
    }
}

impl Reach<f32> {
    /// Whether any receiver in the box `[lo, hi]` may pass [`Self::may_accept`] for the VPL at
    /// `q`: false only where every point of the box is outside the bound or behind the VPL by
    /// twice the margins of the per-pair test, so a receiver the f32 test passes is never
    /// rejected. In f64: the box maps under S to the box `S·(b − q) − S·(c − q) ± |S| h`
    /// (b its centre, h its half size), whose nearest point to the origin must be within
    /// 2·limit − 1 (twice the limit's rounding margin above 1), grown by 1e-3; and the
    /// largest n·d over the box, n·(b − q) + |n|·h, must reach −2·[`SIGN_MARGIN`] times the
    /// largest |d|.
    pub(crate) fn box_may_reach(&self, q: Vec3, lo: Vec3, hi: Vec3) -> bool {
        let (q, lo, hi) = (q.as_dvec3(), lo.as_dvec3(), hi.as_dvec3());
        let (b, h) = ((lo + hi) * 0.5 - q, (hi - lo) * 0.5);
        let n = DVec3::from(self.normal.map(f64::from));
        let reach = (lo - q).abs().max((hi - q).abs()).length();
        if n.dot(b) + n.abs().dot(h) < -2.0 * f64::from(SIGN_MARGIN) * reach {
            return false;
        }
        let s = self.stretch.map(f64::from);
        let rows = [
            DVec3::new(s[0], s[1], s[2]),
            DVec3::new(s[3], s[4], s[5]),
            DVec3::new(s[6], s[7], s[8]),
        ];
        let gap_sq: f64 = rows
            .iter()
            .zip(self.center)
            .map(|(row, c)| {
                let gap = (row.dot(b) - f64::from(c)).abs() - row.abs().dot(h);
                gap.max(0.0).powi(2)
            })
            .sum();
        gap_sq <= (2.0 * f64::from(self.limit) - 1.0) * (1.0 + 1e-3)
    }
}

impl Reach<F8> {
    /// The eight lanes as `L` ([`Lanes8::load`]).
    #[inline(always)]
    pub(crate) fn load<L: Lanes8>(&self) -> Reach<L> {
        Reach {
            normal: load_all(&self.normal),
            stretch: load_all(&self.stretch),
            center: load_all(&self.center),
            limit: L::load(&self.limit),
        }
    }
}

/// Whether `t` (a cosine times |d|) is positive beyond the margin, `t² > SIGN_MARGIN² |d|²`:
/// compared squared, with no square root.
#[inline(always)]
fn behind<R: Real>(t: R, margin_sq: R) -> R::Mask {
    t.gt(R::splat(0.0)) & (t * t).gt(margin_sq)
}

/// What one VPL needs for the early exits: its own bound (the tightest one: the spheroid for
/// a glossy VPL, whatever the culling strategy, since every strategy's bound contains every
/// pair with p > ξ), its normal, its roulette (`Acceptance`) and its bound over boxes of
/// receivers ([`Self::box_may_exceed_xi`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VplReach {
    /// The VPL's position q: the receivers' offsets d = x − q are formed from it.
    pub(crate) position: Vec3,
    pub(crate) reach: Reach<f32>,
    pub(crate) acceptance: Acceptance<f32>,
    /// The bound of p over boxes of receivers (`slc_bounds::BoxBound`, in f32 at `position`): tested
    /// for eight VPLs at a time against the box of the receivers before anything else.
    pub(crate) box_bound: BoxBoundLanes<f32>,
}

impl VplReach {
    /// The early exits of `vpl` under the roulette `params` (its δ and ξ, eq. 2-3). Errors
    /// when the VPL is outside the domain of slc-bounds (see `slc_bounds::BoundsError`).
    /// Its own bound is formed in f32 lanes where the VPL is plain (`crate::vpl_lanes`,
    /// grown by 1e-5 over their rounding), else by slc-bounds, and so is its bound over boxes
    /// (the same bound bit for bit); [`ListedReach::form`] forms the same exits eight VPLs at
    /// a time.
    pub fn new(vpl: &Vpl, params: &StochasticParams) -> Result<Self, CullError> {
        Self::one(vpl, params, true)
    }

    /// [`Self::new`] without the VPL's bounds: only the sign tests and the roulette, its own
    /// bound and its bound over boxes passing everywhere. Forming the bound over boxes and
    /// the stretch of its own bound costs most of [`Self::new`] (about 100 against 210 ns a
    /// VPL on one thread, [`ListedReach::form`] of 200k of Sponza's VPLs at RSM 1024), which a
    /// VPL listed at a few pixels does not earn back.
    /// The same errors: its own bound is still formed (not kept), by the lanes or by
    /// slc-bounds, so a lobe outside slc-bounds' domain or a range beyond f32 is refused as
    /// by [`Self::new`].
    pub fn without_bounds(vpl: &Vpl, params: &StochasticParams) -> Result<Self, CullError> {
        Self::one(vpl, params, false)
    }

    /// One VPL's exits, with its bounds where `bounds` ([`Self::eight`] for one).
    fn one(vpl: &Vpl, params: &StochasticParams, bounds: bool) -> Result<Self, CullError> {
        let mut out = [Self::NONE];
        Self::eight(&[vpl], core::slice::from_ref(params), |_| bounds, &mut out)?;
        Ok(out[0])
    }

    /// The exits of `vpls` (one to eight) under their roulettes `roulette` into `out`, VPL k
    /// with its bounds where `bounded(k)`: the own bounds of the plain ones in lanes, the
    /// others' by slc-bounds. Errors as [`Self::new`], for the first VPL it refuses.
    fn eight(
        vpls: &[&Vpl],
        roulette: &[StochasticParams],
        bounded: impl Fn(usize) -> bool,
        out: &mut [Self],
    ) -> Result<(), CullError> {
        let (formed, bounds) = own_bounds(vpls, |k| (roulette[k].delta(), roulette[k].xi()));
        let wanted = (0..vpls.len()).fold(0u8, |bits, k| {
            bits | u8::from(bounded(k) && !reflects_nothing(vpls[k])) << k
        });
        let boxed = box_bounds(vpls, roulette, wanted, |k, b| {
            out[k].box_bound = b.to_f32(vpls[k].position);
        });
        for (k, ((vpl, params), out)) in vpls.iter().zip(roulette).zip(out).enumerate() {
            let own = (formed >> k & 1 == 1).then(|| bounds.lane(k));
            let boxed = boxed >> k & 1 == 1;
            Self::with(vpl, params, bounded(k), own, boxed, out)?;
        }
        Ok(())
    }

    /// The exits of `vpl` with its bounds where `bounds`, its own bound `own` where the lanes
    /// formed it (a plain VPL that reflects something: its lobe is in slc-bounds' domain),
    /// else formed here by slc-bounds; its bound over boxes already in `out` where `boxed`
    /// (the lanes formed it, [`box_bounds`]), else formed here.
    fn with(
        vpl: &Vpl,
        params: &StochasticParams,
        bounds: bool,
        own: Option<LaneBound>,
        boxed: bool,
        out: &mut Self,
    ) -> Result<(), CullError> {
        let dark = reflects_nothing(vpl);
        let boxes = bounds && !dark && !boxed;
        // The glossy lobe, built once, where slc-bounds' own bound or the bound over boxes of
        // receivers needs it.
        let lobe = match (dark, vpl.lobe) {
            (false, VplLobe::Glossy) if boxes || own.is_none() => Some(vpl.glossy_lobe()?),
            _ => None,
        };
        // Its own bound: the lanes', or slc-bounds'; none for a VPL that reflects nothing.
        let local = match (dark, own, &lobe) {
            (true, _, _) => None,
            (false, Some(own), _) => Some(Own::Lanes(own)),
            (false, None, Some(lobe)) => Some(Own::Local(LocalBound::glossy(
                lobe,
                params,
                GlossyBound::Ellipsoid,
            )?)),
            (false, None, None) => Some(Own::Local(LocalBound::new(
                vpl,
                params,
                GlossyBound::Ellipsoid,
            )?)),
        };
        // Its bound over boxes: none where it reflects nothing or has no bounds; already in
        // `out` where the lanes formed it.
        let box_bound = match (dark || !bounds, boxed, &lobe) {
            (true, _, _) => Some(BoxBoundLanes::ALWAYS),
            (false, true, _) => None,
            (false, false, Some(lobe)) => Some(BoxBound::glossy(lobe, params).to_f32(vpl.position)),
            (false, false, None) => Some(lobe_box_bound(vpl, params)?.to_f32(vpl.position)),
        };
        // Without bounds, a VPL that reflects something keeps only its sign tests.
        let (stretch, center, limit) = match (local, bounds) {
            (None, _) => (DMat3::ZERO, DVec3::ZERO, -1.0),
            (Some(_), false) | (Some(Own::Local(LocalBound::Empty)), true) => {
                (DMat3::ZERO, DVec3::ZERO, f64::INFINITY)
            }
            (Some(Own::Lanes(b)), true) => {
                // S = diag(1/r_u, 1/r, 1/r) [ω_u t1 t2]ᵀ, any unit t1, t2 across ω_u.
                let (t1, t2) = b.axis.any_orthonormal_pair();
                let rows = DMat3::from_cols(b.axis / b.along, t1 / b.across, t2 / b.across);
                stretched(rows.transpose(), b.offset, b.along.max(b.across))
            }
            (Some(Own::Local(LocalBound::Sphere { center, radius_sq })), true) => {
                let radius = radius_sq.sqrt();
                stretched(
                    DMat3::from_diagonal(DVec3::splat(radius.recip())),
                    center,
                    radius,
                )
            }
            (
                Some(Own::Local(LocalBound::Spheroid {
                    center,
                    rotation,
                    semi_axes,
                })),
                true,
            ) => stretched(
                DMat3::from_diagonal(semi_axes.as_dvec3().recip())
                    * rotation.as_dmat3().transpose(),
                center,
                f64::from(semi_axes.max_element()),
            ),
        };
        let rows = stretch.transpose().to_cols_array().map(|v| v as f32);
        out.position = vpl.position;
        out.reach = Reach {
            normal: vpl.normal.to_array(),
            stretch: rows,
            center: center.as_vec3().to_array(),
            limit: limit as f32,
        };
        out.acceptance = Acceptance::new(vpl, params, dark);
        if let Some(box_bound) = box_bound {
            out.box_bound = box_bound;
        }
        Ok(())
    }

    /// Exits that reject every pair (the limit of the bound is −1).
    const NONE: Self = Self {
        position: Vec3::ZERO,
        reach: Reach {
            normal: [0.0; 3],
            stretch: [0.0; 9],
            center: [0.0; 3],
            limit: -1.0,
        },
        acceptance: Acceptance::NEVER,
        box_bound: BoxBoundLanes::ALWAYS,
    };

    /// The roulette (δ and its ξ) and, in parallel, the early exits of every VPL (`None`) or
    /// of the VPLs `listed` (ascending indices into `vpls`, for a caller that tests only
    /// listed pairs: entry j is VPL `listed[j]`'s, so that a million VPLs of which a few
    /// thousand are listed cost a few thousand exits). Only the VPLs it forms exits for are
    /// read: an unlisted VPL is not, so its ξ is not checked here (every bound-based culler
    /// has checked it when it made the lists; at a million VPLs one cache line of each record
    /// costs the shading about 7 ms). Errors as `StochasticParams::new` (for the first listed
    /// VPL out of its domain) and [`Self::new`], or on an index past the VPLs.
    pub fn of_frame(
        vpls: &[Vpl],
        delta: f32,
        listed: Option<&[u32]>,
    ) -> Result<(Vec<StochasticParams>, Vec<Self>), CullError> {
        match listed {
            Some(listed) => Self::of_listed(vpls, delta, listed, |_| true),
            None => {
                let every: Vec<u32> = (0..vpls.len() as u32).collect();
                Self::of_listed(vpls, delta, &every, |_| true)
            }
        }
    }

    /// [`Self::of_frame`] of the VPLs `listed`, entry j with its bounds ([`Self::new`]) where
    /// `bounded(j)`, else without ([`Self::without_bounds`]); [`ListedReach::form`] in new
    /// memory.
    pub fn of_listed(
        vpls: &[Vpl],
        delta: f32,
        listed: &[u32],
        bounded: impl Fn(usize) -> bool + Sync + Send,
    ) -> Result<(Vec<StochasticParams>, Vec<Self>), CullError> {
        let mut table = ListedReach::default();
        table.form(vpls, delta, listed, bounded)?;
        Ok((table.roulette, table.reach))
    }

    /// Whether the roulette of eq. (3) may accept this VPL at the offset `d = x − q` (formed
    /// in f32 as the shader forms it). False only where p(ωo, l) <= ξ for sure: outside the
    /// VPL's own bound (beyond a margin for the f32 rounding of the test), behind the VPL
    /// (ωo·n below −[`SIGN_MARGIN`]: I(ωo) = 0 by eq. 4), or where the shader's own p is
    /// not above ξ (the `acceptance` module).
    #[inline]
    pub fn may_accept(&self, d: Vec3) -> bool {
        let d = d.to_array();
        self.reach.may_accept(d) && self.acceptance.may_accept(self.reach.normal, d)
    }

    /// Whether the pair of this VPL and a receiver with unit normal `receiver_normal` at the
    /// offset `d = x − q` may contribute: [`Self::may_accept`], and the receiver not facing
    /// away (cos θx of eq. 1 not below −[`SIGN_MARGIN`]). False only where the contribution
    /// of eq. (1), weighted by eq. (3), is exactly 0.
    #[inline]
    pub fn may_contribute(&self, d: Vec3, receiver_normal: Vec3) -> bool {
        self.may_reach(d, receiver_normal)
            && self.acceptance.may_accept(self.reach.normal, d.to_array())
    }

    /// Whether p(ωo, l) > ξ may hold at some receiver in the box `[lo, hi]` (the receivers'
    /// f32 positions, from which the shader forms d = x − q): the VPL's bound over boxes
    /// (`slc_bounds::BoxBound` in f32, [`BoxBoundLanes`]). False only where every receiver
    /// in the box has p <= ξ; [`crate::ReceiverChunks`] tests it, eight VPLs at a time, before
    /// any pair.
    #[inline]
    pub fn box_may_exceed_xi(&self, lo: Vec3, hi: Vec3) -> bool {
        self.box_bound.may_exceed_xi(lo.to_array(), hi.to_array())
    }

    /// [`Self::may_contribute`] without the roulette: the bound and sign tests alone. A
    /// scalar caller that goes on to the shader's `vpl_contribution` uses this, since that
    /// forms the roulette first and stops there when it rejects: testing it here as well
    /// would only repeat it (the roulette pays off eight pairs at a time, in `ReceiverChunks`).
    #[inline]
    pub fn may_reach(&self, d: Vec3, receiver_normal: Vec3) -> bool {
        self.reach
            .may_contribute(d.to_array(), receiver_normal.to_array())
    }
}

/// The roulette and early exits of one frame's listed VPLs, entry j VPL `listed[j]`'s
/// ([`VplReach::of_listed`]), in memory a caller keeps from frame to frame: at a million
/// VPLs the table is some 170 MB, and forming it in fresh memory paid a page fault per 4 KiB,
/// about a third of its time (Sponza, RSM 1024: 125-135 ms fresh, 82-116 ms in memory glibc
/// was told to keep).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ListedReach {
    /// Entry j: the roulette of VPL `listed[j]` (δ and its ξ).
    pub roulette: Vec<StochasticParams>,
    /// Entry j: its early exits.
    pub reach: Vec<VplReach>,
}

impl ListedReach {
    /// Forms the table of `listed` (ascending indices into `vpls`) in place of the last one,
    /// as [`VplReach::of_listed`] forms it: the same entries, in this table's memory where it
    /// has room and is not much too large (`par::too_large_to_keep`). On an error the entries
    /// are not the frame's.
    pub fn form(
        &mut self,
        vpls: &[Vpl],
        delta: f32,
        listed: &[u32],
        bounded: impl Fn(usize) -> bool + Sync + Send,
    ) -> Result<(), CullError> {
        if let Some(&i) = listed.iter().find(|&&i| i as usize >= vpls.len()) {
            return Err(CullError::Input(format!(
                "listed VPL {i} of {} VPLs",
                vpls.len()
            )));
        }
        if crate::par::too_large_to_keep(self.reach.capacity(), listed.len()) {
            *self = Self::default();
        }
        let roulette_of = |i: u32| StochasticParams::new(delta, vpls[i as usize].xi);
        let Some(&first) = listed.first() else {
            self.roulette.clear();
            self.reach.clear();
            return Ok(());
        };
        // Every entry is written below; the old ones only fill the room.
        let placeholder = roulette_of(first)?;
        self.roulette.resize(listed.len(), placeholder);
        self.reach.resize(listed.len(), VplReach::NONE);
        // Eight listed VPLs at a time (their own bounds share lanes), in this table's memory,
        // each VPL's roulette formed here too: its record is read once, after it was asked
        // for (a pass of its own over the ξ read each record unasked first: the table of
        // Sponza's 67k listed VPLs at RSM 1024, 480x270, took 7.0-9.2 ms with it, 6.2-8.5
        // without, three alternated runs).
        self.reach
            .par_chunks_mut(8)
            .zip(self.roulette.par_chunks_mut(8))
            .zip(listed.par_chunks(8))
            .enumerate()
            .try_for_each(|(c, ((out, roulette), eight))| {
                // The records of the next eight VPLs, scattered over the whole array, are
                // asked for while these are formed.
                for &ahead in listed.iter().skip(8 * (c + 1)).take(8) {
                    crate::prefetch::prefetch(&vpls[ahead as usize]);
                }
                for (params, &i) in roulette.iter_mut().zip(eight) {
                    *params = roulette_of(i)?;
                }
                let last = eight.len() - 1;
                let group: [&Vpl; 8] = core::array::from_fn(|k| &vpls[eight[k.min(last)] as usize]);
                VplReach::eight(&group[..=last], roulette, |k| bounded(8 * c + k), out)
            })
            .map_err(|e| {
                // A roulette out of the domain first, the first in their order, whichever a
                // thread met.
                listed
                    .iter()
                    .find_map(|&i| roulette_of(i).err().map(CullError::from))
                    .unwrap_or(e)
            })
    }
}

/// A VPL's own bound, as formed: by the lanes, or by slc-bounds.
enum Own {
    Lanes(LaneBound),
    Local(LocalBound),
}

/// The stretch S, centre S·(c − q) and limit of a bound with centre `center` (relative to q)
/// and largest semi-axis `extent`. Near the bound's surface |d| <= |c − q| + extent, so each
/// component of S d − S·(c − q) is formed from terms of size at most
/// cond = ‖S‖ (|c − q| + extent) + |S·(c − q)| with about five f32 roundings (ε/2 each, the
/// stored S and S·(c − q) included): its error is below 2.5 ε cond, that of the squared norm
/// near 1 below 10 ε cond + 3 ε. The limit allows 32 ε cond + 8 ε, so a pair the f64 bound
/// contains is never rejected; farther out the error shrinks relative to the norm.
fn stretched(stretch: DMat3, center: DVec3, extent: f64) -> (DMat3, DVec3, f64) {
    let eps = f64::from(f32::EPSILON);
    let s_center = stretch * center;
    let norm = (stretch.x_axis.length_squared()
        + stretch.y_axis.length_squared()
        + stretch.z_axis.length_squared())
    .sqrt();
    let cond = norm * (center.length() + extent) + s_center.length();
    (stretch, s_center, 1.0 + 32.0 * eps * cond + 8.0 * eps)
}

/// Whether the shader's own tests give every pair of `vpl` exactly 0: ωi·n <= 0 (the one-sided
/// BRDF of eq. 6 and the diffuse lobe, the same f32 dot product the BRDF forms), no flux, or
/// for a diffuse VPL no channel with both flux and kd.
pub(crate) fn reflects_nothing(vpl: &Vpl) -> bool {
    let dark = match vpl.lobe {
        VplLobe::Diffuse => (vpl.flux.cmpeq(Vec3::ZERO) | vpl.brdf.kd.cmpeq(Vec3::ZERO)).all(),
        VplLobe::Glossy => vpl.flux.cmpeq(Vec3::ZERO).all(),
    };
    dark || vpl.normal.dot(vpl.omega_i) <= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{point_of, random_vpl, Rng};

    /// The lanes' own bounds keep every pair slc-bounds' own bounds keep: over random VPLs of both
    /// lobes (δ from 1e-9 to 1e3, flux from 1e-6 to 1e6, α from 0.01 to 1 and in half the groups
    /// from 0.01 to 0.012, ξ near 0 and 1), every offset on the surface of slc-bounds' bound (its
    /// `LocalBound`, grown by `BOUND_SLACK`) that exits formed with it pass, exits formed with the
    /// lanes' bound pass too (a shortfall of 2e-5 fails); the rest of the exits (the normal, the
    /// roulette, the bound over boxes, also formed eight at a time) is the same, and without
    /// bounds the exits are the same whichever formed the own bound.
    #[test]
    fn lane_bounds_keep_every_pair_of_slc_bounds() {
        let mut rng = Rng(0x5EED_0E81);
        let (mut formed, mut points) = (0, 0);
        for case in 0..2000 {
            let delta = 10f32.powf(rng.range(-9.0, 3.0));
            // Every other group at the sharpest lobes the lanes take (α 0.01 to 0.012), where
            // the axis's rounding, drawn out by the elongation, leaves the least margin.
            let vpls: Vec<Vpl> = (0..8)
                .map(|k| {
                    let mut v = random_vpl(&mut rng, case * 8 + k);
                    if case % 2 == 0 {
                        v.brdf.alpha = rng.range(0.01, 0.012);
                    }
                    v
                })
                .collect();
            let group: Vec<&Vpl> = vpls.iter().collect();
            let roulette: Vec<StochasticParams> = vpls
                .iter()
                .map(|v| StochasticParams::new(delta, v.xi).unwrap())
                .collect();
            let (lanes, bounds) = own_bounds(&group, |k| (delta, vpls[k].xi));
            let mut eight = [VplReach::NONE; 8];
            VplReach::eight(&group, &roulette, |_| true, &mut eight).unwrap();
            for (k, (vpl, params)) in vpls.iter().zip(&roulette).enumerate() {
                if lanes >> k & 1 == 0 {
                    continue;
                }
                formed += 1;
                let (mut own, mut scalar) = (VplReach::NONE, VplReach::NONE);
                VplReach::with(vpl, params, false, Some(bounds.lane(k)), false, &mut own).unwrap();
                VplReach::with(vpl, params, false, None, false, &mut scalar).unwrap();
                assert_eq!(own, scalar, "case {case}, lane {k}: without bounds");
                VplReach::with(vpl, params, true, Some(bounds.lane(k)), false, &mut own).unwrap();
                VplReach::with(vpl, params, true, None, false, &mut scalar).unwrap();
                assert_eq!(
                    (
                        own.position,
                        own.reach.normal,
                        own.acceptance,
                        own.box_bound
                    ),
                    (
                        scalar.position,
                        scalar.reach.normal,
                        scalar.acceptance,
                        scalar.box_bound
                    ),
                    "case {case}, lane {k}"
                );
                // Formed eight at a time, the bound over boxes from the lanes
                // (`box_bounds`) is the one formed one VPL at a time, bit for bit.
                assert_eq!(
                    format!("{:?}", eight[k].box_bound),
                    format!("{:?}", scalar.box_bound),
                    "case {case}, lane {k}: eight at a time"
                );
                let local = LocalBound::new(vpl, params, GlossyBound::Ellipsoid).unwrap();
                for _ in 0..40 {
                    let d = point_of(&local, &mut rng, [1.0, 1.0]);
                    let d = d.as_vec3().to_array();
                    if scalar.reach.may_accept(d) {
                        points += 1;
                        assert!(own.reach.may_accept(d), "case {case}, lane {k}: {d:?}");
                    }
                }
            }
        }
        assert!(
            formed > 5000 && points > 50_000,
            "{formed} formed, {points} points"
        );
    }
}
