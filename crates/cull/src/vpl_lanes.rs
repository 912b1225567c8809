//! Eight VPLs' own bounds at a time in f32 lanes: for the plain ones the radius r of eq. (12)
//! and the spheroid of eq. (13)-(15) of a glossy VPL, the sphere of section 6 of a diffuse
//! one, formed as slc-bounds forms them (`GlossyLobe::radius`, `Spheroid::new`,
//! `Sphere::diffuse`: the same formulas, G1/cos its own `g1_over_cos_lanes`) in lanes, grown
//! by `BOUND_SLACK` as every strategy grows them. The
//! others go through slc-bounds one at a time, which bounds them or names what is wrong.
//! `binned`'s scatter ([`crate::scatter_lanes`]) maps these bounds to pixels, and the
//! shading's early exits ([`crate::VplReach`]) test receivers against them: at a million
//! VPLs one VPL at a time waits on its chain of square roots and divisions, and eight lanes
//! share them.
//!
//! The lanes round differently from slc-bounds in a few places (r in f32 rather than f64,
//! the fifth power as three products): a few ulps, which the radius's extra 1e-5
//! ([`LANE_SLACK`]) covers before `BOUND_SLACK` (1e-3) grows the bound. Lobes sharper than
//! [`MIN_ALPHA`] are left to slc-bounds: there the f32 rounding of the axis, tilted by the
//! eccentricity 1/(2α), would eat into that slack.
use crate::reach::reflects_nothing;
use crate::vpl_bounds::BOUND_SLACK;
use glam::{DVec3, Vec3};
use slc_bounds::fresnel::cos_theta_h_max_lanes;
use slc_bounds::ggx::g1_over_cos_lanes;
use slc_bounds::lanes::{
    all3, clamp01, cross, dot, load_all, max, store_all, within, within1, Lanes8, Real, F8, M8,
};
use slc_bounds::{BoxBound, Fresnel, SchlickLobes, StochasticParams};
use slc_core::{Vpl, VplLobe};

/// The smallest α whose glossy VPLs the lanes bound.
const MIN_ALPHA: f32 = 0.01;

/// The radius's growth over its f32 rounding in the lanes.
const LANE_SLACK: f32 = 1e-5;

/// How far |v|² of a unit vector may be from 1 in the lanes: just inside slc-bounds' 1e-3 on
/// |v| ((1 ± 1e-3)² = 1 ± 2.001e-3), so that no vector the lanes take is one it refuses.
const UNIT_SQ_TOLERANCE: f32 = 1.99e-3;

/// The radii the lanes bound: far from f32's underflow and from an overflow of the
/// footprint's squares.
const RADII: [f32; 2] = [1e-12, 1e9];

/// Eight VPLs' own bounds: the spheroid `{c + R diag(along, across, across) w : |w| <= 1}`
/// through its unit `axis` ω_u (a sphere: along = across, axis n), centred `offset` = c − q
/// from the VPL, `length` = |c − q| along the axis; `relative` = q − eye. `empty` where a
/// VPL reflects nothing (ωi·n <= 0, no flux), `left` where it is not plain
/// ([`Self::plain`]) or its radius lies outside [`RADII`] (left to slc-bounds, whose f64
/// radius and overflow checks serve the extremes).
pub(crate) struct OwnBounds<L: Real> {
    pub relative: [L; 3],
    pub axis: [L; 3],
    pub along: L,
    pub across: L,
    pub length: L,
    pub offset: [L; 3],
    pub empty: L::Mask,
    pub left: L::Mask,
}

