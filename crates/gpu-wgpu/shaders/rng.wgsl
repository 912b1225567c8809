// The WGSL twin of crates/core/src/rng.rs (counter-based random numbers): every function
// here must return, bit for bit, what its Rust namesake returns. Keep the two in sync;
// tests/rng.rs checks them against each other. Included in front of the shaders that draw
// random numbers.

// crates/core/src/rng.rs `stream`: independent uses of the same (seed, index).
const STREAM_XI: u32 = 0u;
const STREAM_RSM_JITTER: u32 = 1u;
const STREAM_PIXEL: u32 = 2u;
const STREAM_INTERLEAVE: u32 = 3u;

// The PCG hash of Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020.
// WGSL u32 arithmetic wraps like Rust's wrapping_mul / wrapping_add.
fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The `counter`-th number of `stream` for item `index`.
fn hash4(seed: u32, index: u32, stream: u32, counter: u32) -> u32 {
    let a = pcg_hash(seed ^ pcg_hash((stream * 0x9E3779B9u) ^ counter));
    return pcg_hash(a ^ pcg_hash(index));
}

// A hash to a float strictly inside (0, 1): (23 high bits + 1/2) * 2^-23, exact in f32.
fn to_unit_open(h: u32) -> f32 {
    return (f32(h >> 9u) + 0.5) * (1.0 / 8388608.0);
}

fn uniform_number(seed: u32, index: u32, stream: u32, counter: u32) -> f32 {
    return to_unit_open(hash4(seed, index, stream, counter));
}

// The Russian-roulette number xi of VPL `index` (paper eq. 3).
fn vpl_xi(seed: u32, index: u32) -> f32 {
    return uniform_number(seed, index, STREAM_XI, 0u);
}

// The interleaved-sampling subregion of VPL `vpl_id` for K x K subregions
// (slc_core::Interleaving::vpl_subregion).
fn vpl_subregion(seed: u32, vpl_id: u32, k: u32) -> u32 {
    if k == 1u {
        return 0u;
    }
    return hash4(seed, vpl_id, STREAM_INTERLEAVE, 0u) % (k * k);
}
