// The solid angle of an RSM texel seen from a pinhole light (the RSM resolve, rsm.wgsl, and
// the texel footprints of the VSGL construction, vsgl_build.wgsl).

// dw / dA on the face plane at unit distance: (1 + x^2 + y^2)^(-3/2).
fn solid_angle_density(x: f32, y: f32) -> f32 {
    let r2 = 1.0 + x * x + y * y;
    return 1.0 / (r2 * sqrt(r2));
}

// The solid angle of the texel square centred at (x, y) with side h on the plane at unit
// distance, by 3 x 3 Gauss-Legendre quadrature of the density. rsm.rs evaluates the closed
// form F(x1,y1) - F(x0,y1) - F(x1,y0) + F(x0,y0), F = atan2(xy, sqrt(x^2 + y^2 + 1)), in f64;
// in f32 its four O(1) terms would cancel to a few digits for small texels, while the
// quadrature of the smooth density is exact to ~h^6 relative (below f32 rounding for any
// n >= 4 on a cube face).
fn texel_solid_angle(x: f32, y: f32, h: f32) -> f32 {
    let node = 0.5 * h * 0.7745966692414834;
    let offsets = array<f32, 3>(-node, 0.0, node);
    let weights = array<f32, 3>(5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0);
    var sum = 0.0;
    for (var a = 0; a < 3; a++) {
        for (var b = 0; b < 3; b++) {
            sum += weights[a] * weights[b] * solid_angle_density(x + offsets[a], y + offsets[b]);
        }
    }
    return sum * h * h;
}
