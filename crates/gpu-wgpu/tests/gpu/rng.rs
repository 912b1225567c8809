//! The WGSL RNG twin against `slc_core::rng`, bit for bit.
use crate::common::gpu;
use slc_core::rng::{hash4, pcg_hash, stream, uniform, vpl_xi};
use slc_core::Interleaving;
use slc_gpu_wgpu::vpl::rng::{RngPass, RngQuery};

fn check(pass: &RngPass, ctx: &slc_gpu_wgpu::GpuContext, q: RngQuery, count: u32) {
    let samples = pass.run(ctx, q, count).unwrap();
    assert_eq!(samples.len(), count as usize);
    let il = Interleaving {
        k: q.k,
        seed: q.seed,
    };
    for (i, s) in samples.iter().enumerate() {
        let i = i as u32;
        let h = hash4(q.seed, i, q.stream, q.counter);
        let u = uniform(q.seed, i, q.stream, q.counter);
        let want = (pcg_hash(i ^ q.seed), h, u.to_bits(), il.vpl_subregion(i));
        let got = (s.pcg, s.hash, s.uniform_bits, s.subregion);
        assert_eq!(
            got, want,
            "{q:?}, index {i}: GPU (pcg, hash4, uniform bits, subregion)"
        );
        if q.stream == stream::XI && q.counter == 0 {
            assert_eq!(
                s.uniform_bits,
                vpl_xi(q.seed, i).to_bits(),
                "{q:?}: xi of VPL {i}"
            );
        }
    }
}

#[test]
fn wgsl_rng_matches_cpu_bit_for_bit() {
    let Some(ctx) = gpu() else { return };
    let pass = RngPass::new(&ctx).unwrap();
    let queries = [
        (0, stream::XI, 0, 1),
        (7, stream::XI, 0, 8),
        (0xDEAD_BEEF, stream::INTERLEAVE, 0, 8),
        (12345, stream::RSM_JITTER, 3, 3),
        (u32::MAX, stream::PIXEL, 17, 4),
    ];
    for (seed, stream, counter, k) in queries {
        let q = RngQuery {
            seed,
            stream,
            counter,
            k,
        };
        check(&pass, &ctx, q, 1 << 20);
    }
}

/// More than 65535 workgroups of 64: the dispatch is split into a 2-D grid and every index
/// is still written exactly once with its own numbers.
#[test]
fn rng_beyond_one_dispatch_dimension() {
    let Some(ctx) = gpu() else { return };
    let pass = RngPass::new(&ctx).unwrap();
    let count = 65_536 * 64 + 123;
    let q = RngQuery {
        seed: 99,
        stream: stream::XI,
        counter: 0,
        k: 2,
    };
    check(&pass, &ctx, q, count);
}
