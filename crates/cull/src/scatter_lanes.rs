//! The `binned` strategy's scatter, eight VPLs at a time: for the plain ones the radius r of
//! eq. (12) and the spheroid of eq. (13)-(15) of a glossy VPL, the sphere of section 6 of a
//! diffuse one, formed with slc-bounds' own operations (`GlossyLobe::radius`,
//! `Spheroid::new`, `Sphere::diffuse`) in f32 lanes, then their footprints
//! ([`crate::footprint`]); the others through slc-bounds ([`Screen::scatter`]). At a million
//! VPLs the bounds are most of the culling, and one VPL at a time they wait on their chains
//! of square roots and divisions; eight lanes share them.
//!
//! The lanes round differently from slc-bounds in a few places (r in f32 rather than f64,
//! the fifth power as three products): a few ulps, which the radius's extra 1e-5 covers
//! before `BOUND_SLACK` (1e-3) grows the bound as it grows every strategy's. Lobes sharper
//! than [`MIN_ALPHA`] are left to slc-bounds: there the f32 rounding of the axis, tilted by
//! the eccentricity 1/(2α), would eat into that slack.
use crate::footprint::{footprint, Bound, Footprint, ScreenMap};
use crate::scatter::{PixelTest, Scattered, Screen};
use crate::vpl_bounds::BOUND_SLACK;
use glam::{DVec3, Vec3};
use slc_bounds::lanes::{
    clamp01, cross, dot, load_all, max, splat_all, store_all, Lanes8, Real, F8, M8,
};
use slc_bounds::Fresnel;
use slc_core::{CullError, Vpl, VplLobe};

/// The smallest α whose glossy VPLs the lanes bound.
const MIN_ALPHA: f32 = 0.01;

/// The radius's growth over its f32 rounding in the lanes.
const LANE_SLACK: f32 = 1e-5;

/// How far |v|² of a unit vector may be from 1 in the lanes: just inside slc-bounds' 1e-3 on
/// |v| ((1 ± 1e-3)² = 1 ± 2.001e-3), so that no vector the lanes take is one it refuses.
const UNIT_SQ_TOLERANCE: f32 = 1.99e-3;

/// Each of `vpls` (numbered from `first`) that covers a pixel for the roulette's δ (a valid
/// one), in `out` in their order: eight at a time in lanes, which bound the plain ones (see
/// [`Lanes::plain`]); the others, and the lanes' extremes, go through slc-bounds one at a
/// time ([`Screen::scatter`]), which bounds them or names what is wrong.
pub(crate) fn scatter(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut Vec<Scattered>,
) -> Result<(), CullError> {
    out.clear();
    for (group, eight) in vpls.chunks(8).enumerate() {
        let first = first + 8 * group as u32;
        let mut placed = [None; 8];
        let left = scatter_lanes(screen, eight, first, delta, &mut placed);
        for (k, (vpl, placed)) in eight.iter().zip(&placed).enumerate() {
            match left >> k & 1 {
                1 => out.extend(screen.scatter(vpl, first + k as u32, delta)?),
                _ => out.extend(placed),
            }
        }
    }
    Ok(())
}

/// The lanes of [`scatter`] for one to eight VPLs: the entry of `out` (all `None` on entry)
/// of each VPL that covers a pixel. Returns the lanes left to slc-bounds (bit k: `vpls[k]`): those not plain,
/// and those whose radius under- or overflows the range the lanes keep exact.
fn scatter_lanes(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut [Option<Scattered>; 8],
) -> u8 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { scatter_avx2(screen, vpls, first, delta, out) };
    }
    scatter_in::<F8>(screen, vpls, first, delta, out)
}

/// [`scatter_in`] in AVX registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn scatter_avx2(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut [Option<Scattered>; 8],
) -> u8 {
    scatter_in::<slc_bounds::lanes_avx::A8>(screen, vpls, first, delta, out)
}

