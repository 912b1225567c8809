//! Tests of filtered importance sampling (VSGL section 4.2): the warp's distribution against
//! the importance (chi-square), the unbiasedness of the weights, and the levels chosen.
use super::*;
use slc_core::rng::{uniform, Sequence};
use std::collections::BTreeMap;

/// A deterministic pseudo-random number in (0, 1) for test data.
fn random(seed: u32, index: u32) -> f64 {
    f64::from(uniform(seed, index, 77, 0))
}

/// Masses `u³` with about one texel in five empty, for `faces` maps of `n`² texels.
fn random_masses(seed: u32, faces: u32, n: u32) -> Vec<f64> {
    (0..faces * n * n)
        .map(|k| {
            if random(seed ^ 0x55, k) < 0.2 {
                0.0
            } else {
                random(seed, k).powi(3)
            }
        })
        .collect()
}

/// Independent uniform points (not the stratified set) for distribution tests.
fn iid_points(count: u32, seed: u32) -> Vec<[f64; 2]> {
    (0..count)
        .map(|k| {
            let (a, b) = Sequence::new(seed, k, 78, 0).next_2d();
            [f64::from(a), f64::from(b)]
        })
        .collect()
}

/// The 0.999 quantile of the chi-square distribution with `k` degrees of freedom
/// (Wilson-Hilferty approximation, within 1 % for k ≥ 3).
fn chi2_999(k: usize) -> f64 {
    let k = k as f64;
    let h = 2.0 / (9.0 * k);
    k * (1.0 - h + 3.090 * h.sqrt()).powi(3)
}

/// Pearson's statistic of `observed` against `expected` counts, bins with fewer than 5
/// expected merged into one; returns (statistic, degrees of freedom).
fn chi_square(observed: &[f64], expected: &[f64]) -> (f64, usize) {
    let (mut stat, mut bins) = (0.0, 0);
    let (mut small_o, mut small_e) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e >= 5.0 {
            stat += (o - e).powi(2) / e;
            bins += 1;
        } else {
            small_o += o;
            small_e += e;
        }
    }
    if small_e > 0.0 {
        stat += (small_o - small_e).powi(2) / small_e;
        bins += 1;
    }
    (stat, bins - 1)
}

/// The clusters of the cut of VSGL section 4.2 for `count` samples, found top-down by the
/// definition (the coarsest nodes with `N P ≤ 1`, or level 0), with their probabilities.
fn cut(maps: &[ImportanceMap], count: u32) -> BTreeMap<Cluster, f64> {
    let total: f64 = maps
        .iter()
        .flat_map(|m| (0..m.layout().faces()).map(move |f| m.face_mass(f)))
        .sum();
    let mut out = BTreeMap::new();
    let mut stack = Vec::new();
    for (map, m) in maps.iter().enumerate() {
        for face in 0..m.layout().faces() {
            stack.push((map as u32, face, m.layout().levels() - 1, 0, 0));
        }
    }
    while let Some((map, face, level, x, y)) = stack.pop() {
        let m = &maps[map as usize];
        let p = m.mass(face, level, x, y) / total;
        if p == 0.0 {
            continue;
        }
        if level == 0 || f64::from(count) * p <= 1.0 {
            let c = Cluster {
                map,
                face,
                level,
                y,
                x,
            };
            out.insert(c, p);
        } else {
            for (cx, cy) in m.layout().children(level, x, y) {
                stack.push((map, face, level - 1, cx, cy));
            }
        }
    }
    out
}

fn two_maps() -> Vec<ImportanceMap> {
    vec![
        ImportanceMap::from_texels(5, 2, &random_masses(1, 2, 5)).unwrap(),
        ImportanceMap::from_texels(4, 1, &random_masses(2, 1, 4)).unwrap(),
    ]
}

