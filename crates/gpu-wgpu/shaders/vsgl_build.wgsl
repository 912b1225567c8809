// VSGLs built on the GPU from the frame's RSMs (src/vsgl_build_pass.rs), the twin of
// crates/cpu-ref/src/sampled_lights.rs sample_vsgls with the importance of ImportanceMap::
// from_mip or bidirectional_importance: the mipmapped RSMs of VSGL section 4.1 as pyramids of
// cluster sums (texels, camera_texels, reduce_sums), the importance of section 4.2 or 4.3
// (view, reduce_view), and filtered importance sampling of clusters by hierarchical sample
// warping (sample), each sampled cluster's VSGL scaled by m / (N P(C)) (own, a scan, emit).
// Nothing is read back. Entry points take the bindings they use, by number (GpuContext::encode_dispatch_at);
// structs mirror src/vsgl_build_types.rs. One invocation per item, linear workgroup index
// wid.y * num_workgroups.x + wid.x (buffers::Grid). fresnel_ggx.wgsl, sg.wgsl, gsample.wgsl,
// sg_surface.wgsl, vsgl_light.wgsl, rsm_texel.wgsl, solid_angle.wgsl, vsgl_tree.wgsl,
// vsgl_sums.wgsl and vsgl_from_sums.wgsl come first.

struct BuildParams {
    tree: Tree,
    // texels, view: the map's light position or orthographic origin (xyz) and face extent (w);
    // camera_texels: the eye (xyz) and a pixel's side at unit depth, 2 tan(yfov/2)/height (w).
    origin: vec4<f32>,
    // camera_texels: the view direction (xyz).
    forward: vec4<f32>,
    // Invocations of the dispatch.
    items: u32,
    // reduce_*: the level filled from the one below.
    level: u32,
    // texels, view: the map's first face in the tree and first texel over all maps (faults).
    first_face: u32,
    first_texel: u32,
    // texels: 1 for an orthographic map (a texel's cross-section is its area).
    orthographic: u32,
    // camera_texels: the image width.
    width: u32,
    // sample, emit: the number N of samples; view: the camera VSGLs.
    count: u32,
    // sample, emit: 1 when the importance mixes the view masses (section 4.3).
    bidirectional: u32,
    // sample: the Cranley-Patterson shift of the point set (sampling.rs sample_points).
    shift: vec2<f32>,
    // emit: the floor of σ_v^2.
    sigma2_floor: f32,
    // emit: bit 0 the clamped-cosine diffuse emission, bit 1 count the lights in the status.
    flags: u32,
}

@group(0) @binding(0) var<uniform> params: BuildParams;
@group(0) @binding(1) var<storage, read_write> status: VsglStatus;
// The pyramid of cluster sums, one array per field of Sums (vsgl_sums.wgsl), so that each
// binding stays a fifth of the pyramid (a storage binding is limited, 128 MiB on lavapipe).
@group(0) @binding(2) var<storage, read_write> sums_diffuse_m2: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> sums_specular_w: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> sums_diffuse_mean: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> sums_specular_mean: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> sums_mu: array<vec4<f32>>;
// The pyramid of view masses (bidirectional importance; unused otherwise).
@group(0) @binding(7) var<storage, read_write> view_mass: array<f32>;
// Per tree texel: samples that reached it (2i) and N - the first of them (2i + 1; 0: none).
@group(0) @binding(8) var<storage, read_write> marks: array<atomic<u32>>;
// Per sample: the tree texel it reached (NO_NODE: nothing to sample).
@group(0) @binding(9) var<storage, read_write> hit_node: array<u32>;
// Per light: its VSGL (emit), and its centre mu_v with w = 1.
@group(0) @binding(10) var<storage, read_write> vsgls_out: array<Vsgl>;
@group(0) @binding(11) var<storage, read_write> centres: array<vec4<f32>>;
@group(0) @binding(12) var<storage, read> rsm_texels: array<RsmTexel>;
@group(0) @binding(13) var<storage, read> samples: array<Sample>;
@group(0) @binding(14) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(15) var<storage, read> geometric_normals: array<vec4<f32>>;
@group(0) @binding(16) var<storage, read> camera_vsgls: array<Vsgl>;
// Per sample: 1 where it is the first to reach its cluster, 0 elsewhere (own); scanned into
// each such sample's light index, with the number of lights at [N] (scan.wgsl).
@group(0) @binding(17) var<storage, read_write> slots: array<u32>;

