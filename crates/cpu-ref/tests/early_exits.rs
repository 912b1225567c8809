//! Property test of the early exits (`slc_cull::VplReach`): over random VPLs and receivers,
//! with the receivers placed at the edge of the VPL's random range (eq. 5), where p(ωo, l) of
//! eq. (2) crosses ξ, and at the extremes (α 1e-4 … 1, grazing and normal incidence at both
//! ends, ξ near 0 and 1, δ 1e-9 … 1e3, flux from 1e-6 to 1e6), no exit ever rejects a pair
//! that the roulette accepts (p > ξ) or whose weighted contribution (eq. 1, 3) is not 0, and
//! the eight-lane test passes exactly the pairs the scalar one passes (the receivers-in-lanes
//! test: wherever the VPL's bound over the receivers' box keeps it; where that bound rejects
//! the box, no pair, and the shader accepts none of its receivers). Where the shader forms
//! p in f32 with Schlick's Fresnel or a diffuse lobe, the exits decide exactly as it does: no
//! pair they pass is rejected by the roulette. And the receivers' BRDF formed eight pairs at a
//! time (`slc_cpu_ref::received_lanes`) equals the scalar shader's bit for bit.
use glam::Vec3;
use slc_bounds::lanes::F8;
use slc_bounds::{scalar_intensity, Anisotropy, Brdf, Fresnel, StochasticParams};
use slc_core::{GSample, Vpl, VplLobe};
use slc_cpu_ref::received_lanes::{received_pairs, ReceiverBrdfs};
use slc_cpu_ref::vpl_shading::{received, vpl_contribution};
use slc_cull::{ListedReach, ReachChunks, ReceiverChunks, VplReach};

#[path = "../../../tests/fixtures/rng.rs"]
mod rng;
use rng::Rng;

impl Rng {
    /// A unit vector whose cosine to `n` is `cos` (sign included).
    fn at_cosine(&mut self, n: Vec3, cos: f32) -> Vec3 {
        let t = n.any_orthonormal_vector();
        let b = n.cross(t);
        let phi = self.range(0.0, std::f32::consts::TAU);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        (n * cos + (t * phi.cos() + b * phi.sin()) * sin).normalize()
    }

    /// A cosine from grazing (1e-6) to normal incidence, often at either end.
    fn cosine(&mut self) -> f32 {
        match (self.f32() * 4.0) as u32 {
            0 => self.log(-6.0, -1.0),
            1 => 1.0 - self.log(-7.0, -1.0),
            _ => self.f32(),
        }
    }

    /// A cosine within ±1e-3 of 0, down to ±1e-9 (grazing within float rounding).
    fn grazing(&mut self) -> f32 {
        let sign = if self.f32() < 0.5 { -1.0 } else { 1.0 };
        sign * self.log(-9.0, -3.0)
    }

    /// ξ in (0, 1), often near either end.
    fn xi(&mut self) -> f32 {
        let xi = match (self.f32() * 3.0) as u32 {
            0 => self.log(-7.0, -1.0),
            1 => 1.0 - self.log(-7.0, -1.0),
            _ => self.f32(),
        };
        xi.clamp(1e-7, 1.0 - f32::EPSILON / 2.0)
    }

    fn rgb(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.log(lo, hi), self.log(lo, hi), self.log(lo, hi))
    }
}

fn random_vpl(rng: &mut Rng) -> Vpl {
    let normal = rng.unit();
    // Mostly above the surface, at any incidence; sometimes on or below it.
    let cos_i = if rng.f32() < 0.1 {
        -rng.f32()
    } else {
        rng.cosine()
    };
    let omega_i = rng.at_cosine(normal, cos_i);
    let fresnel = if rng.f32() < 0.2 {
        // Below 1 too (total internal reflection), and near 1.
        Fresnel::Dielectric(match (rng.f32() * 3.0) as u32 {
            0 => rng.range(0.3, 0.999),
            1 => 1.0 + rng.range(-1e-3, 1e-3),
            _ => rng.range(1.01, 3.0),
        })
    } else {
        Fresnel::Schlick(Vec3::new(rng.f32(), rng.f32(), rng.f32()))
    };
    Vpl {
        position: Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ) * rng.log(-2.0, 3.0),
        normal,
        geometric_normal: normal,
        omega_i,
        flux: rng.rgb(-6.0, 6.0),
        brdf: Brdf {
            kd: Vec3::new(rng.f32(), rng.f32(), rng.f32()),
            fresnel,
            alpha: rng.log(-4.0, 0.0),
            anisotropy: None,
        },
        lobe: if rng.f32() < 0.5 {
            VplLobe::Diffuse
        } else {
            VplLobe::Glossy
        },
        id: 0,
        xi: rng.xi(),
    }
}