#[test]
fn texel_samples_follow_the_importance() {
    // Chi-square of 200,000 independent warps to level 0 against N P(texel), over two RSMs (a
    // 5² map with two faces, odd-sized levels, and a 4² map) with empty texels.
    let maps = two_maps();
    let sampler = FilteredSampler::new(&maps);
    let texels = cut(&maps, u32::MAX);
    let m = 200_000;
    let mut observed: BTreeMap<Cluster, f64> = texels.keys().map(|c| (*c, 0.0)).collect();
    for u in iid_points(m, 3) {
        let (c, p) = sampler.warp(u, 1, Footprint::Texel).unwrap();
        assert_eq!(c.level, 0);
        let slot = observed.get_mut(&c).expect("a texel of mass 0 was sampled");
        *slot += 1.0;
        assert!((p - texels[&c]).abs() <= 1e-12, "{c:?}");
    }
    let expected: Vec<f64> = texels.values().map(|p| p * f64::from(m)).collect();
    let observed: Vec<f64> = observed.into_values().collect();
    let (stat, dof) = chi_square(&observed, &expected);
    assert!(dof > 40, "{dof}");
    assert!(stat < chi2_999(dof), "chi2 {stat} with {dof} dof");
}

#[test]
fn filtered_samples_follow_the_importance_of_the_cut() {
    // The same with the level of section 4.2 for N = 6 and N = 40: every warp ends in a
    // cluster of the cut, with frequency P(C).
    let maps = two_maps();
    let sampler = FilteredSampler::new(&maps);
    for n in [6, 40] {
        let clusters = cut(&maps, n);
        let m = 100_000;
        let mut observed: BTreeMap<Cluster, f64> = clusters.keys().map(|c| (*c, 0.0)).collect();
        for u in iid_points(m, 4) {
            let (c, p) = sampler.warp(u, n, Footprint::Filtered).unwrap();
            *observed.get_mut(&c).expect("a cluster outside the cut") += 1.0;
            assert!((p - clusters[&c]).abs() <= 1e-12);
        }
        let expected: Vec<f64> = clusters.values().map(|p| p * f64::from(m)).collect();
        let observed: Vec<f64> = observed.into_values().collect();
        let (stat, dof) = chi_square(&observed, &expected);
        assert!(dof >= 5, "N {n}: {dof}");
        assert!(stat < chi2_999(dof), "N {n}: chi2 {stat} with {dof} dof");
    }
}

#[test]
fn the_total_flux_estimate_is_unbiased() {
    // Σ w_C Φ(C) over the sampled clusters, for an importance unrelated to the flux, averaged
    // over 4000 seeds of the stratified set: the mean is the true total within 4.5 standard
    // errors, for both footprints and several N.
    let (n_tex, faces) = (8, 2);
    let importance =
        [ImportanceMap::from_texels(n_tex, faces, &random_masses(5, faces, n_tex)).unwrap()];
    // The flux is positive only where the importance is (sampling must reach every VPL).
    let flux_texels: Vec<f64> = random_masses(5, faces, n_tex)
        .iter()
        .enumerate()
        .map(|(k, &m)| if m > 0.0 { random(9, k as u32) } else { 0.0 })
        .collect();
    let flux = ImportanceMap::from_texels(n_tex, faces, &flux_texels).unwrap();
    let truth: f64 = flux_texels.iter().sum();
    let sampler = FilteredSampler::new(&importance);
    for footprint in [Footprint::Filtered, Footprint::Texel] {
        for n in [1, 5, 37, 300] {
            let seeds = 4000;
            let (mut sum, mut sum2) = (0.0, 0.0);
            for seed in 0..seeds {
                let points = sample_points(n, seed, SampleSet::Lights);
                let estimate: f64 = sampler
                    .sample(&points, footprint)
                    .iter()
                    .map(|s| {
                        let c = s.cluster;
                        s.weight * flux.mass(c.face, c.level, c.x, c.y)
                    })
                    .sum();
                sum += estimate;
                sum2 += estimate * estimate;
            }
            let mean = sum / f64::from(seeds);
            let var = (sum2 / f64::from(seeds) - mean * mean).max(0.0);
            let stderr = (var / f64::from(seeds)).sqrt();
            assert!(var > 0.0, "{footprint:?} N {n}: a degenerate test");
            assert!(
                (mean - truth).abs() < 4.5 * stderr,
                "{footprint:?} N {n}: mean {mean} truth {truth} stderr {stderr}"
            );
        }
    }
    // With the importance equal to the flux (the paper's default) every sample carries Φ/N:
    // the estimate is exact for every seed.
    let flux_only = [flux.clone()];
    let exact = FilteredSampler::new(&flux_only);
    for seed in 0..20 {
        let estimate: f64 = exact
            .sample(
                &sample_points(13, seed, SampleSet::Lights),
                Footprint::Filtered,
            )
            .iter()
            .map(|s| {
                s.weight * flux.mass(s.cluster.face, s.cluster.level, s.cluster.x, s.cluster.y)
            })
            .sum();
        assert!((estimate / truth - 1.0).abs() < 1e-12, "{estimate} {truth}");
    }
}