impl<L: Lanes8> OwnBounds<L> {
    /// The bounds of `group` for the roulette's δ and ξ of each lane (valid ones), positions
    /// relative to `eye`.
    #[inline(always)]
    pub(crate) fn of(group: &[&Vpl; 8], eye: Vec3, delta: &F8, xi: &F8) -> Self {
        let f = Fields::of(group, eye);
        let [relative, raw_normal, raw_omega, flux, fa, fb] = &f.vectors;
        let (relative, raw_normal, raw_omega) = (
            load_all(relative),
            load_all(raw_normal),
            load_all(raw_omega),
        );
        let (flux, fa, fb): ([L; 3], [L; 3], [L; 3]) = (load_all(flux), load_all(fa), load_all(fb));
        let (alpha, delta, xi) = (L::load(&f.alpha), L::load(delta), L::load(xi));
        let (glossy, kind) = (L::load_mask(&f.glossy), L::load_mask(&f.kind));
        let plain = kind
            & Self::plain(
                glossy,
                [relative, raw_normal, raw_omega, flux, fa],
                alpha,
                xi,
            );
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let (n, wi) = (over_length(raw_normal), over_length(raw_omega));
        let cos_i = dot(n, wi);
        let sin_i = {
            let c = cross(n, wi);
            dot(c, c).sqrt()
        };
        // F_max at θh_max (supplemental eq. 2): cos θh_max = cos θi / sqrt(2 (1 + sin θi)).
        let cos_h = cos_theta_h_max_lanes(cos_i, sin_i);
        let t = one - clamp01(cos_h);
        let t2 = t * t;
        let m = t2 * t2 * t;
        let peak: L = max(
            max(flux[0] * (fa[0] + fb[0] * m), flux[1] * (fa[1] + fb[1] * m)),
            flux[2] * (fa[2] + fb[2] * m),
        );
        // Glossy: r² = Φ F_max G1(ωi) / (4π δ ξ cos θi) (eq. 12), G1/cos in closed form;
        // diffuse: the peak range² = Φ kd / (π δ ξ) (section 6).
        let alpha_sq = alpha * alpha;
        let g1_over_cos = g1_over_cos_lanes(alpha_sq, max(cos_i, -cos_i));
        let factor = L::select(glossy, g1_over_cos * L::splat(0.25), one);
        let pi_delta = L::splat(core::f32::consts::PI) * delta;
        let r = L::sqrt(peak * factor / (pi_delta * xi)) * L::splat(1.0 + LANE_SLACK);
        // Nothing reflected: ωi·n <= 0 as the shader forms it (reach::reflects_nothing), or no
        // flux.
        let empty = !(dot(raw_normal, raw_omega).gt(zero) & peak.gt(zero));
        let left = !plain | (!empty & !(r.gt(L::splat(RADII[0])) & r.le(L::splat(RADII[1]))));
        // Glossy: the spheroid along ω_u = normalize(2 cos θi n − ωi), semi-axes
        // ((1 + α²)/(2α) r, r, r), centre q + (1 − α²)/(2α) r ω_u (eq. 13-15).
        let two_cos = L::splat(2.0) * cos_i;
        let reflected = over_length([
            two_cos * n[0] - wi[0],
            two_cos * n[1] - wi[1],
            two_cos * n[2] - wi[2],
        ]);
        let half_over_alpha = L::splat(0.5) / alpha;
        let along_glossy = (one + alpha_sq) * half_over_alpha * r;
        let offset_glossy = (one - alpha_sq) * half_over_alpha * r;
        // Diffuse (Sphere::diffuse): centre q + r (1/27)^(1/4) n, radius r (4/27)^(1/4).
        let (offset_diffuse, radius_diffuse) = (
            r * L::splat((1.0f32 / 27.0).powf(0.25)),
            r * L::splat((4.0f32 / 27.0).powf(0.25)),
        );
        let grown = L::splat((1.0 + BOUND_SLACK) as f32);
        let along = L::select(glossy, along_glossy, radius_diffuse) * grown;
        let across = L::select(glossy, r, radius_diffuse) * grown;
        let length = L::select(glossy, offset_glossy, offset_diffuse);
        let axis = [
            L::select(glossy, reflected[0], n[0]),
            L::select(glossy, reflected[1], n[1]),
            L::select(glossy, reflected[2], n[2]),
        ];
        Self {
            relative,
            axis,
            along,
            across,
            length,
            offset: [axis[0] * length, axis[1] * length, axis[2] * length],
            empty,
            left,
        }
    }