fn load_sums(i: u32) -> Sums {
    return Sums(sums_diffuse_m2[i], sums_specular_w[i], sums_diffuse_mean[i], sums_specular_mean[i],
                sums_mu[i]);
}

fn store_sums(i: u32, s: Sums) {
    sums_diffuse_m2[i] = s.diffuse_m2;
    sums_specular_w[i] = s.specular_w;
    sums_diffuse_mean[i] = s.diffuse_mean;
    sums_specular_mean[i] = s.specular_mean;
    sums_mu[i] = s.mu;
}

// The positional weight Σ w of tree texel i: its flux importance.
fn flux_mass(i: u32) -> f32 {
    return sums_specular_w[i].w;
}

const WORKGROUP: u32 = 64u;
const NO_NODE: u32 = 0xffffffffu;
// sampling.rs ONE_BELOW in f32: a warped coordinate never reaches 1.
const ONE_BELOW: f32 = 0.99999994;
// bidirectional.rs FLUX_SHARE: the flux importance's share of the mixture.
const FLUX_SHARE: f32 = 0.1;
const CLAMPED_DIFFUSE: u32 = 1u;
const COUNT_LIGHTS: u32 = 2u;

fn item(wid: vec3<u32>, groups: vec3<u32>, lid: u32) -> u32 {
    return (wid.y * groups.x + wid.x) * WORKGROUP + lid;
}

// Texel i of the map (face-major, then row-major): its column, row and level-0 tree texel.
fn map_texel(i: u32) -> vec3<u32> {
    let n = params.tree.n;
    let x = i % n;
    let y = (i / n) % n;
    return vec3<u32>(x, y, tree_index(params.tree, params.first_face + i / (n * n), 0u, x, y));
}

// RSM texel i of the map as ClusterSums::from_texel takes it (vsgl_readback's cpu_rsm had
// rebuilt the same on the CPU): the beam's cross-section is the texel's solid angle times its
// squared distance from the light, or its area for an orthographic map.
fn rsm_texel_input(t: RsmTexel, x: u32, y: u32) -> TexelIn {
    let n = params.tree.n;
    let e = params.origin.w;
    let ts = 2.0 / f32(n);
    var cross_section: f32;
    if params.orthographic != 0u {
        cross_section = (ts * e) * (ts * e);
    } else {
        let cx = (-1.0 + (f32(x) + 0.5) * ts) * e;
        let cy = (1.0 - (f32(y) + 0.5) * ts) * e;
        let d = t.position.xyz - params.origin.xyz;
        cross_section = texel_solid_angle(cx, cy, ts * e) * dot(d, d);
    }
    var alpha = t.normal_alpha.w;
    if t.anisotropy.w > 0.0 {
        alpha = sqrt(t.anisotropy.w * t.normal_alpha.w);
    }
    var f0_eta = t.f0.xyz;
    if t.info.x != FRESNEL_SCHLICK {
        f0_eta = vec3<f32>(t.omega_i_eta.w, 0.0, 0.0);
    }
    let surface = SurfaceIn(t.normal_alpha.xyz, t.omega_i_eta.xyz, t.kd.xyz, alpha, t.info.x, f0_eta);
    return TexelIn(t.position.xyz, t.geometric.xyz, t.flux.xyz, cross_section, surface);
}

// Level 0 of the map's pyramids from its RSM texels (MipRsm::build); a texel outside the SG
// domain is a fault and adds nothing.
@compute @workgroup_size(64)
fn texels(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
          @builtin(local_invocation_index) lid: u32) {
    let i = item(wid, groups, lid);
    if i >= params.items {
        return;
    }
    let at = map_texel(i);
    let t = rsm_texels[i];
    var s = sums_zero();
    if t.position.w != 0.0 {
        let input = rsm_texel_input(t, at.x, at.y);
        if valid_surface(input.surface) {
            s = texel_sums(input);
        } else {
            atomicMin(&status.bad_texel, params.first_texel + i);
        }
    }
    store_sums(at.z, s);
}

