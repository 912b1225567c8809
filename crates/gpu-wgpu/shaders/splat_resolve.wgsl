// The splatted atlas (splat.wgsl: subregion (i, j)'s viewport at (i view_w, j view_h)) back
// to the screen's pixel order: RGB per pixel, every pixel written. bound_mesh.wgsl prepended.

@group(0) @binding(0) var<uniform> params: RasterParams;
@group(0) @binding(1) var atlas: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> image: array<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.width || gid.y >= params.height {
        return;
    }
    let ij = gid.xy % params.k;
    let texel = ij * vec2<u32>(params.view_w, params.view_h) + gid.xy / params.k;
    let c = textureLoad(atlas, vec2<i32>(texel), 0);
    let pixel = gid.y * params.width + gid.x;
    image[3u * pixel] = c.x;
    image[3u * pixel + 1u] = c.y;
    image[3u * pixel + 2u] = c.z;
}
