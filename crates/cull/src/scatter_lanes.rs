//! The `binned` strategy's scatter, eight VPLs at a time: the plain VPLs' own bounds in f32
//! lanes ([`crate::vpl_lanes`]), then their footprints ([`crate::footprint`]); the others
//! through slc-bounds ([`Screen::scatter`]).
use crate::footprint::{footprint, Bound, ScreenMap};
use crate::prefetch::prefetch;
use crate::rectangles::Footprints;
use crate::scatter::{whole, PixelTest, Scattered, Screen};
use crate::vpl_lanes::OwnBounds;
use slc_bounds::lanes::{dot, splat_all, store_all, Lanes8, F8};
use slc_core::{CullError, Vpl};

/// Each of `vpls` (numbered from `first`) that covers a pixel for the roulette's δ (a valid
/// one), in `out` in their order: eight at a time in lanes, which bound the plain ones (see
/// [`crate::vpl_lanes`]); the others, and the lanes' extremes, go through slc-bounds one at a
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
        // The next eight records asked for while these are bounded: without the hint the
        // lanes wait on each group's first read (docs/many-vpls.md, "The next eight records
        // asked for"). A hint only: the results are the same.
        for next in vpls.iter().skip(8 * group + 8).take(8) {
            prefetch(next);
        }
        let first = first + 8 * group as u32;
        scatter_lanes(screen, eight, first, delta, out, |vpl, index| {
            screen.scatter(vpl, index, delta)
        })?;
    }
    Ok(())
}

/// The lanes of [`scatter`] for one to eight VPLs (numbered from `first`): pushes each VPL
/// that covers a pixel onto `out`, in their order. The lanes bound the plain ones; the
/// others (not plain, or with a radius that under- or overflows the range the lanes keep
/// exact) are left to `left_to` (slc-bounds, [`Screen::scatter`], which bounds them or
/// names what is wrong), whose first error is returned. The VPLs are pushed as they are
/// placed, lane by lane (an array of eight entries copied onto `out` afterwards cost a
/// copy of each and a branch per lane more).
fn scatter_lanes(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut Vec<Scattered>,
    left_to: impl FnMut(&Vpl, u32) -> Result<Option<Scattered>, CullError>,
) -> Result<(), CullError> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { scatter_avx2(screen, vpls, first, delta, out, left_to) };
    }
    scatter_in::<F8>(screen, vpls, first, delta, out, left_to)
}