/// A direction from the VPL: near its mirror direction (the glossy peak, within a few α),
/// grazing its surface, or anywhere.
fn direction(rng: &mut Rng, vpl: &Vpl) -> Vec3 {
    match (rng.f32() * 3.0) as u32 {
        0 => {
            let mirror = 2.0 * vpl.normal.dot(vpl.omega_i) * vpl.normal - vpl.omega_i;
            let spread = vpl.brdf.alpha * rng.range(0.0, 4.0);
            (mirror + rng.unit() * spread).normalize()
        }
        1 => {
            let cos = rng.grazing();
            rng.at_cosine(vpl.normal, cos)
        }
        _ => rng.unit(),
    }
}

/// A receiver at `x` with a random normal, often grazing the direction `omega` it is lit
/// from, and a random view direction above it.
fn receiver(rng: &mut Rng, x: Vec3, omega: Vec3) -> GSample {
    let normal = if rng.f32() < 0.3 {
        let cos = rng.grazing();
        rng.at_cosine(-omega, cos)
    } else {
        rng.unit()
    };
    let cos_o = rng.cosine();
    let omega_o = rng.at_cosine(normal, cos_o);
    GSample {
        position: x,
        normal,
        geometric_normal: normal,
        omega_o,
        depth: 1.0,
        brdf: Brdf {
            kd: Vec3::new(rng.f32(), rng.f32(), rng.f32()),
            fresnel: Fresnel::Schlick(Vec3::splat(rng.f32())),
            alpha: rng.log(-3.0, 0.0),
            anisotropy: None,
        },
    }
}

/// A pair of `vpl` and a receiver: its offset d = x − q, l², p(ωo, l) of eq. (2) and whether
/// p > ξ, exactly as the shader (and the metrics' truth) decide it, and the pair's weighted
/// contribution (eq. 1, 3).
struct Pair {
    g: GSample,
    d: Vec3,
    l2: f32,
    distance: f32,
    p: f32,
    accepts: bool,
    contribution: Vec3,
}

/// A receiver for `vpl` in a random direction, at the range l_max(ωo) = sqrt(I/(δ ξ)) of
/// eq. (5) within ±1e-2 … ±1e-6, or anywhere; `None` where it lies at the VPL.
fn pair_at_range_edge(rng: &mut Rng, vpl: &Vpl, params: &StochasticParams) -> Option<Pair> {
    let omega = direction(rng, vpl);
    let range = params.range(scalar_intensity(vpl.intensity(omega)));
    let distance = if range > 0.0 && range < 1e15 && rng.f32() < 0.8 {
        let sign = if rng.f32() < 0.5 { -1.0 } else { 1.0 };
        range * (1.0 + sign * rng.log(-6.0, -2.0))
    } else {
        rng.log(-3.0, 4.0)
    };
    let g = receiver(rng, vpl.position + omega * distance, omega);
    let d = g.position - vpl.position;
    let l2 = d.length_squared();
    if l2 <= 0.0 {
        return None;
    }
    let p = params.probability(scalar_intensity(vpl.intensity(d / l2.sqrt())), l2);
    Some(Pair {
        g,
        d,
        l2,
        distance,
        p,
        accepts: p > params.xi(),
        contribution: vpl_contribution(&g, vpl, Some(params)),
    })
}