    /// Where a VPL of a [`lane_kind`] is plain: every input in the domain slc-bounds accepts
    /// (`[q − eye, n, ωi, Φ, F0 or kd]` finite, n unit, Φ non-negative, ξ in (0, 1) and
    /// normal), and for a glossy VPL ωi unit, α in [[`MIN_ALPHA`], 1] and F0 in [0, 1], for a
    /// diffuse one kd non-negative with Φ kd far from f32's overflow. Each comparison fails
    /// on NaN, and each limit lies inside slc-bounds' own, so a VPL it refuses is never
    /// plain; the others go through it, which bounds them or names what is wrong.
    #[inline(always)]
    fn plain(glossy: L::Mask, vectors: [[L; 3]; 5], alpha: L, xi: L) -> L::Mask {
        let [relative, normal, omega, flux, fa] = vectors;
        let (zero, one, big) = (L::splat(0.0), L::splat(1.0), L::splat(f32::MAX));
        let finite = all3(within(relative, -big, big)) & all3(within(omega, -big, big));
        let unit_sq = (
            L::splat(1.0 - UNIT_SQ_TOLERANCE),
            L::splat(1.0 + UNIT_SQ_TOLERANCE),
        );
        let common = finite
            & within1(dot(normal, normal), unit_sq.0, unit_sq.1)
            & all3(within(flux, zero, big))
            & xi.gt(L::splat(f32::MIN_POSITIVE))
            & one.gt(xi);
        let lobe_glossy = within1(dot(omega, omega), unit_sq.0, unit_sq.1)
            & within1(alpha, L::splat(MIN_ALPHA), one)
            & all3(within(fa, zero, one));
        let reflected = [flux[0] * fa[0], flux[1] * fa[1], flux[2] * fa[2]];
        let lobe_diffuse =
            all3(within(fa, zero, big)) & all3(within(reflected, zero, L::splat(1e38)));
        common & ((glossy & lobe_glossy) | (!glossy & lobe_diffuse))
    }

    /// The lanes' bounds as arrays, to be read one VPL at a time.
    #[inline(always)]
    pub(crate) fn store(&self) -> StoredBounds {
        StoredBounds {
            offset: store_all(&self.offset),
            axis: store_all(&self.axis),
            along: self.along.store(),
            across: self.across.store(),
        }
    }
}

/// [`OwnBounds`] stored ([`OwnBounds::store`]).
pub(crate) struct StoredBounds {
    offset: [F8; 3],
    axis: [F8; 3],
    along: F8,
    across: F8,
}

/// One VPL's own bound from the lanes in f64, as the f64 tests take it: the spheroid (or
/// sphere) centred `offset` from q, of semi-axes `along` its `axis` (unit in f64) and
/// `across` it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LaneBound {
    pub offset: DVec3,
    pub axis: DVec3,
    pub along: f64,
    pub across: f64,
}

impl StoredBounds {
    /// Lane `k`'s bound.
    #[inline(always)]
    pub(crate) fn lane(&self, k: usize) -> LaneBound {
        let at = |v: &F8| f64::from(v.0[k]);
        LaneBound {
            offset: DVec3::from(self.offset.each_ref().map(at)),
            axis: DVec3::from(self.axis.each_ref().map(at)).normalize(),
            along: at(&self.along),
            across: at(&self.across),
        }
    }
}