/// [`scatter_lanes`] in lanes of `L`. A lane whose footprint ends before the image or starts
/// after it (with a pixel to spare, [`Screen::edges`]) is dropped here, before its test is
/// formed: at a million VPLs about half lie off screen.
#[inline(always)]
fn scatter_in<L: Lanes8>(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut [Option<Scattered>; 8],
) -> u8 {
    let last = vpls.len() - 1;
    let group: [&Vpl; 8] = core::array::from_fn(|k| &vpls[k.min(last)]);
    let lanes = Lanes::<L>::of(&group, screen.eye, delta);
    let [x, y, z] = screen.map.rows;
    let [sx, sy] = screen.map.scale;
    let [ox, oy] = screen.map.offset;
    let screen_map = ScreenMap {
        rows: [splat_all(&x), splat_all(&y), splat_all(&z)],
        scale: [L::splat(sx), L::splat(sy)],
        offset: [L::splat(ox), L::splat(oy)],
        near: L::splat(screen.map.near),
    };
    let f = footprint(&lanes.bound, &screen_map);
    let [before, after] = screen.edges;
    let off_screen = !f.everywhere
        & (L::splat(before[0]).gt(f.hi[0])
            | L::splat(before[1]).gt(f.hi[1])
            | f.lo[0].gt(L::splat(after[0]))
            | f.lo[1].gt(L::splat(after[1])));
    // The lanes holding a VPL (past the last, they repeat it).
    let held = u8::MAX >> (7 - last);
    let left = L::bits(lanes.left) & held;
    let covers = !L::bits(lanes.empty | f.nowhere | off_screen) & !left & held;
    if covers == 0 {
        return left;
    }
    let (lo, hi) = (store_all(&f.lo), store_all(&f.hi));
    let (center, axis) = (store_all(&lanes.offset), store_all(&lanes.bound.axis));
    let (along, across) = (lanes.bound.along.store(), lanes.bound.across.store());
    let everywhere = L::bits(f.everywhere);
    for (k, (vpl, slot)) in vpls.iter().zip(out.iter_mut()).enumerate() {
        if covers >> k & 1 == 0 {
            continue;
        }
        let lane = |v: &F8| v.0[k];
        let footprint = Footprint {
            lo: lo.each_ref().map(lane),
            hi: hi.each_ref().map(lane),
            nowhere: false,
            everywhere: everywhere >> k & 1 == 1,
        };
        *slot = screen.place(vpl, first + k as u32, &footprint, || {
            PixelTest::new(
                vpl.position.as_dvec3(),
                vpl.normal.as_dvec3(),
                DVec3::from(center.each_ref().map(|c| f64::from(lane(c)))),
                DVec3::from(axis.each_ref().map(|c| f64::from(lane(c)))).normalize(),
                f64::from(lane(&along)),
                f64::from(lane(&across)),
            )
        });
    }
    left
}

/// Eight VPLs' bounds: for the footprint, and the centre's offset from q for the pixels'
/// test; `empty` where a VPL reflects nothing (ωi·n <= 0, no flux), `left` where it is not
/// plain ([`Self::plain`]) or its radius lies outside [`RADII`] (left to slc-bounds, whose
/// f64 radius and overflow checks serve the extremes).
struct Lanes<L: Real> {
    bound: Bound<L>,
    offset: [L; 3],
    empty: L::Mask,
    left: L::Mask,
}

/// The radii the lanes bound: far from f32's underflow and from an overflow of the
/// footprint's squares.
const RADII: [f32; 2] = [1e-12, 1e9];