#[test]
fn no_early_exit_drops_an_accepted_or_contributing_pair() {
    let mut rng = Rng(0x5EED_1234_ABCD_0001);
    let (mut accepted, mut contributing, mut edge, mut rejected) = (0u32, 0u32, 0u32, 0u32);
    let mut exact = 0u32;
    let cases = 400_000u32;
    let mut recent = Vec::new();
    let mut receivers = Vec::new();
    let mut receiver_lanes = ReceiverChunks::default();
    let mut passing = Vec::new();
    let mut handed_on = 0u32;
    let mut box_rejected = 0u32;
    for case in 0..cases {
        let vpl = random_vpl(&mut rng);
        let params = StochasticParams::new(rng.log(-9.0, 3.0), vpl.xi).unwrap();
        let reach = VplReach::new(&vpl, &params).unwrap();
        if recent.len() < 8 {
            recent.resize(8, (vpl, reach));
        }
        let Some(Pair {
            g,
            d,
            l2,
            distance,
            p,
            accepts,
            contribution,
        }) = pair_at_range_edge(&mut rng, &vpl, &params)
        else {
            continue;
        };
        if exact_in_f32(&vpl, d / l2.sqrt()) {
            assert_eq!(
                reach.may_accept(d),
                accepts,
                "case {case}: p {p}, ξ {}: {vpl:?} at {:?}",
                params.xi(),
                g.position
            );
            exact += 1;
        }
        assert!(
            !accepts || reach.may_accept(d),
            "case {case}: p {p} > ξ {} rejected: {vpl:?} at {:?}",
            params.xi(),
            g.position
        );
        assert!(
            contribution == Vec3::ZERO || reach.may_contribute(d, g.normal),
            "case {case}: contribution {contribution} rejected: {vpl:?} at {g:?}"
        );
        // The eight-lane test (`ReachChunks`) passes exactly the VPLs the scalar one passes,
        // in whatever lane: the recent VPLs in one chunk, tested at this receiver.
        recent[(case % 8) as usize] = (vpl, reach);
        let (vpls, reaches): (Vec<Vpl>, Vec<VplReach>) = recent.iter().copied().unzip();
        let chunks = ReachChunks::new(&vpls, &reaches, [&[0, 1, 2, 3, 4, 5, 6, 7][..]]);
        for normal in [None, Some(g.normal)] {
            let mut lanes = Vec::new();
            chunks.for_each_passing(0, g.position, normal, |i| lanes.push(i));
            let scalar: Vec<u32> = (0..8u32)
                .filter(|&i| {
                    let (v, r) = &recent[i as usize];
                    let d = g.position - v.position;
                    normal.map_or(r.may_accept(d), |n| r.may_contribute(d, n))
                })
                .collect();
            assert_eq!(lanes, scalar, "case {case}");
        }
        // The receivers-in-lanes test (`ReceiverChunks`) passes exactly the receivers the
        // scalar one passes: this VPL against the last 11 receivers (a full chunk and a
        // partial one).
        // Every other case the receivers are this one and ten more within a small box
        // around it (1e-7 … 1e-2 of its distance), so that the box test of
        // `ReceiverChunks::passing` is tried at the bound's edge.
        if case % 2 == 0 {
            receivers.push((g.position, g.normal));
            if receivers.len() > 11 {
                receivers.remove(0);
            }
        } else {
            let spread = distance * rng.log(-7.0, -2.0);
            receivers.clear();
            receivers.push((g.position, g.normal));
            for _ in 0..10 {
                let jitter = Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 2.0 - Vec3::ONE;
                receivers.push((g.position + jitter * spread, g.normal));
            }
        }
        receiver_lanes.refill(receivers.iter().copied());
        for normals in [false, true] {
            receiver_lanes.passing(&[reach], &[0], normals, &mut passing);
            let mut lanes = Vec::new();
            for chunk in &passing {
                for lane in (0..8).filter(|&k| chunk.bits & (1 << k) != 0) {
                    let i = chunk.chunk * 8 + lane;
                    lanes.push(i);
                    // Where the lanes hand their values on, they are the shader's, bit for
                    // bit, and the shader accepts the pair.
                    if let Some((omega, l2, intensity)) = chunk.exact(lane) {
                        let d = receivers[i].0 - vpl.position;
                        let l2_shader = d.length_squared();
                        let omega_shader = d / l2_shader.sqrt();
                        let intensity_shader = vpl.intensity(omega_shader);
                        assert_eq!(
                            (omega.to_array().map(f32::to_bits), l2.to_bits()),
                            (
                                omega_shader.to_array().map(f32::to_bits),
                                l2_shader.to_bits()
                            ),
                            "case {case}"
                        );
                        assert_eq!(
                            intensity.to_array().map(f32::to_bits),
                            intensity_shader.to_array().map(f32::to_bits),
                            "case {case}: {vpl:?}"
                        );
                        let p = params.probability(scalar_intensity(intensity_shader), l2_shader);
                        assert!(p > params.xi(), "case {case}");
                        handed_on += 1;
                    }
                }
            }
            let scalar: Vec<usize> = (0..receivers.len())
                .filter(|&i| {
                    let (x, n) = receivers[i];
                    match normals {
                        true => reach.may_contribute(x - vpl.position, n),
                        false => reach.may_accept(x - vpl.position),
                    }
                })
                .collect();
            // The lanes first test the VPL's bound over the receivers' box: where it passes,
            // they pass exactly the receivers the scalar test passes; where it does not, none,
            // and the shader accepts none of them.
            let (lo, hi) = receivers
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &(x, _)| {
                    (lo.min(x), hi.max(x))
                });
            if reach.box_may_exceed_xi(lo, hi) {
                assert_eq!(lanes, scalar, "case {case}: receivers in lanes");
            } else {
                assert!(
                    lanes.is_empty(),
                    "case {case}: receivers in lanes {lanes:?}"
                );
                for &(x, _) in &receivers {
                    let d = x - vpl.position;
                    let l2 = d.length_squared();
                    let p = params.probability(scalar_intensity(vpl.intensity(d / l2.sqrt())), l2);
                    assert!(
                        !(l2 > 0.0 && p > params.xi()),
                        "case {case}: box rejected p {p}"
                    );
                }
                box_rejected += u32::from(normals);
            }
        }
        accepted += u32::from(accepts);
        contributing += u32::from(contribution != Vec3::ZERO);
        edge += u32::from(accepts && (p - params.xi()) < 1e-3 * params.xi());
        rejected += u32::from(!reach.may_contribute(d, g.normal));
    }
    // The cases are not vacuous: many pairs are accepted, many just barely, and the exits
    // reject many others.
    assert!(accepted > cases / 10, "{accepted} accepted");
    assert!(contributing > cases / 20, "{contributing} contributing");
    assert!(edge > cases / 100, "{edge} accepted within 1e-3 of ξ");
    assert!(rejected > cases / 4, "{rejected} rejected");
    assert!(exact > cases / 2, "{exact} decided exactly");
    assert!(
        handed_on > cases / 20,
        "{handed_on} pairs' values handed on"
    );
    assert!(
        box_rejected > cases / 20,
        "{box_rejected} boxes of receivers rejected"
    );
}