/// The own bounds of `vpls` (one to eight), VPL k under the roulette of δ and ξ
/// `delta_xi(k)`, and the lanes that formed one (bit k: `vpls[k]`, plain under a roulette
/// slc-bounds accepts, reflecting something by [`reflects_nothing`] and the lanes, with a
/// radius in [`RADII`]). The others are left to slc-bounds, which bounds them or names what
/// is wrong.
pub(crate) fn own_bounds(
    vpls: &[&Vpl],
    delta_xi: impl Fn(usize) -> (f32, f32),
) -> (u8, StoredBounds) {
    debug_assert!((1..=8).contains(&vpls.len()), "{} VPLs", vpls.len());
    let last = vpls.len() - 1;
    let group: [&Vpl; 8] = core::array::from_fn(|k| vpls[k.min(last)]);
    let roulette: [(f32, f32); 8] = core::array::from_fn(|k| delta_xi(k.min(last)));
    let delta = F8(roulette.map(|r| r.0));
    let xi = F8(roulette.map(|r| r.1));
    // As slc-bounds' callers see them: the roulette in its domain (a subnormal δ would give
    // the lanes a finite range), and `reflects_nothing`'s test.
    let mut scalar = 0;
    for (k, (vpl, (delta, xi))) in vpls.iter().zip(roulette).enumerate() {
        let ok = StochasticParams::new(delta, xi).is_ok() && !reflects_nothing(vpl);
        scalar |= u8::from(ok) << k;
    }
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        let (formed, bounds) = unsafe { own_bounds_avx2(&group, &delta, &xi) };
        return (formed & scalar, bounds);
    }
    let (formed, bounds) = own_bounds_in::<F8>(&group, &delta, &xi);
    (formed & scalar, bounds)
}

/// The bounds over boxes of receivers ([`BoxBound::glossy`]) of the VPLs `vpls` (one to
/// eight) that the lanes take, VPL k under the roulette `params[k]`, handed to `each(k, bound)`
/// for every k in `wanted` (bit k): the glossy ones of a [`lane_kind`] whose lobe slc-bounds
/// accepts, formed eight at a time by [`SchlickLobes::box_bounds`] (the same bounds bit for
/// bit). Returns those VPLs; the others are the caller's to bound one at a time, or to refuse.
pub(crate) fn box_bounds(
    vpls: &[&Vpl],
    params: &[StochasticParams],
    wanted: u8,
    each: impl FnMut(usize, BoxBound),
) -> u8 {
    debug_assert!((1..=8).contains(&vpls.len()), "{} VPLs", vpls.len());
    let wanted = vpls.iter().enumerate().fold(0u8, |bits, (k, v)| {
        let taken = wanted >> k & 1 == 1 && v.lobe == VplLobe::Glossy && lane_kind(v);
        bits | u8::from(taken) << k
    });
    if wanted == 0 {
        return 0;
    }
    let last = vpls.len() - 1;
    let group: [&Vpl; 8] = core::array::from_fn(|k| vpls[k.min(last)]);
    let fields = Fields::of(&group, Vec3::ZERO);
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { box_bounds_avx2(&fields, wanted, params, each) };
    }
    box_bounds_in::<F8>(&fields, wanted, params, each)
}

/// [`box_bounds_in`] in AVX registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn box_bounds_avx2(
    fields: &Fields,
    wanted: u8,
    params: &[StochasticParams],
    each: impl FnMut(usize, BoxBound),
) -> u8 {
    box_bounds_in::<slc_bounds::lanes_avx::A8>(fields, wanted, params, each)
}

/// [`box_bounds`] of the transposed `fields` in lanes of `L` (for a glossy VPL of a
/// [`lane_kind`], the fields' `a` is Schlick's F0).
#[inline(always)]
fn box_bounds_in<L: Lanes8>(
    fields: &Fields,
    wanted: u8,
    params: &[StochasticParams],
    each: impl FnMut(usize, BoxBound),
) -> u8 {
    let [_, normal, omega_i, flux, f0, _] = &fields.vectors;
    SchlickLobes::<L> {
        normal: load_all(normal),
        omega_i: load_all(omega_i),
        alpha: L::load(&fields.alpha),
        flux: load_all(flux),
        f0: load_all(f0),
    }
    .box_bounds(wanted, params, each)
}

