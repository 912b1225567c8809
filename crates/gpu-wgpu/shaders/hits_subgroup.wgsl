// tiled_shade.wgsl's mark_hits with subgroup operations (wgpu's Features::SUBGROUP): where all invocations of a subgroup hold entries of one
// mask word (its local indices lie in one aligned run of 32, as with subgroups of at most 32
// invocations in order), their bits are combined by subgroupOr and one invocation sets them:
// one atomic per subgroup and mask instead of one per hit. Otherwise (wider subgroups, or
// another layout) each invocation sets its own bit, as hits_atomic.wgsl does. The subgroup
// operations run in the workgroup's uniform control flow.
fn mark_hits(lid: u32, hit: vec2<u32>) {
    let word = lid / 32u;
    let bit = 1u << (lid % 32u);
    let near = select(0u, bit, hit.x != 0u);
    let far = select(0u, bit, hit.y != 0u);
    // The subgroup's first active invocation writes for it.
    let first = subgroupBroadcastFirst(lid);
    let one_word = subgroupAll(word == first / 32u);
    let near_word = subgroupOr(near);
    let far_word = subgroupOr(far);
    let elected = lid == first;
    if one_word {
        if elected && near_word != 0u {
            atomicOr(&near_bits[word], near_word);
        }
        if elected && far_word != 0u {
            atomicOr(&far_bits[word], far_word);
        }
    } else {
        if near != 0u {
            atomicOr(&near_bits[word], near);
        }
        if far != 0u {
            atomicOr(&far_bits[word], far);
        }
    }
}
