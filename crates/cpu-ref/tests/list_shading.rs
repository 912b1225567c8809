//! `shade_lists` (tile order, eight-lane exits and roulette) against the plainest form of
//! paper eq. (3) with interleaving: every pixel's list in its order, each VPL's weighted
//! contribution from `vpl_contribution`, times K². The images must be equal bit for bit, for
//! every culling layout and several K, on the built-in scene as it is and with dielectric
//! Fresnel factors (η above and below 1) on some of its VPLs and receivers, or anisotropic
//! receivers; and for lists of any order and length, many of them in one tile.
use glam::Vec3;
use slc_bounds::{Anisotropy, Fresnel, StochasticParams};
use slc_core::frame::{Method, RenderSettings};
use slc_core::{builtin, CullInput, Image, Interleaving, LightLists, Strategy, NO_LIST};
use slc_cpu_ref::vpl_shading::{shade_lists, shade_lists_into, vpl_contribution};
use slc_cpu_ref::{prepare, Tracer};
use slc_cull::ListedReach;

/// The built-in scene's G-buffer and VPLs at `width` x `height` with RSM `rsm`.
fn prepared(width: u32, height: u32, rsm: u32) -> slc_cpu_ref::CpuPrepared {
    let scene = builtin("default").unwrap();
    let settings = RenderSettings {
        seed: 3,
        ..RenderSettings::new(width, height, rsm, Method::VplReference)
    };
    prepare(&scene, &settings, Tracer::new(&scene), None)
}

fn plain(input: &CullInput, lists: &slc_core::LightLists) -> Image {
    let mut image = Image::new(input.gbuffer.width, input.gbuffer.height);
    let scale = input.interleaving.scale();
    for (p, o) in image.pixels.iter_mut().enumerate() {
        let Some(g) = &input.gbuffer.samples[p] else {
            continue;
        };
        for &k in lists.for_pixel(p).iter() {
            let v = &input.vpls[k as usize];
            let r = StochasticParams::new(input.delta, v.xi).unwrap();
            let c = vpl_contribution(g, v, Some(&r));
            if c != Vec3::ZERO {
                *o += c * scale;
            }
        }
    }
    image
}

/// `shade_lists` and the plain sum of `lists`. Shading into a spare image of the same size
/// full of NaN (every pixel written), or into one of another size (dropped), with the listed
/// VPLs' exits formed in a used table (every VPL's, at another δ, then the last shading's),
/// gives the same image.
fn shaded_and_plain(
    p: &slc_cpu_ref::CpuPrepared,
    input: &CullInput,
    lists: &LightLists,
) -> (Image, Image) {
    let got = shade_lists(&p.tracer, input, lists, false, &|_| {}).unwrap();
    let (w, h) = (input.gbuffer.width, input.gbuffer.height);
    let nan = Image {
        width: w,
        height: h,
        pixels: vec![Vec3::NAN; got.pixels.len()],
    };
    let mut exits = ListedReach::default();
    let every: Vec<u32> = (0..input.vpls.len() as u32).collect();
    exits
        .form(input.vpls, input.delta * 2.0, &every, |j| j % 3 == 0)
        .unwrap();
    for spare in [nan, Image::new(w + 1, h), Image::new(h, w)] {
        let into = shade_lists_into(
            &p.tracer,
            input,
            lists,
            false,
            &|_| {},
            Some(spare),
            &mut exits,
        );
        let into = into.unwrap();
        assert_eq!((into.width, into.height), (w, h));
        assert_eq!(differing(&into, &got), 0, "into a spare image");
    }
    (got, plain(input, lists))
}

/// The pixels of `a` and `b` that differ in any bit.
fn differing(a: &Image, b: &Image) -> usize {
    let bits = |v: &Vec3| v.to_array().map(f32::to_bits);
    a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(x, y)| bits(x) != bits(y))
        .count()
}

#[test]
fn shade_lists_equals_the_plain_sum_bit_for_bit() {
    for name in ["default", "dielectric", "anisotropic"] {
        let mut p = prepared(61, 47, 24);
        if name == "anisotropic" {
            // Every third receiver anisotropic (its BRDF left to the scalar shader).
            for g in p.gbuffer.samples.iter_mut().flatten().step_by(3) {
                let t = g.normal.any_orthonormal_vector();
                g.brdf.anisotropy = Some(Anisotropy {
                    tangent: t,
                    alpha_t: 0.05,
                });
            }
        }
        if name == "dielectric" {
            let eta = |i: usize| if i.is_multiple_of(2) { 1.5 } else { 0.8 };
            for (i, v) in p
                .vpls
                .iter_mut()
                .enumerate()
                .filter(|(i, _)| i.is_multiple_of(3))
            {
                v.brdf.fresnel = Fresnel::Dielectric(eta(i / 3));
            }
            for (i, g) in p.gbuffer.samples.iter_mut().flatten().enumerate() {
                if i % 3 == 1 {
                    g.brdf.fresnel = Fresnel::Dielectric(eta(i / 3));
                }
            }
        }
        for k in [1, 3, 4] {
            for strategy in [
                Strategy::None,
                Strategy::Ellipsoid,
                Strategy::Clustered,
                Strategy::Binned,
            ] {
                let input = p.cull_input(1e-3, Interleaving { k, seed: 3 });
                let lists = slc_cull::culler(strategy).cull(&input).unwrap();
                if strategy == Strategy::Binned && k == 1 {
                    // Ranges wider than a tile: shared lists beside the pixels' own.
                    assert!(!lists.shared_list.is_empty(), "{name}: shared lists");
                }
                let (got, want) = shaded_and_plain(&p, &input, &lists);
                assert_eq!(differing(&got, &want), 0, "{name} K {k} {strategy:?}");
                assert!(want.pixels.iter().any(|o| *o != Vec3::ZERO), "{name}: lit");
            }
        }
    }
}