/// [`own_bounds_in`] in AVX registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn own_bounds_avx2(group: &[&Vpl; 8], delta: &F8, xi: &F8) -> (u8, StoredBounds) {
    own_bounds_in::<slc_bounds::lanes_avx::A8>(group, delta, xi)
}

/// [`own_bounds`] in lanes of `L`: the lanes the lanes bound, and the bounds.
#[inline(always)]
fn own_bounds_in<L: Lanes8>(group: &[&Vpl; 8], delta: &F8, xi: &F8) -> (u8, StoredBounds) {
    let bounds = OwnBounds::<L>::of(group, Vec3::ZERO, delta, xi);
    (!L::bits(bounds.left | bounds.empty), bounds.store())
}

/// What the lanes model of a VPL's kind: its shading normal its geometric one, isotropic,
/// and glossy with Schlick's Fresnel factor or diffuse.
#[inline(always)]
fn lane_kind(vpl: &Vpl) -> bool {
    vpl.normal == vpl.geometric_normal
        && vpl.brdf.anisotropy.is_none()
        && !matches!(
            (vpl.lobe, vpl.brdf.fresnel),
            (VplLobe::Glossy, Fresnel::Dielectric(_))
        )
}

/// Eight VPLs' fields as lanes, each VPL read once: `[q − eye, n, ωi, Φ, a, b]` with
/// F(c) = a + b (1 − c)⁵ per channel (Schlick: (F0, 1 − F0); diffuse: (kd, 0)), α, and
/// the flags glossy and [`lane_kind`].
struct Fields {
    vectors: [[F8; 3]; 6],
    alpha: F8,
    glossy: M8,
    kind: M8,
}

impl Fields {
    /// The transposition of `group` (a plain loop: no closure, which in the AVX2 kernel
    /// would be a call per field and VPL).
    #[inline(always)]
    fn of(group: &[&Vpl; 8], eye: Vec3) -> Self {
        let mut f = Self {
            vectors: [[F8([0.0; 8]); 3]; 6],
            alpha: F8([0.0; 8]),
            glossy: M8([0; 8]),
            kind: M8([0; 8]),
        };
        for (k, v) in group.iter().enumerate() {
            let (a, b) = fresnel(v);
            let vectors = [v.position - eye, v.normal, v.omega_i, v.flux, a, b];
            for (lanes, value) in f.vectors.iter_mut().zip(vectors) {
                for (c, lane) in lanes.iter_mut().enumerate() {
                    lane.0[k] = value[c];
                }
            }
            f.alpha.0[k] = v.brdf.alpha;
            f.glossy.0[k] = u32::from(v.lobe == VplLobe::Glossy).wrapping_neg();
            f.kind.0[k] = u32::from(lane_kind(v)).wrapping_neg();
        }
        f
    }
}

/// `v` over its length (`check::unit`'s renormalisation). The mirror direction ω_u is
/// normalised here the same way, where `GlossyLobe::reflection` (glam's `normalize`,
/// `slc_bounds::lanes::normalize`) multiplies by 1/|v|: an ulp apart, which the own bounds'
/// slack covers; the bounds over boxes (`SchlickLobes::box_bounds`), which must equal
/// slc-bounds' bit for bit, form it as glam does.
#[inline(always)]
fn over_length<L: Real>(v: [L; 3]) -> [L; 3] {
    let len = dot(v, v).sqrt();
    [v[0] / len, v[1] / len, v[2] / len]
}