#[test]
fn levels_follow_the_paper_formula() {
    // Uniform importance on one 16² face, l_max = 4: l = ⌊l_max − ½ log2(N p)⌋ with p = 1 on
    // the unit square, clamped to [0, 4]; N = 1 takes the whole face, N ≥ 256 single texels.
    let uniform_map = [ImportanceMap::from_texels(16, 1, &[1.0; 256]).unwrap()];
    let sampler = FilteredSampler::new(&uniform_map);
    for n in [1u32, 2, 3, 4, 5, 15, 16, 17, 64, 100, 255, 256, 1000] {
        let want = (4.0 - 0.5 * f64::from(n).log2()).floor().clamp(0.0, 4.0) as u32;
        let samples = sampler.sample(&sample_points(n, 1, SampleSet::Lights), Footprint::Filtered);
        assert!(!samples.is_empty());
        for s in &samples {
            assert_eq!(s.cluster.level, want, "N {n}");
        }
        // Σ w P(C) = Σ m / N = 1: every sample is counted once.
        let total: f64 = samples.iter().map(|s| s.weight * s.probability).sum();
        assert!((total - 1.0).abs() < 1e-12, "N {n}: {total}");
    }
    // Several faces and maps with uneven importance: N = 1 stops at the top of every face; for
    // any N each cluster expects at most one sample or is a texel, and its parent more than one.
    let maps = two_maps();
    let sampler = FilteredSampler::new(&maps);
    for s in sampler.sample(&sample_points(1, 2, SampleSet::Lights), Footprint::Filtered) {
        let top = maps[s.cluster.map as usize].layout().levels() - 1;
        assert_eq!(s.cluster.level, top);
    }
    for n in [3, 10, 50, 200, 5000] {
        for s in sampler.sample(&sample_points(n, 3, SampleSet::Lights), Footprint::Filtered) {
            let c = s.cluster;
            let layout = maps[c.map as usize].layout();
            assert!(c.level == 0 || f64::from(n) * s.probability <= 1.0, "{c:?}");
            if c.level + 1 < layout.levels() {
                let parent = Cluster {
                    level: c.level + 1,
                    x: c.x / 2,
                    y: c.y / 2,
                    ..c
                };
                assert!(f64::from(n) * sampler.probability(&parent) > 1.0, "{c:?}");
            }
        }
    }
}

#[test]
fn sample_sets_are_deterministic_and_degenerate_inputs_are_empty() {
    let maps = two_maps();
    let sampler = FilteredSampler::new(&maps);
    let sample = |seed, set| sampler.sample(&sample_points(64, seed, set), Footprint::Filtered);
    let a = sample(7, SampleSet::Lights);
    let b = sample(7, SampleSet::Lights);
    let c = sample(8, SampleSet::Lights);
    let d = sample(7, SampleSet::Camera);
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert_ne!(a, d);
    // Sorted, distinct, and the hits add up to N.
    assert!(a.windows(2).all(|w| w[0].cluster < w[1].cluster));
    let hits: f64 = a.iter().map(|s| s.weight * 64.0 * s.probability).sum();
    assert!((hits - 64.0).abs() < 1e-9, "{hits}");
    for p in sample_points(1000, 7, SampleSet::Lights) {
        assert!(p.iter().all(|u| (0.0..1.0).contains(u)), "{p:?}");
    }
    assert!(sampler
        .sample(&sample_points(0, 7, SampleSet::Lights), Footprint::Filtered)
        .is_empty());
    let empty = [ImportanceMap::from_texels(4, 6, &[0.0; 96]).unwrap()];
    let none = FilteredSampler::new(&empty);
    assert_eq!(none.total(), 0.0);
    assert!(none.warp([0.5, 0.5], 4, Footprint::Filtered).is_none());
    assert!(none
        .sample(&sample_points(16, 7, SampleSet::Lights), Footprint::Texel)
        .is_empty());
    assert!(ImportanceMap::from_texels(2, 1, &[1.0, f64::NAN, 0.0, 0.0]).is_err());
    assert!(ImportanceMap::from_texels(2, 1, &[1.0, -1.0, 0.0, 0.0]).is_err());
    assert!(ImportanceMap::from_texels(2, 1, &[1.0; 3]).is_err());
}
