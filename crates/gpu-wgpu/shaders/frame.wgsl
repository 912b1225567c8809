// The frame of Duff et al. 2017 around the unit vector z (crates/bounds frame.rs Frame): x and
// y with x, y, z right-handed and orthonormal, branch-free and accurate for every z.

// copysign(1, z.z) as frame.rs: -1 for z.z = -0.0 too (the tangent angle of a G-buffer sample
// is stored in this frame, so both sides must build the same one).
fn frame_sign(z: vec3<f32>) -> f32 {
    return select(-1.0, 1.0, (bitcast<u32>(z.z) & 0x80000000u) == 0u);
}

fn frame_x(z: vec3<f32>) -> vec3<f32> {
    let s = frame_sign(z);
    let a = -1.0 / (s + z.z);
    let b = z.x * z.y * a;
    return vec3<f32>(1.0 + s * z.x * z.x * a, s * b, -s * z.x);
}

fn frame_y(z: vec3<f32>) -> vec3<f32> {
    let s = frame_sign(z);
    let a = -1.0 / (s + z.z);
    let b = z.x * z.y * a;
    return vec3<f32>(b, s + z.y * z.y * a, -z.y);
}