#[test]
fn shade_lists_refuses_lists_of_another_size() {
    let p = prepared(8, 8, 8);
    let input = p.cull_input(1e-3, Interleaving { k: 2, seed: 0 });
    let lists = slc_cull::culler(Strategy::Ellipsoid).cull(&input).unwrap();
    let malformed: [fn(&mut LightLists); 4] = [
        |l| l.pixel_list.truncate(l.pixel_list.len() - 1),
        |l| l.indices[0] = u32::MAX - 1,
        |l| l.offsets.push(0),
        |l| l.pixel_list[0] = l.offsets.len() as u32,
    ];
    for spoil in malformed {
        let mut lists = lists.clone();
        spoil(&mut lists);
        assert!(shade_lists(&p.tracer, &input, &lists, false, &|_| {}).is_err());
    }
    let k0 = CullInput {
        interleaving: Interleaving { k: 0, seed: 0 },
        ..input
    };
    let lists = slc_cull::culler(Strategy::None).cull(&input).unwrap();
    assert!(shade_lists(&p.tracer, &k0, &lists, false, &|_| {}).is_err());
}

/// A xorshift generator from `state`: each call a number below its argument (0 below 0 or 1).
fn xorshift(mut state: u64) -> impl FnMut(u64) -> u64 {
    move |m| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % m.max(1)
    }
}

/// `count` lists of VPLs drawn by `next` below `vpls`, list l of length `lens[l % lens.len()]`
/// and put in order by `order(l, list)`; no pixel names one yet.
fn random_lists(
    next: &mut impl FnMut(u64) -> u64,
    count: usize,
    lens: &[usize],
    vpls: usize,
    order: impl Fn(usize, &mut Vec<u32>),
) -> LightLists {
    let mut lists = LightLists {
        offsets: vec![0],
        ..LightLists::default()
    };
    for l in 0..count {
        let mut list: Vec<u32> = (0..lens[l % lens.len()])
            .map(|_| next(vpls as u64) as u32)
            .collect();
        order(l, &mut list);
        lists.indices.extend(&list);
        lists.offsets.push(lists.indices.len() as u32);
    }
    lists
}

/// Lists of any kind: ascending, shuffled, with repeated VPLs, empty, long and short, up to
/// one per pixel (far more than 32 in a tile), some pixels without a list. `shade_lists`
/// still equals the plain sum of each pixel's list in its order, bit for bit.
#[test]
fn shade_lists_equals_the_plain_sum_for_lists_of_any_order() {
    let p = prepared(53, 41, 16);
    let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
    let mut lists = random_lists(
        &mut next,
        600,
        &[0, 1, 3, 17, 200],
        p.vpls.len(),
        |l, list| match l % 3 {
            0 => {
                list.sort_unstable();
                list.dedup();
            }
            1 => list.sort_unstable(),
            _ => {}
        },
    );
    let pixels = p.gbuffer.samples.len();
    lists.pixel_list = (0..pixels)
        .map(|i| match i % 7 {
            0 => NO_LIST,
            // Runs of neighbours sharing a list, and pixels with lists of their own.
            1..=3 => (i / 11 % 600) as u32,
            _ => next(600) as u32,
        })
        .collect();
    for k in [1, 2, 4] {
        let input = p.cull_input(1e-4, Interleaving { k, seed: 5 });
        let (got, want) = shaded_and_plain(&p, &input, &lists);
        assert_eq!(differing(&got, &want), 0, "K {k}");
        let lit = want.pixels.iter().filter(|o| **o != Vec3::ZERO).count();
        assert!(lit > pixels / 4, "{lit} of {pixels} lit");
    }
}