/// [`scatter_in`] in AVX registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn scatter_avx2(
    screen: &Screen,
    vpls: &[Vpl],
    first: u32,
    delta: f32,
    out: &mut Vec<Scattered>,
    left_to: impl FnMut(&Vpl, u32) -> Result<Option<Scattered>, CullError>,
) -> Result<(), CullError> {
    scatter_in::<slc_bounds::lanes_avx::A8>(screen, vpls, first, delta, out, left_to)
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
    out: &mut Vec<Scattered>,
    mut left_to: impl FnMut(&Vpl, u32) -> Result<Option<Scattered>, CullError>,
) -> Result<(), CullError> {
    let last = vpls.len() - 1;
    let group: [&Vpl; 8] = core::array::from_fn(|k| &vpls[k.min(last)]);
    let xi = F8(core::array::from_fn(|k| group[k].xi));
    let lanes = OwnBounds::<L>::of(&group, screen.eye, &F8([delta; 8]), &xi);
    let bound = Bound {
        center: [
            lanes.relative[0] + lanes.offset[0],
            lanes.relative[1] + lanes.offset[1],
            lanes.relative[2] + lanes.offset[2],
        ],
        axis: lanes.axis,
        along: lanes.along,
        across: lanes.across,
        size: dot(lanes.relative, lanes.relative).sqrt() + lanes.length + lanes.along,
    };
    let [x, y, z] = screen.map.rows;
    let [sx, sy] = screen.map.scale;
    let [ox, oy] = screen.map.offset;
    let screen_map = ScreenMap {
        rows: [splat_all(&x), splat_all(&y), splat_all(&z)],
        scale: [L::splat(sx), L::splat(sy)],
        offset: [L::splat(ox), L::splat(oy)],
        near: L::splat(screen.map.near),
    };
    let f = footprint(&bound, &screen_map);
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
    if covers | left == 0 {
        return Ok(());
    }
    let mut footprints = Footprints {
        lo: store_all(&f.lo),
        hi: store_all(&f.hi),
        subregions: [[0; 2]; 8],
        sizes: [[0; 2]; 8],
    };
    let stored = lanes.store();
    let everywhere = L::bits(f.everywhere);
    // Each covering lane's subregion, then all eight rectangles at once.
    let mut lanes_left = covers;
    while lanes_left != 0 {
        let k = lanes_left.trailing_zeros() as usize;
        lanes_left &= lanes_left - 1;
        let subregion = screen.subregions.of_vpl(vpls[k].id);
        footprints.subregions[k] = subregion;
        footprints.sizes[k] = screen.subregions.size(subregion);
    }
    let (rectangles, filled) = screen.rectangles(&footprints);
    let Footprints {
        subregions, sizes, ..
    } = footprints;
    let mut todo = (covers & (filled | everywhere)) | left;
    while todo != 0 {
        let k = todo.trailing_zeros() as usize;
        todo &= todo - 1;
        let (vpl, index) = (&vpls[k], first + k as u32);
        if left >> k & 1 == 1 {
            out.extend(left_to(vpl, index)?);
            continue;
        }
        let pixels = match everywhere >> k & 1 {
            1 => match whole(sizes[k]) {
                Some(pixels) => pixels,
                None => continue,
            },
            _ => rectangles[k],
        };
        let b = stored.lane(k);
        out.push(Scattered {
            index,
            subregion: subregions[k],
            test: PixelTest::new(
                vpl.position.as_dvec3(),
                vpl.normal.as_dvec3(),
                b.offset,
                b.axis,
                b.along,
                b.across,
            ),
            pixels,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{point_of, random_vpl, Rng};
    use crate::view::CullView;
    use crate::vpl_bounds::LocalBound;
    use glam::Vec3;
    use slc_bounds::{Brdf, Fresnel, StochasticParams};
    use slc_core::{Camera, Interleaving, VplLobe};

    /// [`scatter_lanes`] of `vpls` (numbered from 0): each one's entry (`None` where it
    /// covers no pixel or is left to slc-bounds), and the lanes left (bit k: `vpls[k]`).
    fn lanes_of(screen: &Screen, vpls: &[Vpl], delta: f32) -> ([Option<Scattered>; 8], u8) {
        let (mut out, mut left) = (Vec::new(), 0u8);
        scatter_lanes(screen, vpls, 0, delta, &mut out, |_, index| {
            left |= 1 << index;
            Ok(None)
        })
        .unwrap();
        let mut placed = [None; 8];
        for s in out {
            placed[s.index as usize] = Some(s);
        }
        (placed, left)
    }

    /// The lanes bound plain VPLs (δ from 1e-9 to 1e3, flux from 1e-6 to 1e6, α from 0.01
    /// to 1, ξ near 0 and 1) at least as far as slc-bounds does: every point of slc-bounds'
    /// bound (its `LocalBound`, grown by `BOUND_SLACK`) passes the lanes' pixel test, where it
    /// is not behind the VPL, and every pixel the scalar path places the VPL on the lanes
    /// place it on too.
    #[test]
    fn lanes_contain_the_scalar_bounds() {
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 1.2).unwrap();
        // An image of 96 x 64 pixels, and one of 3 x 2 split K = 4 times, where most
        // subregion images are empty.
        let screens = [(96, 64, 2), (3, 2, 4)].map(|(w, h, k)| {
            let view = CullView::new(&cam, w, h).unwrap();
            Screen::new(&view, w, h, Interleaving { k, seed: 1 }, 0.0, 0.05).unwrap()
        });
        let mut rng = Rng(0x0B14_ED42);
        let (mut in_lanes, mut placed, mut points, mut in_empty) = (0, 0, 0, 0);
        for case in 0..3000 {
            let screen = &screens[usize::from(case % 4 == 3)];
            let delta = 10f32.powf(rng.range(-9.0, 3.0));
            let vpls: Vec<Vpl> = (0..8).map(|k| random_vpl(&mut rng, case * 8 + k)).collect();
            let (out, left) = lanes_of(screen, &vpls, delta);
            for (k, vpl) in vpls.iter().enumerate() {
                let scalar = screen.scatter(vpl, k as u32, delta).unwrap();
                if left >> k & 1 == 1 {
                    continue;
                }
                in_lanes += 1;
                let lanes = out[k];
                // A VPL of an empty subregion image is placed nowhere, whatever it covers.
                let size = screen.subregions.size(screen.subregions.of_vpl(vpl.id));
                if size.contains(&0) {
                    in_empty += 1;
                    assert!(lanes.is_none(), "case {case}, lane {k}: {lanes:?}");
                }
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
                for _ in 0..40 {
                    let d = point_of(&local, &mut rng, [0.99, 1.0]);
                    let x = (vpl.position.as_dvec3() + d).as_vec3();
                    if s.test.contains(x) {
                        points += 1;
                        assert!(l.test.contains(x), "case {case}: {d} in {local:?}");
                    }
                }
            }
        }
        assert!(
            in_lanes > 20_000 && placed > 1000 && points > 10_000 && in_empty > 500,
            "{in_lanes} in lanes, {placed} placed, {points} points, {in_empty} in empty images"
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
        let screen = Screen::new(&view, 64, 64, Interleaving { k: 2, seed: 1 }, 0.0, 0.05).unwrap();
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
            let (out, left) = lanes_of(&screen, &[base; 8], 1e-3);
            assert_eq!(left, 0);
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
                    let (_, left) = lanes_of(&screen, &group, 1e-3);
                    assert_eq!(left, 1 << k, "{what} in lane {k} of {:?}", base.lobe);
                    // The scatter places the VPL slc-bounds bounds among the others, in
                    // their order, or names what is wrong with it.
                    let mut placed = Vec::new();
                    match scatter(&screen, &group, 0, 1e-3, &mut placed) {
                        Ok(()) => {
                            let order: Vec<u32> = placed.iter().map(|s| s.index).collect();
                            let want = match screen.scatter(&group[k], k as u32, 1e-3) {
                                Ok(Some(_)) => (0..8).collect::<Vec<u32>>(),
                                _ => (0..8).filter(|&i| i != k as u32).collect(),
                            };
                            assert_eq!(order, want, "{what} in lane {k}");
                        }
                        Err(e) => assert_eq!(
                            Some(e.to_string()),
                            screen
                                .scatter(&group[k], k as u32, 1e-3)
                                .err()
                                .map(|e| e.to_string()),
                            "{what} in lane {k}"
                        ),
                    }
                }
            }
        }
    }
}
