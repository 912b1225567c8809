//! VSGLs shaded eight at a time: [`Emitter`]s packed into chunks of eight lanes, whose
//! radiance at a receiver is [`Emitter::radiance_in`] in AVX registers where the CPU has AVX2
//! (in plain arrays elsewhere), equal to the one-VSGL form bit for bit.
use super::emitter::{ClampedDiffuse, EmittedLobe, Emitter, OVERFLOW};
use super::error::VsglError;
use glam::Vec3;
use slc_bounds::lanes::{Lanes8, F8, M8};
use slc_bounds::sg::{splat3, IrradianceFit, LobeStretch, SgLanes};
use slc_bounds::SgSurface;

/// Emitters in chunks of eight lanes (the last chunk's unused lanes dark), grouped by the
/// SG lobes they shade: a chunk evaluates a lobe for all its lanes where any lane has it, so
/// VSGLs with one specular SG and those with the three of the mixture share no chunk where
/// that can be helped. Within a group they go by `σ²`, so that a chunk's lanes see positional
/// lobes of similar sharpness `λ_σ = |μ − x|²/σ²` and take the same branches more often.
pub(crate) struct EmitterChunks {
    chunks: Vec<Emitter<F8>>,
    /// The emitters' indices in lane order.
    order: Vec<usize>,
    avx2: bool,
}

impl EmitterChunks {
    pub(crate) fn new(emitters: &[Emitter]) -> Self {
        let mut order: Vec<usize> = (0..emitters.len()).collect();
        order.sort_by(|&a, &b| {
            let (ea, eb) = (&emitters[a], &emitters[b]);
            (Self::shape(ea).cmp(&Self::shape(eb))).then(ea.sigma2.total_cmp(&eb.sigma2))
        });
        let chunks = order
            .chunks(8)
            .map(|c| {
                let lane = |k: usize| c.get(k).map_or(&Emitter::DARK, |&i| &emitters[i]);
                gather(core::array::from_fn(lane))
            })
            .collect();
        #[cfg(target_arch = "x86_64")]
        let avx2 = std::arch::is_x86_feature_detected!("avx2");
        #[cfg(not(target_arch = "x86_64"))]
        let avx2 = false;
        Self {
            chunks,
            order,
            avx2,
        }
    }

    /// Which lobes an emitter shades, as a sort key: the present SG lobes and the clamped
    /// diffuse intensity, one bit each.
    fn shape(e: &Emitter) -> u8 {
        let lobes = e.lobes.iter().enumerate();
        lobes.fold(u8::from(e.clamped.present), |key, (j, l)| {
            key | (u8::from(l.present) << (j + 1))
        })
    }

    /// Calls `visit` with the index and radiance of every emitter at the receiver `surface` at
    /// `x_p` (its [`Emitter::radiance`], bit for bit), eight at a time, in the chunks' order
    /// (grouped by [`Self::shape`], not the emitters' order); fails where a `λ_σ` or lobe
    /// product leaves `f32`.
    pub(crate) fn each_radiance(
        &self,
        surface: &SgSurface,
        x_p: Vec3,
        mut visit: impl FnMut(usize, Vec3),
    ) -> Result<(), VsglError> {
        for (chunk, indices) in self.chunks.iter().zip(self.order.chunks(8)) {
            let (radiance, overflow) = self.radiance(chunk, surface, x_p);
            if overflow != 0 {
                return Err(OVERFLOW.into());
            }
            for (k, &i) in indices.iter().enumerate() {
                let c = Vec3::new(radiance[0].0[k], radiance[1].0[k], radiance[2].0[k]);
                visit(i, c);
            }
        }
        Ok(())
    }