/// Pixels with a second, shared list ([`LightLists::shared_list`]): strictly ascending lists,
/// a pixel with its own list, a shared one, both (sharing VPLs or not) or neither, shared
/// lists held by runs of neighbours and by single pixels. `shade_lists` equals the plain sum
/// of each pixel's union in ascending order, bit for bit, and the flattened lists' image.
#[test]
fn shade_lists_equals_the_plain_sum_with_shared_lists() {
    let p = prepared(53, 41, 16);
    let mut next = xorshift(0x2545_f491_4f6c_dd1d);
    let mut lists = random_lists(
        &mut next,
        400,
        &[0, 1, 5, 40, 150],
        p.vpls.len(),
        |_, list| {
            list.sort_unstable();
            list.dedup();
        },
    );
    let pixels = p.gbuffer.samples.len();
    let mut pick = |i: usize, none: usize| match i % 5 {
        j if j == none => NO_LIST,
        1 | 2 => (i / 13 % 400) as u32,
        _ => next(400) as u32,
    };
    lists.pixel_list = (0..pixels).map(|i| pick(i, 0)).collect();
    lists.shared_list = (0..pixels).map(|i| pick(i / 3, 3)).collect();
    let flat = lists.flattened().unwrap();
    for k in [1, 2, 4] {
        let input = p.cull_input(1e-4, Interleaving { k, seed: 5 });
        let (got, want) = shaded_and_plain(&p, &input, &lists);
        assert_eq!(differing(&got, &want), 0, "K {k}");
        let (flat_got, _) = shaded_and_plain(&p, &input, &flat);
        assert_eq!(differing(&got, &flat_got), 0, "K {k}: flattened");
        let lit = want.pixels.iter().filter(|o| **o != Vec3::ZERO).count();
        assert!(lit > pixels / 4, "{lit} of {pixels} lit");
    }
}

/// `shade_lists` builds the early exits of the listed VPLs only: a VPL outside slc-bounds'
/// domain (a glossy VPL with α = 0) that no list holds is never read,
/// and the image is that of the valid VPLs; the same VPL listed is an error.
#[test]
fn shade_lists_checks_the_listed_vpls() {
    let p = prepared(8, 8, 8);
    let input = p.cull_input(1e-3, Interleaving { k: 2, seed: 0 });
    let spoilt = |v: &slc_core::Vpl| {
        let mut v = *v;
        v.brdf.alpha = 0.0;
        v
    };
    let bad = (0..p.vpls.len())
        .find(|&i| {
            let params = StochasticParams::new(input.delta, p.vpls[i].xi).unwrap();
            slc_cull::VplReach::new(&spoilt(&p.vpls[i]), &params).is_err()
        })
        .expect("a VPL whose exits check its roughness");
    let lists = |listed: u32| LightLists {
        offsets: vec![0, 1],
        indices: vec![listed],
        pixel_list: vec![0; p.gbuffer.samples.len()],
        shared_list: Vec::new(),
    };
    let other = u32::from(bad == 0);
    let shaded = shade_lists(&p.tracer, &input, &lists(other), false, &|_| {}).unwrap();
    let mut vpls = p.vpls.clone();
    vpls[bad] = spoilt(&vpls[bad]);
    let spoilt_input = CullInput {
        vpls: &vpls,
        ..input
    };
    let unlisted = shade_lists(&p.tracer, &spoilt_input, &lists(other), false, &|_| {}).unwrap();
    assert_eq!(unlisted.pixels, shaded.pixels);
    let listed = shade_lists(&p.tracer, &spoilt_input, &lists(bad as u32), false, &|_| {});
    assert!(listed.is_err());
}

/// `CpuRenderer` shades the next frame into the noisy image its filter consumed: frame after
/// frame (cull, shade, filter), two frames of one size (other VPLs) and one of another size
/// in turn, each frame's images are the same bit for bit as the first time.
#[test]
fn the_renderer_shades_frame_after_frame_into_the_filtered_image() {
    use slc_core::Renderer;
    let r = slc_cpu_ref::CpuRenderer::default();
    let frames = [
        prepared(61, 47, 24),
        prepared(61, 47, 16),
        prepared(20, 12, 8),
    ];
    let k = Interleaving { k: 4, seed: 3 };
    let frame = |p: &slc_cpu_ref::CpuPrepared| {
        let lists = r.cull(p, Strategy::Ellipsoid, 1e-3, k).unwrap();
        let noisy = r
            .shade_lists(&p.tracer, p, &lists, 1e-3, k, false, &|_| {})
            .unwrap();
        let filtered = r.denoise(p, noisy.clone(), &|_| {}).unwrap();
        (noisy, filtered)
    };
    let first: Vec<_> = frames.iter().map(frame).collect();
    assert_ne!(
        differing(&first[0].0, &first[1].0),
        0,
        "other VPLs, another image"
    );
    for (i, p) in [0, 1, 0, 2, 1, 1, 0].map(|i| (i, &frames[i])) {
        let (noisy, filtered) = frame(p);
        assert_eq!(differing(&noisy, &first[i].0), 0, "frame {i} shaded");
        assert_eq!(differing(&filtered, &first[i].1), 0, "frame {i} filtered");
    }
}