/// Whether the shader forms the VPL's intensity towards `omega` entirely in f32 with a
/// Fresnel factor the lanes form the same way: a diffuse lobe, or a glossy one with Schlick's
/// Fresnel whose half vector is well conditioned (`slc_bounds::brdf::microfacet`).
fn exact_in_f32(vpl: &Vpl, omega: Vec3) -> bool {
    match (vpl.lobe, vpl.brdf.fresnel) {
        (VplLobe::Diffuse, _) => true,
        (VplLobe::Glossy, Fresnel::Dielectric(_)) => false,
        (VplLobe::Glossy, Fresnel::Schlick(_)) => {
            let s2 = (vpl.omega_i + omega).length_squared();
            s2 * vpl.brdf.alpha * vpl.brdf.alpha > 1e-6
        }
    }
}

/// A receiver at the extremes: α from 1e-4 to 1, grazing views, dielectric and
/// anisotropic lobes (not modelled here) among them.
fn lobe_receiver(rng: &mut Rng) -> GSample {
    let normal = rng.unit();
    let omega_o = match rng.f32() {
        u if u < 0.2 => (normal * rng.log(-7.0, -2.0) + rng.unit().cross(normal)).normalize(),
        u if u < 0.3 => -normal,
        _ => rng.unit(),
    };
    let alpha = if rng.f32() < 0.1 {
        1.0
    } else {
        rng.log(-4.0, 0.0)
    };
    let fresnel = if rng.f32() < 0.1 {
        Fresnel::Dielectric(rng.range(0.5, 2.0))
    } else {
        Fresnel::Schlick(Vec3::new(rng.f32(), rng.f32(), rng.f32()))
    };
    let anisotropy = (rng.f32() < 0.1).then(|| Anisotropy {
        tangent: rng.unit().cross(normal).normalize(),
        alpha_t: rng.log(-3.0, 0.0),
    });
    GSample {
        position: Vec3::ZERO,
        normal,
        geometric_normal: normal,
        omega_o,
        depth: 1.0,
        brdf: Brdf {
            kd: Vec3::new(rng.f32(), rng.f32(), 0.0),
            fresnel,
            alpha,
            anisotropy,
        },
    }
}