    /// The radiance of `chunk`'s eight lanes at the receiver, and the overflowing lanes' bits.
    fn radiance(&self, chunk: &Emitter<F8>, surface: &SgSurface, x_p: Vec3) -> ([F8; 3], u8) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` holds only where the CPU supports AVX2 (checked in `new`).
            return unsafe { radiance_avx2(chunk, surface, x_p) };
        }
        radiance_lanes::<F8>(chunk, surface, x_p)
    }
}

/// [`radiance_lanes`] in AVX registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn radiance_avx2(chunk: &Emitter<F8>, surface: &SgSurface, x_p: Vec3) -> ([F8; 3], u8) {
    radiance_lanes::<slc_bounds::lanes_avx::A8>(chunk, surface, x_p)
}

/// `chunk`'s radiance at the receiver in lanes of `L`, stored, with the overflow bits.
#[inline(always)]
fn radiance_lanes<L: Lanes8>(chunk: &Emitter<F8>, surface: &SgSurface, x_p: Vec3) -> ([F8; 3], u8) {
    let (radiance, overflow) = load::<L>(chunk).radiance_in(surface, splat3(x_p));
    let [r, g, b] = radiance;
    ([r.store(), g.store(), b.store()], L::bits(overflow))
}

/// Eight emitters in the lanes of one.
fn gather(lanes: [&Emitter; 8]) -> Emitter<F8> {
    let f = |v: &dyn Fn(&Emitter) -> f32| F8(lanes.map(v));
    let m = |v: &dyn Fn(&Emitter) -> bool| M8(lanes.map(|e| u32::from(v(e)).wrapping_neg()));
    let f3 = |v: &dyn Fn(&Emitter) -> [f32; 3]| -> [F8; 3] {
        core::array::from_fn(|i| F8(lanes.map(|e| v(e)[i])))
    };
    let lobe = |j: usize| EmittedLobe {
        c: f3(&|e| e.lobes[j].c),
        lobe: SgLanes {
            axis: f3(&|e| e.lobes[j].lobe.axis),
            sharpness: f(&|e| e.lobes[j].lobe.sharpness),
            amplitude: f(&|e| e.lobes[j].lobe.amplitude),
        },
        present: m(&|e| e.lobes[j].present),
        stretched: m(&|e| e.lobes[j].stretched),
    };
    Emitter {
        mu: f3(&|e| e.mu),
        sigma2: f(&|e| e.sigma2),
        density: f(&|e| e.density),
        lobes: [lobe(0), lobe(1), lobe(2), lobe(3)],
        clamped: ClampedDiffuse {
            peak: f3(&|e| e.clamped.peak),
            normal: f3(&|e| e.clamped.normal),
            fit: IrradianceFit {
                mean: f(&|e| e.clamped.fit.mean),
                x: f(&|e| e.clamped.fit.x),
                away: f(&|e| e.clamped.fit.away),
            },
            present: m(&|e| e.clamped.present),
        },
        stretch: LobeStretch {
            tangent: f3(&|e| e.stretch.tangent),
            bitangent: f3(&|e| e.stretch.bitangent),
            cos: f(&|e| e.stretch.cos),
            inv_cos: f(&|e| e.stretch.inv_cos),
        },
        live: m(&|e| e.live),
    }
}

/// A chunk in the lanes of `L`.
#[inline(always)]
fn load<L: Lanes8>(e: &Emitter<F8>) -> Emitter<L> {
    let v3 = |v: &[F8; 3]| [L::load(&v[0]), L::load(&v[1]), L::load(&v[2])];
    let lobe = |l: &EmittedLobe<F8>| EmittedLobe {
        c: v3(&l.c),
        lobe: SgLanes {
            axis: v3(&l.lobe.axis),
            sharpness: L::load(&l.lobe.sharpness),
            amplitude: L::load(&l.lobe.amplitude),
        },
        present: L::load_mask(&l.present),
        stretched: L::load_mask(&l.stretched),
    };
    let c = &e.clamped;
    Emitter {
        mu: v3(&e.mu),
        sigma2: L::load(&e.sigma2),
        density: L::load(&e.density),
        lobes: [
            lobe(&e.lobes[0]),
            lobe(&e.lobes[1]),
            lobe(&e.lobes[2]),
            lobe(&e.lobes[3]),
        ],
        clamped: ClampedDiffuse {
            peak: v3(&c.peak),
            normal: v3(&c.normal),
            fit: IrradianceFit {
                mean: L::load(&c.fit.mean),
                x: L::load(&c.fit.x),
                away: L::load(&c.fit.away),
            },
            present: L::load_mask(&c.present),
        },
        stretch: LobeStretch {
            tangent: v3(&e.stretch.tangent),
            bitangent: v3(&e.stretch.bitangent),
            cos: L::load(&e.stretch.cos),
            inv_cos: L::load(&e.stretch.inv_cos),
        },
        live: L::load_mask(&e.live),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vsgl::Vsgl;
    use slc_bounds::{Brdf, Fresnel};
    use slc_core::frame::DiffuseEmission;

    /// A xorshift stream of numbers in [0, 1).
    struct Rng(u64);

    impl Rng {
        fn f32(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }
        fn range(&mut self, lo: f32, hi: f32) -> f32 {
            lo + (hi - lo) * self.f32()
        }
        fn unit(&mut self) -> Vec3 {
            loop {
                let v = Vec3::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.f32());
                if v.length_squared() > 0.01 {
                    return v.normalize();
                }
            }
        }
        /// `10^u` with `u` uniform in `[lo, hi)`, or 0 one time in `zero_in`.
        fn log(&mut self, lo: f32, hi: f32, zero_in: u32) -> f32 {
            if (self.f32() * zero_in as f32) < 1.0 {
                0.0
            } else {
                10f32.powf(self.range(lo, hi))
            }
        }
    }

    /// A VSGL with lobes of sharpness 1e-4…1e5 (each missing now and then), concentration up to
    /// 1e7 and `σ²` from 1e-6 to 100, near the origin.
    fn vsgl(rng: &mut Rng) -> Vsgl {
        let c = |rng: &mut Rng| Vec3::new(rng.f32(), rng.f32(), rng.f32()) * rng.log(-3.0, 3.0, 5);
        let xi_specular = rng.unit();
        // The specular normal unknown now and then, along the lobe's axis now and then, else
        // any direction.
        let specular_normal = match (rng.f32() * 8.0) as u32 {
            0 => Vec3::ZERO,
            1 => xi_specular,
            _ => rng.unit(),
        };
        Vsgl {
            c_diffuse: c(rng),
            xi_diffuse: rng.unit(),
            lambda_diffuse: rng.log(-4.0, 2.0, 8),
            normal_concentration: rng.log(-3.0, 7.0, 8),
            c_specular: c(rng),
            xi_specular,
            lambda_specular: rng.log(-3.0, 5.0, 8),
            specular_normal,
            mu: Vec3::new(
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
            ),
            sigma2: 10f32.powf(rng.range(-6.0, 2.0)),
            weight: 1.0,
        }
    }

    fn brdf(f0: f32, alpha: f32) -> Brdf {
        Brdf {
            kd: Vec3::new(0.8, 0.5, 0.1),
            fresnel: Fresnel::Schlick(Vec3::splat(f0)),
            alpha,
            anisotropy: None,
        }
    }

    /// The radiance of every emitter through the chunks, as bit patterns in the emitters'
    /// order (each visited once).
    fn through(chunks: &EmitterChunks, surface: &SgSurface, x_p: Vec3) -> Vec<[u32; 3]> {
        let mut out = vec![None; chunks.order.len()];
        chunks
            .each_radiance(surface, x_p, |i, c| {
                assert!(out[i].is_none(), "{i} twice");
                out[i] = Some(c.to_array().map(f32::to_bits));
            })
            .unwrap();
        out.into_iter().map(Option::unwrap).collect()
    }

    /// Eight at a time (AVX2 where the CPU has it, plain arrays too) equals one at a time bit
    /// for bit, for both diffuse forms, counts that are not multiples of eight, receivers at a
    /// VSGL's mean and lanes taking different branches; an overflowing `λ_σ` fails in both.
    #[test]
    fn chunks_equal_one_vsgl_at_a_time_bit_for_bit() {
        let mut rng = Rng(0x005E_ED0F_7511);
        for trial in 0..400 {
            let count = 1 + (rng.f32() * 19.0) as usize;
            let vsgls: Vec<Vsgl> = (0..count).map(|_| vsgl(&mut rng)).collect();
            let n = rng.unit();
            let brdf = brdf(rng.f32(), rng.log(-3.0, 0.0, 1_000_000).max(1e-3));
            let surface = SgSurface::new(n, (n + rng.unit()).normalize(), &brdf).unwrap();
            let x_p = if trial % 7 == 0 {
                vsgls[0].mu
            } else {
                Vec3::new(
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                )
            };
            for diffuse in [DiffuseEmission::ClampedCosine, DiffuseEmission::Sg] {
                let emitters: Vec<Emitter> = vsgls
                    .iter()
                    .map(|v| Emitter::new(v, diffuse).unwrap())
                    .collect();
                let one_at_a_time: Vec<[u32; 3]> = emitters
                    .iter()
                    .map(|e| {
                        let c = e.radiance(&surface, x_p).unwrap();
                        assert!(c.is_finite() && c.min_element() >= 0.0, "{c}");
                        c.to_array().map(f32::to_bits)
                    })
                    .collect();
                let mut chunks = EmitterChunks::new(&emitters);
                // Grouped by shape: a chunk mixes shapes only where one group ends.
                let shapes: Vec<u8> = chunks
                    .order
                    .iter()
                    .map(|&i| EmitterChunks::shape(&emitters[i]))
                    .collect();
                assert!(shapes.windows(2).all(|w| w[0] <= w[1]), "{shapes:?}");
                assert_eq!(through(&chunks, &surface, x_p), one_at_a_time);
                chunks.avx2 = false;
                assert_eq!(through(&chunks, &surface, x_p), one_at_a_time);
            }
        }
        // λ_σ = |μ − x|²/σ² beyond f32 in one lane: an error either way.
        let mut far = vsgl(&mut rng);
        far.sigma2 = 1e-36;
        far.mu = Vec3::splat(1e3);
        let emitters: Vec<Emitter> = [vsgl(&mut rng), vsgl(&mut rng), far]
            .iter()
            .map(|v| Emitter::new(v, DiffuseEmission::Sg).unwrap())
            .collect();
        let surface = SgSurface::new(Vec3::Z, Vec3::Z, &brdf(0.04, 0.5)).unwrap();
        assert!(emitters[2].radiance(&surface, Vec3::ZERO).is_err());
        let chunks = EmitterChunks::new(&emitters);
        assert!(chunks
            .each_radiance(&surface, Vec3::ZERO, |_, _| {})
            .is_err());
    }
}