// Level 0 of the camera's map from the G-buffer (bidirectional.rs camera_rsm): pixel (x, y) is
// texel (x, y) of one square face, a surface of flux 1 lit from the camera, its cross-section
// the square of a pixel's side at its depth. Texels beyond the image stay zero.
@compute @workgroup_size(64)
fn camera_texels(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
                 @builtin(local_invocation_index) lid: u32) {
    let p = item(wid, groups, lid);
    if p >= params.items {
        return;
    }
    let x = p % params.width;
    let y = p / params.width;
    let s = samples[p];
    var out = sums_zero();
    if sample_present(s) {
        let position = positions[p].xyz;
        let depth = dot(position - params.origin.xyz, params.forward.xyz);
        let side = params.origin.w * depth;
        let input = TexelIn(position, geometric_normals[p].xyz, vec3<f32>(1.0), side * side, sample_surface(s));
        if valid_surface(input.surface) {
            out = texel_sums(input);
        } else {
            atomicMin(&status.bad_pixel, p);
        }
    }
    store_sums(tree_index(params.tree, 0u, 0u, x, y), out);
}

// The face, column and row of texel i of `level` (every face of the tree).
fn level_texel(i: u32, level: u32) -> vec3<u32> {
    let size = tree_size(params.tree, level);
    return vec3<u32>(i / (size * size), i % size, (i / size) % size);
}

// Child c of texel t (face, column, row) of params.level, in the order (0, 0), (1, 0),
// (0, 1), (1, 1) (Quadtree::children); NO_NODE beyond the edge of a level with odd size.
fn child_index(t: vec3<u32>, c: u32) -> u32 {
    let level = params.level - 1u;
    let size = tree_size(params.tree, level);
    let cx = 2u * t.y + (c & 1u);
    let cy = 2u * t.z + (c >> 1u);
    if cx < size && cy < size {
        return tree_index(params.tree, t.x, level, cx, cy);
    }
    return NO_NODE;
}

// Quadtree::fill_levels for the cluster sums: each texel of `level` merges its children, in
// the order (0, 0), (1, 0), (0, 1), (1, 1).
@compute @workgroup_size(64)
fn reduce_sums(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
               @builtin(local_invocation_index) lid: u32) {
    let i = item(wid, groups, lid);
    if i >= params.items {
        return;
    }
    let t = level_texel(i, params.level);
    var s = sums_zero();
    for (var c = 0u; c < 4u; c++) {
        let child = child_index(t, c);
        if child != NO_NODE {
            s = sums_merge(s, load_sums(child));
        }
    }
    store_sums(tree_index(params.tree, t.x, params.level, t.y, t.z), s);
}

// The same for the view masses.
@compute @workgroup_size(64)
fn reduce_view(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
               @builtin(local_invocation_index) lid: u32) {
    let i = item(wid, groups, lid);
    if i >= params.items {
        return;
    }
    let t = level_texel(i, params.level);
    var m = 0.0;
    for (var c = 0u; c < 4u; c++) {
        let child = child_index(t, c);
        if child != NO_NODE {
            m += view_mass[child];
        }
    }
    view_mass[tree_index(params.tree, t.x, params.level, t.y, t.z)] = m;
}

// The view importance of the map's texels (bidirectional.rs texel_masses): each texel shaded
// as a receiver seen from its light by every camera VSGL, without visibility; the mass is the
// RGB total of its flux times that radiance.
@compute @workgroup_size(64)
fn view(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
        @builtin(local_invocation_index) lid: u32) {
    let i = item(wid, groups, lid);
    if i >= params.items {
        return;
    }
    let at = map_texel(i);
    let t = rsm_texels[i];
    var mass = 0.0;
    if t.position.w != 0.0 {
        let input = rsm_texel_input(t, at.x, at.y);
        // A texel outside the domain is the texels pass's fault already.
        if valid_surface(input.surface) {
            let surface = make_surface(input.surface);
            var radiance = vec3<f32>(0.0);
            for (var v = 0u; v < params.count; v++) {
                let r = vsgl_contribution(surface, input.position, camera_vsgls[v]);
                if r.w != 0.0 {
                    atomicMin(&status.bad_view, params.first_texel + i);
                    break;
                }
                radiance += r.xyz;
            }
            let weighted = input.flux * radiance;
            mass = weighted.x + weighted.y + weighted.z;
            if !sg_finite(mass) {
                atomicMin(&status.bad_view, params.first_texel + i);
                mass = 0.0;
            }
        }
    }
    view_mass[at.z] = mass;
}