/// Every lane the lanes say they formed equals the scalar `received` bit for bit, over
/// 200,000 random pairs: directions near the mirror one (the half vector formed in f64
/// there), grazing at both ends, δ from 1e-9 to 1e3, ξ near 0 and 1, intensities from 0
/// to 1e30 and l² from 1e-12 to 1e12.
#[test]
fn formed_lanes_equal_the_scalar_shader() {
    if !std::arch::is_x86_feature_detected!("avx2") {
        return;
    }
    let mut rng = Rng(0xbeef);
    let (mut formed_nonzero, mut left) = (0, 0);
    for _ in 0..25_000 {
        let receivers: Vec<GSample> = (0..8).map(|_| lobe_receiver(&mut rng)).collect();
        let brdfs = ReceiverBrdfs::of_chunk(&receivers);
        let xi = match rng.f32() {
            u if u < 0.2 => rng.log(-7.0, -3.0),
            u if u < 0.4 => 1.0 - rng.log(-7.0, -3.0),
            _ => rng.range(1e-6, 0.999_999),
        };
        let params = StochasticParams::new(rng.log(-9.0, 3.0), xi).unwrap();
        let lane_omega: Vec<Vec3> = receivers
            .iter()
            .map(|g| match rng.f32() {
                // Near the mirror of ωo (ωi ≈ reflect(ωo), so ωi + ωo is tiny only
                // at grazing), exactly opposite ωo (s = 0), or anywhere.
                u if u < 0.2 => -(g.normal * 2.0 * g.normal.dot(g.omega_o) - g.omega_o
                    + rng.unit() * rng.log(-7.0, -1.0))
                .normalize(),
                u if u < 0.3 => g.omega_o,
                u if u < 0.4 => (-g.normal * rng.log(-7.0, -2.0) + rng.unit()).normalize(),
                _ => rng.unit(),
            })
            .collect();
        let l2: Vec<f32> = (0..8).map(|_| rng.log(-12.0, 12.0)).collect();
        let intensity: Vec<Vec3> = (0..8)
            .map(|_| {
                let scale = if rng.f32() < 0.05 {
                    0.0
                } else {
                    rng.log(-6.0, 30.0)
                };
                Vec3::new(rng.f32(), rng.f32(), rng.f32()) * scale
            })
            .collect();
        let lanes3 = |v: &[Vec3]| [0, 1, 2].map(|c| F8(core::array::from_fn(|k| v[k][c])));
        let mut out = [F8([0.0; 8]); 3];
        let formed = received_pairs(
            &brdfs,
            &lanes3(&lane_omega),
            &F8(core::array::from_fn(|k| l2[k])),
            &lanes3(&intensity),
            &params,
            &mut out,
        );
        for (k, g) in receivers.iter().enumerate() {
            let want = received(g, lane_omega[k], l2[k], || intensity[k], Some(&params));
            if formed & (1 << k) == 0 {
                left += 1;
                continue;
            }
            let got = Vec3::new(out[0].0[k], out[1].0[k], out[2].0[k]);
            assert_eq!(
                got.to_array().map(f32::to_bits),
                want.to_array().map(f32::to_bits),
                "lane {k}: {g:?} ω {} l² {} I {} {params:?}",
                lane_omega[k],
                l2[k],
                intensity[k]
            );
            formed_nonzero += usize::from(got != Vec3::ZERO);
        }
    }
    // Most pairs are formed by the lanes, thousands of them non-zero; the unmodelled
    // receivers and ill-conditioned half vectors are left to the scalar shader.
    assert!(formed_nonzero > 5_000, "{formed_nonzero} non-zero formed");
    assert!(
        left > 10_000 && left < 100_000,
        "{left} left to the scalar shader"
    );
}