impl<L: Lanes8> Lanes<L> {
    /// The bounds of `group` for δ = `delta`, centres relative to `eye`.
    #[inline(always)]
    fn of(group: &[&Vpl; 8], eye: Vec3, delta: f32) -> Self {
        let f = Fields::of(group, eye);
        let [relative, raw_normal, raw_omega, flux, fa, fb] = &f.vectors;
        let (relative, raw_normal, raw_omega) = (
            load_all(relative),
            load_all(raw_normal),
            load_all(raw_omega),
        );
        let (flux, fa, fb): ([L; 3], [L; 3], [L; 3]) = (load_all(flux), load_all(fa), load_all(fb));
        let (alpha, xi) = (L::load(&f.alpha), L::load(&f.xi));
        let (glossy, kind) = (L::load_mask(&f.glossy), L::load_mask(&f.kind));
        let plain = kind
            & Self::plain(
                glossy,
                [relative, raw_normal, raw_omega, flux, fa],
                alpha,
                xi,
            );
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let (n, wi) = (normalize(raw_normal), normalize(raw_omega));
        let cos_i = dot(n, wi);
        let sin_i = {
            let c = cross(n, wi);
            dot(c, c).sqrt()
        };
        // F_max at θh_max (supplemental eq. 2): cos θh_max = cos θi / sqrt(2 (1 + sin θi)).
        let cos_h = clamp01(cos_i) / (L::splat(2.0) * (one + clamp01(sin_i))).sqrt();
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
        let c = max(cos_i, -cos_i);
        let g1_over_cos = L::splat(2.0) / (c + ((one - alpha_sq) * c * c + alpha_sq).sqrt());
        let factor = L::select(glossy, g1_over_cos * L::splat(0.25), one);
        let pi_delta = L::splat(core::f32::consts::PI * delta);
        let r = L::sqrt(peak * factor / (pi_delta * xi)) * L::splat(1.0 + LANE_SLACK);
        // Nothing reflected: ωi·n <= 0 as the shader forms it (reach::reflects_nothing), or no
        // flux.
        let empty = !(dot(raw_normal, raw_omega).gt(zero) & peak.gt(zero));
        let left = !plain | (!empty & !(r.gt(L::splat(RADII[0])) & r.le(L::splat(RADII[1]))));
        // Glossy: the spheroid along ω_u = normalize(2 cos θi n − ωi), semi-axes
        // ((1 + α²)/(2α) r, r, r), centre q + (1 − α²)/(2α) r ω_u (eq. 13-15).
        let two_cos = L::splat(2.0) * cos_i;
        let reflected = normalize([
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
        let offset = [axis[0] * length, axis[1] * length, axis[2] * length];
        let center = [
            relative[0] + offset[0],
            relative[1] + offset[1],
            relative[2] + offset[2],
        ];
        let size = dot(relative, relative).sqrt() + length + along;
        Self {
            bound: Bound {
                center,
                axis,
                along,
                across,
                size,
            },
            offset,
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

/// Where `lo <= v <= hi` (false for NaN).
#[inline(always)]
fn within1<L: Real>(v: L, lo: L, hi: L) -> L::Mask {
    !lo.gt(v) & v.le(hi)
}

/// [`within1`] per component.
#[inline(always)]
fn within<L: Real>(v: [L; 3], lo: L, hi: L) -> [L::Mask; 3] {
    [
        within1(v[0], lo, hi),
        within1(v[1], lo, hi),
        within1(v[2], lo, hi),
    ]
}

/// Where all three hold.
#[inline(always)]
fn all3<M: core::ops::BitAnd<Output = M> + Copy>(m: [M; 3]) -> M {
    m[0] & m[1] & m[2]
}

/// Eight VPLs' fields as lanes, each VPL read once: `[q − eye, n, ωi, Φ, a, b]` with
/// F(c) = a + b (1 − c)⁵ per channel (Schlick: (F0, 1 − F0); diffuse: (kd, 0)), α, ξ, and
/// the flags glossy and [`lane_kind`].
struct Fields {
    vectors: [[F8; 3]; 6],
    alpha: F8,
    xi: F8,
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
            xi: F8([0.0; 8]),
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
            f.xi.0[k] = v.xi;
            f.glossy.0[k] = u32::from(v.lobe == VplLobe::Glossy).wrapping_neg();
            f.kind.0[k] = u32::from(lane_kind(v)).wrapping_neg();
        }
        f
    }
}

/// `v` over its length (`check::unit`'s renormalisation).
#[inline(always)]
fn normalize<L: Real>(v: [L; 3]) -> [L; 3] {
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
    use crate::test_rng::Rng;
    use crate::view::CullView;
    use crate::vpl_bounds::LocalBound;
    use slc_bounds::{Brdf, StochasticParams};
    use slc_core::{Camera, Interleaving};

    fn random_vpl(rng: &mut Rng, id: u32) -> Vpl {
        let unit = |rng: &mut Rng| loop {
            let v = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            if v.length_squared() > 1e-3 && v.length_squared() <= 1.0 {
                break v.normalize();
            }
        };
        let normal = unit(rng);
        let mut omega_i = unit(rng);
        if omega_i.dot(normal) < 0.0 && rng.f32() < 0.9 {
            omega_i = -omega_i;
        }
        Vpl {
            position: Vec3::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-20.0, 2.0),
            ),
            normal,
            geometric_normal: normal,
            omega_i,
            flux: Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 10f32.powf(rng.range(-6.0, 6.0)),
            brdf: Brdf {
                kd: Vec3::new(rng.f32(), rng.f32(), rng.f32()),
                fresnel: Fresnel::Schlick(Vec3::new(rng.f32(), rng.f32(), rng.f32())),
                alpha: 10f32.powf(rng.range(-2.0, 0.0)),
                anisotropy: None,
            },
            lobe: if rng.f32() < 0.7 {
                VplLobe::Glossy
            } else {
                VplLobe::Diffuse
            },
            id,
            xi: if rng.f32() < 0.2 {
                [1e-6, 1.0 - 1e-6][rng.f32().round() as usize]
            } else {
                rng.range(1e-4, 1.0)
            },
        }
    }

    /// The lanes bound plain VPLs (δ from 1e-9 to 1e3, flux from 1e-6 to 1e6, α from 0.01
    /// to 1, ξ near 0 and 1) at least as far as slc-bounds does: every point of slc-bounds'
    /// bound (its `LocalBound`, grown by `BOUND_SLACK`) passes the lanes' pixel test, where it
    /// is not behind the VPL, and every pixel the scalar path places the VPL on the lanes
    /// place it on too.
    #[test]
    fn lanes_contain_the_scalar_bounds() {
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 1.2).unwrap();
        let (w, h) = (96, 64);
        let view = CullView::new(&cam, w, h).unwrap();
        let screen = Screen::new(&view, w, h, Interleaving { k: 2, seed: 1 }, 0.0, 0.05);
        let mut rng = Rng(0x0B14_ED42);
        let (mut in_lanes, mut placed, mut points) = (0, 0, 0);
        for case in 0..3000 {
            let delta = 10f32.powf(rng.range(-9.0, 3.0));
            let vpls: Vec<Vpl> = (0..8).map(|k| random_vpl(&mut rng, case * 8 + k)).collect();
            let mut out = [None; 8];
            let left = scatter_lanes(&screen, &vpls, 0, delta, &mut out);
            for (k, vpl) in vpls.iter().enumerate() {
                let scalar = screen.scatter(vpl, k as u32, delta).unwrap();
                if left >> k & 1 == 1 {
                    continue;
                }
                in_lanes += 1;
                let lanes = out[k];
                let (Some(s), Some(l)) = (scalar, lanes) else {
                    assert!(scalar.is_none(), "case {case}, lane {k}: {vpl:?}");
                    continue;
                };
                placed += 1;
                let [a0, b0, a1, b1] = s.pixels;
                let [c0, d0, c1, d1] = l.pixels;
                assert!(
                    c0 <= a0 && d0 <= b0 && c1 >= a1 && d1 >= b1,
                    "case {case}: {s:?} {l:?}"
                );
                let params = StochasticParams::new(delta, vpl.xi).unwrap();
                let local = LocalBound::new(vpl, &params, crate::GlossyBound::Ellipsoid).unwrap();
                let (center, rotation, semi) = match local {
                    LocalBound::Sphere { center, radius_sq } => (
                        center,
                        glam::DMat3::IDENTITY,
                        glam::DVec3::splat(radius_sq.sqrt()),
                    ),
                    LocalBound::Spheroid {
                        center,
                        rotation,
                        semi_axes,
                    } => (center, rotation.as_dmat3(), semi_axes.as_dvec3()),
                    LocalBound::Empty => unreachable!("placed"),
                };
                for _ in 0..40 {
                    let u = glam::DVec3::new(
                        rng.range64(-1.0, 1.0),
                        rng.range64(-1.0, 1.0),
                        rng.range64(-1.0, 1.0),
                    );
                    let Some(u) = u.try_normalize() else { continue };
                    let d = center + rotation * (semi * u * rng.range64(0.99, 1.0));
                    let x = (vpl.position.as_dvec3() + d).as_vec3();
                    if s.test.contains(x) {
                        points += 1;
                        assert!(l.test.contains(x), "case {case}: {d} in {local:?}");
                    }
                }
            }
        }
        assert!(
            in_lanes > 20_000 && placed > 1000 && points > 10_000,
            "{in_lanes} in lanes, {placed} placed, {points} points"
        );
    }