// The importance p(s) of a tree texel up to a constant (ImportanceMap, bidirectional.rs mix):
// the flux importance, its cluster's weight Σ w; with the bidirectional importance
// (1 - FLUX_SHARE) view / V + FLUX_SHARE flux / F over the totals V and F of every face (the
// flux alone where nothing is seen).
struct Importance {
    view_scale: f32,
    flux_scale: f32,
    total: f32,
}

fn mass(m: Importance, node: u32) -> f32 {
    var value = m.flux_scale * flux_mass(node);
    if m.view_scale > 0.0 {
        value += m.view_scale * view_mass[node];
    }
    return value;
}

fn face_top(face: u32) -> u32 {
    return tree_index(params.tree, face, params.tree.levels - 1u, 0u, 0u);
}

fn importance() -> Importance {
    var m = Importance(0.0, 1.0, 0.0);
    if params.bidirectional != 0u {
        var view_total = 0.0;
        var flux_total = 0.0;
        for (var f = 0u; f < params.tree.faces; f++) {
            view_total += view_mass[face_top(f)];
            flux_total += flux_mass(face_top(f));
        }
        var share = 1.0;
        if view_total > 0.0 {
            m.view_scale = (1.0 - FLUX_SHARE) / view_total;
            share = FLUX_SHARE;
        }
        m.flux_scale = select(0.0, share / flux_total, flux_total > 0.0);
    }
    for (var f = 0u; f < params.tree.faces; f++) {
        let face_mass = mass(m, face_top(f));
        if face_mass > 0.0 {
            m.total += face_mass;
        }
    }
    return m;
}

// sampling.rs split: the first branch with probability a / (a + b), never one of mass 0, and
// u rescaled onto the chosen branch (x: the branch, y: the new u).
fn split(u: f32, a: f32, b: f32) -> vec2<f32> {
    if b <= 0.0 {
        return vec2<f32>(0.0, u);
    }
    if a <= 0.0 {
        return vec2<f32>(1.0, u);
    }
    let p = a / (a + b);
    if u < p {
        return vec2<f32>(0.0, min(u / p, ONE_BELOW));
    }
    return vec2<f32>(1.0, clamp((u - p) / (1.0 - p), 0.0, ONE_BELOW));
}

// (v + shift) mod 1 for v and shift in [0, 1], formed below 1 (a sum in [1, 2) would keep
// one bit less), at most ONE_BELOW: the point to f32's 2^-24, where the CPU forms it in f64.
// From about 2^23 samples on, neighbouring points can round to one value.
fn shifted(v: f32, shift: f32) -> f32 {
    let room = 1.0 - shift;
    if v >= room {
        return min(v - room, ONE_BELOW);
    }
    return min(v + shift, ONE_BELOW);
}

