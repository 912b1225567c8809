// Light::spot_falloff (crates/core/src/light.rs, SpotCone): the KHR_lights_punctual falloff
// t^2 with t = (h_outer - h) / h_width, where h = 1 - cos of the angle between the emitted
// direction and the axis, taken as half the squared chord so that narrow cones (down to
// 0.01 degrees, where cos is 1 in f32) keep their precision; h_width = 0 is a hard edge.
fn spot_falloff(emitted: vec3<f32>, axis: vec3<f32>, h_outer: f32, h_width: f32) -> f32 {
    let chord = emitted - axis;
    let h = 0.5 * dot(chord, chord);
    if h_width > 0.0 {
        let t = clamp((h_outer - h) / h_width, 0.0, 1.0);
        return t * t;
    }
    return select(0.0, 1.0, h < h_outer);
}