/// `VplReach::of_frame` gives every VPL, or each listed VPL in its place, its own exits and
/// roulette; it checks the ξ of every VPL it forms exits for (naming the first one out of
/// its domain), reads no other, and refuses an index past the VPLs.
#[test]
fn frame_exits_cover_the_listed_vpls() {
    let mut rng = Rng(0x0F_F2A3);
    let mut vpls: Vec<Vpl> = (0..300).map(|_| random_vpl(&mut rng)).collect();
    let delta = 1e-3;
    let listed: Vec<u32> = (0..vpls.len() as u32).filter(|i| i % 3 != 0).collect();
    let (roulette, reach) = VplReach::of_frame(&vpls, delta, Some(&listed)).unwrap();
    let (every, all) = VplReach::of_frame(&vpls, delta, None).unwrap();
    assert_eq!((every.len(), all.len()), (vpls.len(), vpls.len()));
    assert_eq!((roulette.len(), reach.len()), (listed.len(), listed.len()));
    for (i, vpl) in vpls.iter().enumerate() {
        let params = StochasticParams::new(delta, vpl.xi).unwrap();
        assert_eq!(every[i], params);
        assert_eq!(all[i], VplReach::new(vpl, &params).unwrap());
    }
    for (j, &i) in listed.iter().enumerate() {
        assert_eq!(roulette[j], every[i as usize]);
        assert_eq!(reach[j], all[i as usize]);
    }
    assert!(VplReach::of_frame(&vpls, delta, Some(&[300])).is_err());
    // VPL 0 is not listed: its ξ is not read.
    vpls[0].xi = 1.0;
    assert!(VplReach::of_frame(&vpls, delta, Some(&listed)).is_ok());
    assert!(VplReach::of_frame(&vpls, delta, None).is_err());
    // Listed ones are checked, and the first in their order is named.
    vpls[250].xi = 0.0;
    vpls[100].xi = f32::NAN;
    for _ in 0..20 {
        let err = VplReach::of_frame(&vpls, delta, Some(&listed)).unwrap_err();
        assert!(err.to_string().contains("NaN"), "{err}");
    }
}

