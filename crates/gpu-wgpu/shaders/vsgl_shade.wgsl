// Shading by virtual spherical Gaussian lights (Tokuyoshi 2015, section 3.2, eq. 2-5), the GPU
// twin of crates/cpu-ref/src/vsgl/shading.rs shade_vsgls without visibility: each pixel with
// a sample sums, over the VSGLs, for each lobe c_v G(w; xi_v, lambda_v) of the VSGL's radiant
// intensity, c_v times the reflected radiance of the incoming SG of eq. (5)
//   L_in(w) = 1/(2 pi sigma_v^2) G(w; -xi_v, lambda_v) G(w; xi_mu, lambda_sigma),
//   xi_mu = (mu_v - x_p)/|mu_v - x_p|, lambda_sigma = |mu_v - x_p|^2 / sigma_v^2 (eq. 4),
// a product of two SGs, shaded in closed form as crates/bounds/src/sg/shading.rs SgSurface
// does: kd/pi times its irradiance plus the fitted GGX lobe's weight times an inner product
// (specular.rs SpecularLobeSg). fresnel_ggx.wgsl, sg.wgsl, gsample.wgsl, sg_surface.wgsl and
// vsgl_light.wgsl (the VSGL record, its radiance and the fault record) come first.
// Structs mirror src/vsgl_types.rs; one invocation per pixel, linear workgroup index
// wid.y * num_workgroups.x + wid.x (buffers::Grid).

struct VsglParams {
    pixel_count: u32,
    vsgl_count: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> params: VsglParams;
@group(0) @binding(1) var<storage, read> samples: array<Sample>;
@group(0) @binding(2) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vsgls: array<Vsgl>;
// RGB per pixel.
@group(0) @binding(4) var<storage, read_write> image: array<f32>;
@group(0) @binding(5) var<storage, read_write> status: VsglStatus;

const WORKGROUP: u32 = 64u;

// VSGL v at the receiver (vsgl_light.wgsl), its overflow recorded; w != 0 stops the pixel's
// sum (the frame is an error then).
fn contribution(surface: Surface, x: vec3<f32>, v: u32) -> vec4<f32> {
    let r = vsgl_contribution(surface, x, vsgls[v]);
    if r.w != 0.0 {
        atomicMin(&status.overflow_vsgl, v);
    }
    return r;
}

fn write_pixel(pixel: u32, sum: vec3<f32>) {
    image[3u * pixel] = sum.x;
    image[3u * pixel + 1u] = sum.y;
    image[3u * pixel + 2u] = sum.z;
}

// Without visibility (shade_vsgls(..., visibility = false, ...)).
@compute @workgroup_size(64)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if pixel >= params.pixel_count {
        return;
    }
    let s = samples[pixel];
    var sum = vec3<f32>(0.0);
    if sample_present(s) {
        let input = sample_surface(s);
        if valid_surface(input) {
            let surface = make_surface(input);
            let x = positions[pixel].xyz;
            for (var v = 0u; v < params.vsgl_count; v++) {
                let r = contribution(surface, x, v);
                if r.w != 0.0 {
                    break;
                }
                sum += r.xyz;
            }
        } else {
            atomicMin(&status.bad_pixel, pixel);
        }
    }
    write_pixel(pixel, sum);
}

// With visibility from imperfect shadow maps (ism.wgsl; ism_map.wgsl comes before this file):
// the geometric normal per pixel (xyz), the maps' parameters and their distances (one map of
// resolution^2 f32 bits per VSGL, in VSGL order).
@group(0) @binding(6) var<storage, read> geometric_normals: array<vec4<f32>>;
@group(0) @binding(7) var<uniform> ism: IsmParams;
@group(0) @binding(8) var<storage, read> ism_depth: array<u32>;

// V(x_p, mu_v) of eq. (3) from the map of VSGL v: the receiver x lifted by the tracer's
// epsilon along its geometric normal (Tracer::lift) is visible when its distance to mu_v is at
// most the map's distance in its direction plus the bias
//   lift + dist * texel_angle * (bias_constant + bias_slope * tan(incidence)),
// the incidence between the geometric normal and the direction to mu_v, its tangent capped at
// 20 (receivers more grazing than 87 degrees reflect next to nothing). Segments no longer than
// twice the lift are unoccluded, as Tracer::unoccluded has them.
fn ism_visible(v: u32, x: vec3<f32>, n_g: vec3<f32>, mu: vec3<f32>) -> bool {
    let d = x + n_g * ism.lift - mu;
    let dist = length(d);
    if dist <= 2.0 * ism.lift {
        return true;
    }
    let dir = d / dist;
    let res = ism.resolution;
    let t = oct_texel(dir, res);
    let z = bitcast<f32>(ism_depth[v * res * res + t.y * res + t.x]);
    let c = max(abs(dot(n_g, dir)), 0.05);
    let slope = sqrt(max(1.0 - c * c, 0.0)) / c;
    let bias = ism.lift + dist * ism.texel_angle * (ism.bias_constant + ism.bias_slope * slope);
    return dist <= z + bias;
}

// shade_vsgls(..., visibility = true, ...) with the maps for shadow rays: each VSGL that
// contributes is weighted by ism_visible.
@compute @workgroup_size(64)
fn main_visible(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let pixel = (wid.y * groups.x + wid.x) * WORKGROUP + lid;
    if pixel >= params.pixel_count {
        return;
    }
    let s = samples[pixel];
    var sum = vec3<f32>(0.0);
    if sample_present(s) {
        let input = sample_surface(s);
        if valid_surface(input) {
            let surface = make_surface(input);
            let x = positions[pixel].xyz;
            let n_g = geometric_normals[pixel].xyz;
            for (var v = 0u; v < params.vsgl_count; v++) {
                let r = contribution(surface, x, v);
                if r.w != 0.0 {
                    break;
                }
                if any(r.xyz != vec3<f32>(0.0)) && ism_visible(v, x, n_g, vsgls[v].mu_sigma2.xyz) {
                    sum += r.xyz;
                }
            }
        } else {
            atomicMin(&status.bad_pixel, pixel);
        }
    }
    write_pixel(pixel, sum);
}