// Sample k of N (sampling.rs sample_points and FilteredSampler::warp with Footprint::
// Filtered): the Hammersley point ((k + 1/2)/N, φ2(k)) shifted modulo 1; a face by its mass;
// down its quadtree, columns then rows of the chosen column by their masses, stopping at the
// first texel with N P(C) <= 1 or at level 0. Each texel reached counts its samples and keeps
// the first sample's index.
@compute @workgroup_size(64)
fn sample(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
          @builtin(local_invocation_index) lid: u32) {
    let k = item(wid, groups, lid);
    let count = params.count;
    if k >= count {
        return;
    }
    let m = importance();
    if !(m.total > 0.0) {
        hit_node[k] = NO_NODE;
        return;
    }
    let u0 = shifted(f32(2u * k + 1u) / f32(2u * count), params.shift.x);
    var uy = shifted(f32(reverseBits(k)) * 2.3283064365386963e-10, params.shift.y);
    // choose_face: the face whose interval of the cumulative masses holds u0 * total (the
    // last face with mass where rounding leaves the target at the end).
    let target_mass = u0 * m.total;
    var face = NO_NODE;
    var start = 0.0;
    var face_mass = 0.0;
    var last = NO_NODE;
    var last_start = 0.0;
    for (var f = 0u; f < params.tree.faces; f++) {
        let fm = mass(m, face_top(f));
        if !(fm > 0.0) {
            continue;
        }
        if face == NO_NODE && target_mass < start + fm {
            face = f;
            face_mass = fm;
            last_start = start;
        }
        last = f;
        start += fm;
    }
    if face == NO_NODE {
        face = last;
        face_mass = mass(m, face_top(last));
        last_start = m.total - face_mass;
    }
    var ux = clamp((target_mass - last_start) / face_mass, 0.0, ONE_BELOW);
    var level = params.tree.levels - 1u;
    var x = 0u;
    var y = 0u;
    loop {
        let probability = mass(m, tree_index(params.tree, face, level, x, y)) / m.total;
        if level == 0u || f32(count) * probability <= 1.0 {
            break;
        }
        let size = tree_size(params.tree, level - 1u);
        let x0 = 2u * x;
        let y0 = 2u * y;
        var child = array<f32, 4>(0.0, 0.0, 0.0, 0.0);
        for (var c = 0u; c < 4u; c++) {
            let cx = x0 + (c & 1u);
            let cy = y0 + (c >> 1u);
            if cx < size && cy < size {
                child[c] = mass(m, tree_index(params.tree, face, level - 1u, cx, cy));
            }
        }
        // child[0] = (x0, y0), child[1] = (x0 + 1, y0), child[2] = (x0, y0 + 1), child[3] = (x0 + 1, y0 + 1).
        let sx = split(ux, child[0] + child[2], child[1] + child[3]);
        let i = u32(sx.x);
        let sy = split(uy, child[i], child[i + 2u]);
        ux = sx.y;
        uy = sy.y;
        level -= 1u;
        x = x0 + i;
        y = y0 + u32(sy.x);
    }
    let node = tree_index(params.tree, face, level, x, y);
    hit_node[k] = node;
    atomicAdd(&marks[2u * node], 1u);
    atomicMax(&marks[2u * node + 1u], count - k);
}

// Whether sample k is the first to reach its cluster (the atomics of `sample`), which then
// becomes one light.
fn owns(k: u32) -> bool {
    let node = hit_node[k];
    return node != NO_NODE && params.count - atomicLoad(&marks[2u * node + 1u]) == k;
}

@compute @workgroup_size(64)
fn own(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
       @builtin(local_invocation_index) lid: u32) {
    let k = item(wid, groups, lid);
    if k < params.count {
        slots[k] = select(0u, 1u, owns(k));
    }
}

// The lights (sampled_lights.rs sample_vsgls): the first sample to reach a cluster writes the
// cluster's VSGL, scaled by m / (N P(C)) for the m samples that reached it, at its light
// index (the scan of `own`'s flags), so the lights are packed in the order of their first
// samples; the clusters are the CPU's, which sorts them by cluster instead.
@compute @workgroup_size(64)
fn emit(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>,
        @builtin(local_invocation_index) lid: u32) {
    let k = item(wid, groups, lid);
    let count = params.count;
    if k >= count || !owns(k) {
        return;
    }
    let node = hit_node[k];
    let light = slots[k];
    let hits = atomicLoad(&marks[2u * node]);
    let m = importance();
    // m / (N P(C)), P(C) = mass / total.
    let weight = f32(hits) * (m.total / (f32(count) * mass(m, node)));
    let packed = vsgl_pack(load_sums(node), weight, params.sigma2_floor, (params.flags & CLAMPED_DIFFUSE) != 0u);
    let lights = (params.flags & COUNT_LIGHTS) != 0u;
    if packed.ok && sg_finite(weight) {
        vsgls_out[light] = packed.vsgl;
        centres[light] = vec4<f32>(packed.vsgl.mu_sigma2.xyz, 1.0);
    } else if lights {
        atomicMin(&status.bad_vsgl, light);
    } else {
        atomicMin(&status.bad_camera_vsgl, light);
    }
    if lights {
        atomicAdd(&status.lights, 1u);
    }
}