/// `VplReach::without_bounds` (what the shading forms for a VPL listed at few pixels) keeps
/// the sign tests and the roulette of `VplReach::new` and drops only its bounds: over random
/// VPLs and pairs at the edge of their range it rejects no pair that the roulette accepts or
/// that contributes, it passes every pair `new` passes, where the shader forms p in f32 it
/// decides as the shader does, its bound over boxes passes every box, and the
/// receivers-in-lanes test passes exactly the receivers its scalar test passes. It refuses the
/// VPLs `new` refuses, and `of_listed` forms each listed VPL's exits as asked.
#[test]
fn exits_without_bounds_keep_the_signs_and_the_roulette() {
    let mut rng = Rng(0x5EED_0B0D_FEED_0002);
    let (mut tighter, mut exact, mut contributing) = (0u32, 0u32, 0u32);
    let mut receiver_lanes = ReceiverChunks::default();
    let mut passing = Vec::new();
    let cases = 100_000u32;
    for case in 0..cases {
        let vpl = random_vpl(&mut rng);
        let params = StochasticParams::new(rng.log(-9.0, 3.0), vpl.xi).unwrap();
        let bounded = VplReach::new(&vpl, &params).unwrap();
        let reach = VplReach::without_bounds(&vpl, &params).unwrap();
        let Some(pair) = pair_at_range_edge(&mut rng, &vpl, &params) else {
            continue;
        };
        let (g, d, accepts, contribution) = (pair.g, pair.d, pair.accepts, pair.contribution);
        assert!(!accepts || reach.may_accept(d), "case {case}: {vpl:?}");
        assert!(
            contribution == Vec3::ZERO || reach.may_contribute(d, g.normal),
            "case {case}: {vpl:?}"
        );
        assert!(!bounded.may_contribute(d, g.normal) || reach.may_contribute(d, g.normal));
        if exact_in_f32(&vpl, d / pair.l2.sqrt()) {
            assert_eq!(reach.may_accept(d), accepts, "case {case}: {vpl:?}");
            exact += 1;
        }
        let spread = pair.distance * rng.log(-7.0, 0.0);
        assert!(reach.box_may_exceed_xi(g.position - spread, g.position + spread));
        let receivers: Vec<(Vec3, Vec3)> = (0..11)
            .map(|_| {
                let jitter = Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 2.0 - Vec3::ONE;
                (g.position + jitter * spread, g.normal)
            })
            .collect();
        receiver_lanes.refill(receivers.iter().copied());
        receiver_lanes.passing(&[reach], &[0], true, &mut passing);
        let lanes: Vec<usize> = passing
            .iter()
            .flat_map(|c| {
                (0..8)
                    .filter(|&k| c.bits & (1 << k) != 0)
                    .map(|k| c.chunk * 8 + k)
            })
            .collect();
        let scalar: Vec<usize> = (0..receivers.len())
            .filter(|&i| reach.may_contribute(receivers[i].0 - vpl.position, receivers[i].1))
            .collect();
        assert_eq!(lanes, scalar, "case {case}");
        tighter +=
            u32::from(reach.may_contribute(d, g.normal) && !bounded.may_contribute(d, g.normal));
        contributing += u32::from(contribution != Vec3::ZERO);
    }
    // Not vacuous: pairs contribute, p is often decided exactly, and the bounds `new` adds
    // reject some pairs these exits pass (few: most pairs here lie at the edge of the
    // range, where the roulette decides as the bound does; the bounds save time, the
    // roulette's test being dearer).
    assert!(contributing > cases / 20, "{contributing} contributing");
    assert!(exact > cases / 2, "{exact} decided exactly");
    assert!(
        tighter > cases / 1000,
        "{tighter} rejected only by the bounds"
    );

    // The same refusals: a lobe outside slc-bounds' domain (a quarter of the VPLs, those
    // that reflect something), and a range beyond f32 (another quarter: a flux of 1e38 at
    // normal incidence with δ = 1e-9 and ξ = 1e-37).
    let mut spoilt: Vec<Vpl> = (0..40).map(|_| random_vpl(&mut rng)).collect();
    for (i, v) in spoilt.iter_mut().enumerate() {
        match i % 4 {
            0 => v.normal = [Vec3::NAN, Vec3::splat(0.7)][i % 2],
            1 => (v.flux, v.xi, v.omega_i) = (Vec3::splat(1e38), 1e-37, v.normal),
            _ => {}
        }
    }
    let mut refused = 0;
    for (i, v) in spoilt.iter().enumerate() {
        let delta = if i % 4 == 1 { 1e-9 } else { 1e-3 };
        let params = StochasticParams::new(delta, v.xi).unwrap();
        let err = VplReach::new(v, &params).is_err();
        assert_eq!(err, VplReach::without_bounds(v, &params).is_err(), "{v:?}");
        refused += usize::from(err);
    }
    assert!(refused >= 15, "{refused} of 40 refused");
    // `of_listed`: entry j with its bounds where asked.
    let vpls: Vec<Vpl> = (0..40).map(|_| random_vpl(&mut rng)).collect();
    let listed: Vec<u32> = (0..vpls.len() as u32).collect();
    let (roulette, reach) = VplReach::of_listed(&vpls, 1e-3, &listed, |j| j % 2 == 0).unwrap();
    for (j, v) in vpls.iter().enumerate() {
        let want = match j % 2 {
            0 => VplReach::new(v, &roulette[j]),
            _ => VplReach::without_bounds(v, &roulette[j]),
        };
        assert_eq!(reach[j], want.unwrap(), "VPL {j}");
    }
    // `ListedReach::form` in a used table, larger (kept, then more than four times too
    // large: dropped) or smaller: the same entries; an empty list empties it.
    let some: Vec<u32> = listed.iter().copied().filter(|i| i % 3 != 1).collect();
    let fresh = |listed: &[u32]| VplReach::of_listed(&vpls, 1e-3, listed, |j| j % 2 == 0);
    let mut table = ListedReach::default();
    for listed in [&listed[..], &some, &listed[..8], &listed[..], &[]] {
        table.form(&vpls, 1e-3, listed, |j| j % 2 == 0).unwrap();
        let (roulette, reach) = fresh(listed).unwrap();
        assert_eq!((&table.roulette, &table.reach), (&roulette, &reach));
    }
    assert!(table.form(&vpls, 1e-3, &[3, 40], |_| true).is_err());
    // A roulette out of the domain is named before a lobe out of it, and the first in the
    // listed order, whichever group of eight a thread met first (a NaN normal in the first
    // group, ξ 0 in the fourth, ξ 2 in the fifth).
    let mut spoilt = vpls.clone();
    spoilt[5].normal = Vec3::NAN;
    (spoilt[30].xi, spoilt[37].xi) = (0.0, 2.0);
    let first = StochasticParams::new(1e-3, 0.0).unwrap_err();
    for _ in 0..20 {
        let err = table.form(&spoilt, 1e-3, &listed, |_| true).unwrap_err();
        assert_eq!(
            err.to_string(),
            slc_core::CullError::from(first).to_string()
        );
    }
}
