//! The VPLs of each interleaved-sampling subregion (paper section 6, Fig. 8).
use slc_core::{CullError, Interleaving, Vpl};

/// VPL indices grouped by subregion in compressed rows, ascending within each subregion:
/// subregion `s` holds `indices[offsets[s]..offsets[s + 1]]`. Every VPL is in exactly one
/// subregion, `Interleaving::vpl_subregion(vpl.id)`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Partition {
    offsets: Vec<u32>,
    indices: Vec<u32>,
}

impl Partition {
    /// Groups `vpls` by subregion (a counting sort, stable in the VPL index).
    pub(crate) fn new(vpls: &[Vpl], interleaving: Interleaving) -> Result<Self, CullError> {
        let subregions = check(interleaving, vpls.len())? as usize;
        let of: Vec<u32> = vpls
            .iter()
            .map(|v| interleaving.vpl_subregion(v.id))
            .collect();
        let (offsets, indices) = group_by(&of, subregions);
        Ok(Self { offsets, indices })
    }

    /// Number of subregions, K².
    pub(crate) fn subregions(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The VPL indices of subregion `s`, ascending.
    #[inline]
    pub(crate) fn of(&self, s: u32) -> &[u32] {
        &self.indices[self.offsets[s as usize] as usize..self.offsets[s as usize + 1] as usize]
    }
}

/// The indices `0..keys.len()` grouped by their key (each below `groups`), ascending within
/// each group (a counting sort, stable), in compressed rows: group `g` holds
/// `indices[offsets[g]..offsets[g + 1]]`. Returns `(offsets, indices)`.
pub(crate) fn group_by(keys: &[u32], groups: usize) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; groups + 1];
    for &g in keys {
        offsets[g as usize + 1] += 1;
    }
    for g in 0..groups {
        offsets[g + 1] += offsets[g];
    }
    let mut next = offsets.clone();
    let mut indices = vec![0u32; keys.len()];
    for (i, &g) in keys.iter().enumerate() {
        indices[next[g as usize] as usize] = i as u32;
        next[g as usize] += 1;
    }
    (offsets, indices)
}

/// Largest accepted interleaving factor K (K² = 2^20 subregions; more than any image needs).
pub(crate) const MAX_K: u32 = 1024;

/// Validates the interleaving factor 1 <= K <= [`MAX_K`] and a VPL count that fits the u32
/// indices of the light lists; returns K².
pub(crate) fn check(interleaving: Interleaving, vpl_count: usize) -> Result<u32, CullError> {
    let k = interleaving.k;
    if !(1..=MAX_K).contains(&k) {
        return Err(CullError::Input(format!(
            "interleaving factor K = {k} must lie in 1..={MAX_K}"
        )));
    }
    if u32::try_from(vpl_count).is_err() {
        return Err(CullError::Input(format!(
            "{vpl_count} VPLs do not fit 32-bit light indices"
        )));
    }
    Ok(k * k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use slc_bounds::{Brdf, Fresnel};
    use slc_core::VplLobe;

    fn vpls(n: u32) -> Vec<Vpl> {
        (0..n)
            .map(|id| Vpl {
                position: Vec3::ZERO,
                normal: Vec3::Y,
                geometric_normal: Vec3::Y,
                omega_i: Vec3::Y,
                flux: Vec3::ONE,
                brdf: Brdf {
                    kd: Vec3::ONE,
                    fresnel: Fresnel::Schlick(Vec3::ZERO),
                    alpha: 1.0,
                    anisotropy: None,
                },
                lobe: VplLobe::Diffuse,
                id,
                xi: 0.5,
            })
            .collect()
    }

    #[test]
    fn every_vpl_is_in_exactly_one_subregion() {
        let v = vpls(5000);
        for k in [1, 2, 3, 8] {
            let il = Interleaving { k, seed: 17 };
            let p = Partition::new(&v, il).unwrap();
            assert_eq!(p.subregions() as u32, k * k);
            let mut seen = vec![0u32; v.len()];
            for s in 0..k * k {
                let list = p.of(s);
                assert!(list.windows(2).all(|w| w[0] < w[1]), "ascending");
                for &i in list {
                    assert_eq!(il.vpl_subregion(v[i as usize].id), s);
                    seen[i as usize] += 1;
                }
            }
            assert!(seen.iter().all(|&c| c == 1));
        }
    }

    /// The subregion of a VPL is uniform: Pearson's chi-square of the counts of 65,536 ids
    /// over 64 subregions (63 degrees of freedom, mean 63, sd 11.2) stays below 130 (p < 1e-5
    /// for a uniform assignment), for several seeds; and every subregion gets some.
    #[test]
    fn subregions_are_uniform_chi_square() {
        let v = vpls(65_536);
        for seed in [0, 1, 7, 12345] {
            let il = Interleaving { k: 8, seed };
            let p = Partition::new(&v, il).unwrap();
            let expected = v.len() as f64 / 64.0;
            let chi2: f64 = (0..64)
                .map(|s| {
                    let d = p.of(s).len() as f64 - expected;
                    d * d / expected
                })
                .sum();
            println!("seed {seed}: chi-square {chi2:.1} (63 dof)");
            assert!(chi2 < 130.0, "seed {seed}: chi-square {chi2}");
            assert!((0..64).all(|s| !p.of(s).is_empty()));
        }
    }

    #[test]
    fn invalid_k_is_an_error() {
        assert!(Partition::new(&vpls(3), Interleaving { k: 0, seed: 0 }).is_err());
        assert!(Partition::new(&vpls(3), Interleaving { k: 70_000, seed: 0 }).is_err());
        assert!(Partition::new(&[], Interleaving { k: 2, seed: 0 }).is_ok());
    }
}
