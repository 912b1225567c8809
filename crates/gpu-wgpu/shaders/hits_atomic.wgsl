// tiled_shade.wgsl's mark_hits without subgroup operations: each invocation sets its batch
// entry's bit in the near and far masks with its own atomic.
fn mark_hits(lid: u32, hit: vec2<u32>) {
    let bit = 1u << (lid % 32u);
    if hit.x != 0u {
        atomicOr(&near_bits[lid / 32u], bit);
    }
    if hit.y != 0u {
        atomicOr(&far_bits[lid / 32u], bit);
    }
}