    /// Every VPL outside the domain the lanes model is left to slc-bounds, which refuses it
    /// or bounds it itself: one field at a time made non-finite, non-unit, negative, out of
    /// range or of another kind, in each lane of a group of otherwise plain VPLs (whose
    /// lanes are taken).
    #[test]
    fn lanes_leave_every_vpl_they_do_not_model() {
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 1.2).unwrap();
        let view = CullView::new(&cam, 64, 64).unwrap();
        let screen = Screen::new(&view, 64, 64, Interleaving { k: 2, seed: 1 }, 0.0, 0.05);
        let glossy = Vpl {
            position: Vec3::new(0.0, -1.0, 0.0),
            normal: Vec3::Y,
            geometric_normal: Vec3::Y,
            omega_i: Vec3::new(0.6, 0.8, 0.0),
            flux: Vec3::splat(1.0),
            brdf: Brdf {
                kd: Vec3::splat(0.5),
                fresnel: Fresnel::Schlick(Vec3::splat(0.04)),
                alpha: 0.2,
                anisotropy: None,
            },
            lobe: VplLobe::Glossy,
            id: 0,
            xi: 0.5,
        };
        let diffuse = Vpl {
            lobe: VplLobe::Diffuse,
            ..glossy
        };
        type Change = (&'static str, fn(&mut Vpl));
        let changes: [Change; 22] = [
            ("NaN position", |v| v.position.x = f32::NAN),
            ("infinite position", |v| v.position.z = f32::INFINITY),
            ("NaN ωi", |v| v.omega_i.y = f32::NAN),
            ("normal 0.2% long", |v| v.normal *= 1.002),
            ("normal 0.2% short", |v| v.normal *= 0.998),
            ("NaN normal", |v| v.normal = Vec3::NAN),
            ("negative flux", |v| v.flux.y = -1.0),
            ("NaN flux", |v| v.flux.z = f32::NAN),
            ("infinite flux", |v| v.flux.x = f32::INFINITY),
            ("ξ 0", |v| v.xi = 0.0),
            ("ξ 1", |v| v.xi = 1.0),
            ("ξ subnormal", |v| v.xi = f32::MIN_POSITIVE / 2.0),
            ("NaN ξ", |v| v.xi = f32::NAN),
            ("a shading normal", |v| {
                v.normal = Vec3::new(0.1, 1.0, 0.0).normalize()
            }),
            ("anisotropic", |v| {
                v.brdf.anisotropy = Some(slc_bounds::Anisotropy {
                    tangent: Vec3::X,
                    alpha_t: 0.5,
                })
            }),
            ("ωi 0.2% long (glossy)", |v| v.omega_i *= 1.002),
            ("α 0.005 (glossy)", |v| v.brdf.alpha = 0.005),
            ("α 1.5 (glossy)", |v| v.brdf.alpha = 1.5),
            ("F0 above 1 (glossy)", |v| {
                v.brdf.fresnel = Fresnel::Schlick(Vec3::new(0.5, 1.5, 0.5))
            }),
            ("dielectric (glossy)", |v| {
                v.brdf.fresnel = Fresnel::Dielectric(1.5)
            }),
            ("negative kd (diffuse)", |v| v.brdf.kd.x = -0.1),
            ("Φ kd overflowing (diffuse)", |v| {
                (v.flux, v.brdf.kd) = (Vec3::splat(3e38), Vec3::splat(2.0))
            }),
        ];
        for base in [glossy, diffuse] {
            let mut out = [None; 8];
            let eight = [base; 8];
            assert_eq!(scatter_lanes(&screen, &eight, 0, 1e-3, &mut out), 0);
            assert!(out.iter().all(Option::is_some), "{base:?}");
            for (what, change) in changes {
                // A change of one lobe's fields is tried on that lobe only.
                let other = match base.lobe {
                    VplLobe::Glossy => "(diffuse)",
                    VplLobe::Diffuse => "(glossy)",
                };
                if what.ends_with(other) {
                    continue;
                }
                for k in 0..8 {
                    let mut group = [base; 8];
                    change(&mut group[k]);
                    let left = scatter_lanes(&screen, &group, 0, 1e-3, &mut [None; 8]);
                    assert_eq!(left, 1 << k, "{what} in lane {k} of {:?}", base.lobe);
                }
            }
        }
    }
}