/// A plain VPL's F(c) = a + b (1 − c)⁵ per channel as (a, b): Schlick's (F0, 1 − F0) for a
/// glossy VPL, (kd, 0) for a diffuse one (Φ kd is its reflected flux).
#[inline(always)]
fn fresnel(vpl: &Vpl) -> (Vec3, Vec3) {
    match (vpl.lobe, vpl.brdf.fresnel) {
        (VplLobe::Glossy, Fresnel::Schlick(f0)) => (f0, Vec3::ONE - f0),
        _ => (vpl.brdf.kd, Vec3::ZERO),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{random_vpl, Rng};
    use crate::vpl_bounds::lobe_box_bound;
    use slc_bounds::Anisotropy;

    /// A random VPL (`random_vpl`), one in three changed into one the lanes leave or refuse:
    /// tilted, anisotropic, with a dielectric's Fresnel factor, α 0 or above 1, a NaN or
    /// non-unit normal, a negative flux or F0 above 1.
    fn any_vpl(rng: &mut Rng, id: u32) -> Vpl {
        let mut v = random_vpl(rng, id);
        let t = v.normal.any_orthonormal_vector();
        match (rng.f32() * 30.0) as u32 {
            0 => v.geometric_normal = (v.normal + 0.01 * t).normalize(),
            1 => {
                v.brdf.anisotropy = Some(Anisotropy {
                    tangent: t,
                    alpha_t: 0.5,
                })
            }
            2 => v.brdf.fresnel = Fresnel::Dielectric(1.5),
            3 => v.brdf.alpha = 0.0,
            4 => v.brdf.alpha = 1.5,
            5 => v.normal.x = f32::NAN,
            6 => v.omega_i *= 1.01,
            7 => v.flux.y = -1.0,
            8 => v.brdf.fresnel = Fresnel::Schlick(Vec3::new(0.5, 1.5, 0.5)),
            9 => v.normal *= 1.0005,
            _ => {}
        }
        v.geometric_normal = match v.geometric_normal == v.normal || rng.f32() < 0.5 {
            true => v.geometric_normal,
            false => v.normal,
        };
        v
    }

    /// `box_bounds` hands on exactly the wanted glossy VPLs of a lane kind whose lobe
    /// slc-bounds accepts, each with slc-bounds' own bound bit for bit (`lobe_box_bound`).
    #[test]
    fn box_bounds_are_slc_bounds_bit_for_bit() {
        let mut rng = Rng(0xB0B0_0E16);
        let (mut handed, mut left) = (0, 0);
        for case in 0..4000u32 {
            let n = 1 + case as usize % 8;
            let vpls: Vec<Vpl> = (0..n)
                .map(|k| any_vpl(&mut rng, 8 * case + k as u32))
                .collect();
            let group: Vec<&Vpl> = vpls.iter().collect();
            let delta = 10f32.powf(rng.range(-9.0, 3.0));
            let params: Vec<StochasticParams> = vpls
                .iter()
                .map(|v| StochasticParams::new(delta, v.xi).unwrap())
                .collect();
            let wanted = if case % 2 == 0 {
                u8::MAX
            } else {
                rng.f32().to_bits() as u8
            };
            let mut got = vec![None; n];
            let bits = box_bounds(&group, &params, wanted, |k, b| {
                got[k] = Some(format!("{b:?}"))
            });
            for (k, (v, p)) in vpls.iter().zip(&params).enumerate() {
                let expected = (wanted >> k & 1 == 1 && v.lobe == VplLobe::Glossy && lane_kind(v))
                    .then(|| lobe_box_bound(v, p).ok().map(|b| format!("{b:?}")))
                    .flatten();
                assert_eq!(got[k], expected, "case {case}, VPL {k}: {v:?}");
                assert_eq!(bits >> k & 1 == 1, expected.is_some());
                handed += usize::from(expected.is_some());
                left += usize::from(expected.is_none());
            }
            assert_eq!(u16::from(bits) >> n, 0, "no lane past the VPLs");
        }
        assert!(handed > 5000 && left > 5000, "{handed} handed, {left} left");
    }
}
