//! GPU tiled culling against `slc_cull`'s for identical inputs (the CPU's G-buffer and
//! VPLs uploaded): every pixel's light list must be the same; any entry that differs is
//! reported with its pixel, subregion, tile and VPL.
use crate::bounds::{reference, Reference};
use crate::common::{cull_input, gpu};
use glam::{DVec2, DVec3};
use slc_core::frame::LobeSelection;
use slc_core::{builtin, Camera, CullInput, GBuffer, LightLists, Scene, Vpl, TILE_SIZE};
use slc_cpu_ref::gbuffer::{trace_gbuffer, PixelSample};
use slc_cpu_ref::rsm::{trace_rsm, TexelSample};
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::Tracer;
use slc_cull::{CullView, GlossyBound, FRUSTUM_SLACK};
use slc_gpu_wgpu::cull::tiled::TiledCuller;
use slc_gpu_wgpu::cull::ListCulling;

pub fn frame(scene: &Scene, camera: &Camera, size: (u32, u32), rsm: u32) -> (GBuffer, Vec<Vpl>) {
    let jittered = PixelSample::Jittered { seed: 5, index: 0 };
    frame_sampled(scene, camera, size, rsm, jittered)
}

/// [`frame`] with the G-buffer's samples taken at `sample` in each pixel.
pub fn frame_sampled(
    scene: &Scene,
    camera: &Camera,
    (w, h): (u32, u32),
    rsm: u32,
    sample: PixelSample,
) -> (GBuffer, Vec<Vpl>) {
    let tracer = Tracer::new(scene);
    let gbuffer = trace_gbuffer(scene, &tracer, camera, w, h, sample);
    let maps: Vec<_> = scene
        .lights
        .iter()
        .map(|l| trace_rsm(scene, &tracer, l, rsm, TexelSample::Centre))
        .collect();
    (gbuffer, generate_vpls(&maps, 11, LobeSelection::Both))
}

/// Largest distance of the bound's surface from the frustum box at which the CPU's f64 test
/// and the GPU's f32 test may disagree, relative to the scale of the f32 rounding of the
/// quantities compared: the scales of the bounds' conformance test (tests/gpu/bounds.rs),
/// where the GPU's errors stay below 3e-7 (f32 rounds at 6e-8).
const BORDER: f64 = 1e-6;

/// How much farther a CPU bound may reach than the reference, relative to the same scale:
/// the CPU forms the plain VPLs' bounds in f32 lanes grown by 1e-5 over slc-bounds' own
/// (`slc_cull`'s `vpl_lanes`), so it may list a VPL whose reference bound misses the
/// cluster by up to that much. The scale is at least the bound's size wherever the eye and
/// the world's origin lie outside the bound's reach of the VPL, as in these frames (else
/// such an entry would be reported as a real difference: a false alarm, never a miss).
const LANE_GROWTH: f64 = 1e-5;

/// The CPU's f64 tile (`crates/cull/src/tiled.rs` gather, `frusta.rs` set with
/// FRUSTUM_SLACK) holding pixel (x, y): its rectangle at unit depth, grown, and the view
/// depths of its samples.
pub fn cpu_tile(input: &CullInput, view: &CullView, x: u32, y: u32) -> ([DVec2; 2], Vec<f64>) {
    let (w, h, k) = (
        input.gbuffer.width,
        input.gbuffer.height,
        input.interleaving.k,
    );
    let (sx, sy) = (x % k, y % k);
    let first = (
        (x / k) / TILE_SIZE * TILE_SIZE,
        (y / k) / TILE_SIZE * TILE_SIZE,
    );
    let size = ((w - sx).div_ceil(k), (h - sy).div_ceil(k));
    let count = (
        TILE_SIZE.min(size.0 - first.0),
        TILE_SIZE.min(size.1 - first.1),
    );
    let screen = |a: u32, b: u32| (sx + k * (first.0 + a), sy + k * (first.1 + b));
    let (x0, y0) = screen(0, 0);
    let (x1, y1) = screen(count.0 - 1, count.1 - 1);
    let (mut lo, mut hi) = view.image_rect(x0, y0, x1 + 1, y1 + 1);
    let mut zs = Vec::new();
    for b in 0..count.1 {
        for a in 0..count.0 {
            let (px, py) = screen(a, b);
            if let Some(g) = &input.gbuffer.samples[(py * w + px) as usize] {
                let p = view.to_view(g.position);
                lo = lo.min(DVec2::new(p.x, p.y) / p.z);
                hi = hi.max(DVec2::new(p.x, p.y) / p.z);
                zs.push(p.z);
            }
        }
    }
    let pad = FRUSTUM_SLACK * (1.0 + lo.abs().max(hi.abs()).max_element());
    ([lo - pad, hi + pad], zs)
}

/// A cluster's depth range: the extremes of `zs`, grown by FRUSTUM_SLACK (`frusta.rs` set).
pub fn grown_range<'a>(zs: impl Iterator<Item = &'a f64>) -> [f64; 2] {
    let [a, b] = zs.fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &v| {
        [a.min(v), b.max(v)]
    });
    [a * (1.0 - FRUSTUM_SLACK), b * (1.0 + FRUSTUM_SLACK)]
}

/// The view depth of pixel (x, y)'s sample in the CPU's f64 culling view.
pub fn cpu_depth(input: &CullInput, view: &CullView, x: u32, y: u32) -> f64 {
    let w = input.gbuffer.width;
    let g = input.gbuffer.samples[(y * w + x) as usize]
        .as_ref()
        .unwrap();
    view.to_view(g.position).z
}

/// The CPU's f64 frustum of pixel (x, y)'s Modified HalfZ cluster (`depth.rs` HalfZ): the
/// tile rectangle and the cluster's depth range, and the cluster's name.
fn half_z_frustum(input: &CullInput, view: &CullView, x: u32, y: u32) -> (Frustum, String) {
    let (rect, zs) = cpu_tile(input, view, x, y);
    let z = cpu_depth(input, view, x, y);
    let (zmin, zmax) = zs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    let half = 0.5 * (zmin + zmax);
    let near = z < half;
    let range = grown_range(zs.iter().filter(|&&v| (v < half) == near));
    let name = if near { "near" } else { "far" };
    ((rect, range), format!("{name} cluster"))
}

/// A cluster frustum: the tile rectangle at unit depth and the cluster's depth range.
pub type Frustum = ([DVec2; 2], [f64; 2]);

/// How far outside (> 0) or inside (< 0) the cluster `frustum`'s box the CPU's f64 bound of
/// `vpl` is (`frusta.rs` sphere_hits and ellipsoid_hits), relative to the rounding scale of
/// [`BORDER`].
fn cpu_margin(
    input: &CullInput,
    view: &CullView,
    glossy: GlossyBound,
    vpl: usize,
    ([lo, hi], [z0, z1]): Frustum,
) -> f64 {
    let swept = |a: DVec3, b: DVec3| ((a * z0).min(a * z1), (b * z0).max(b * z1));
    let gap =
        |(bmin, bmax): (DVec3, DVec3), c: DVec3| (bmin - c).max(c - bmax).max(DVec3::ZERO).length();
    let inputs =
        input.vpls[vpl].position.as_dvec3().length() + input.camera.position.as_dvec3().length();
    match reference(&input.vpls[vpl], input.delta, view, glossy) {
        Reference::Empty => f64::INFINITY,
        Reference::Sphere { center, radius } => {
            let b = swept(lo.extend(1.0), hi.extend(1.0));
            (gap(b, center) - radius) / (center.length() + radius + inputs)
        }
        Reference::Ellipsoid {
            bs,
            center,
            view_center,
        } => {
            let (u0, u1) = (bs.x_axis * lo.x, bs.x_axis * hi.x);
            let (v0, v1) = (bs.y_axis * lo.y, bs.y_axis * hi.y);
            let ilo = bs.z_axis + u0.min(u1) + v0.min(v1);
            let ihi = bs.z_axis + u0.max(u1) + v0.max(v1);
            let norm = (bs.x_axis.length_squared()
                + bs.y_axis.length_squared()
                + bs.z_axis.length_squared())
            .sqrt();
            (gap(swept(ilo, ihi), center) - 1.0) / (norm * (view_center.length() + inputs))
        }
    }
}

/// Every entry in which the two pixels' lists differ, with where it is, split into the
/// borderline ones (the CPU's f64 bound lies within [`BORDER`] of the pixel's cluster
/// frustum box, `frustum(x, y)` with the cluster's name, where f32 and f64 may decide
/// differently, or on the CPU only and outside the box by less than [`LANE_GROWTH`] more;
/// or `frustum` gives `None`: the pixel's cluster is itself decided within rounding) and the
/// others.
pub fn differences(
    input: &CullInput,
    glossy: GlossyBound,
    cpu: &LightLists,
    gpu: &LightLists,
    frustum: impl Fn(&CullView, u32, u32) -> Option<(Frustum, String)>,
) -> (Vec<String>, Vec<String>) {
    let (width, k) = (input.gbuffer.width, input.interleaving.k);
    let view = CullView::new(input.camera, width, input.gbuffer.height).unwrap();
    let (mut border, mut real) = (Vec::new(), Vec::new());
    for p in 0..cpu.pixel_list.len() {
        let (a, b) = (cpu.for_pixel(p), gpu.for_pixel(p));
        if a == b {
            continue;
        }
        let (x, y) = (p as u32 % width, p as u32 / width);
        let tile = ((x / k) / TILE_SIZE, (y / k) / TILE_SIZE);
        let sub = (y % k) * k + x % k;
        let only = a.iter().filter(|v| !b.contains(v)).map(|&v| (v, "CPU"));
        let only = only.chain(b.iter().filter(|v| !a.contains(v)).map(|&v| (v, "GPU")));
        let mut any = false;
        let cluster = frustum(&view, x, y);
        for (v, side) in only {
            any = true;
            let Some((f, cluster)) = &cluster else {
                border.push(format!(
                    "pixel ({x}, {y}) subregion {sub} tile {tile:?}: VPL {v} on the {side} \
                     only, in a cluster decided within rounding"
                ));
                continue;
            };
            let margin = cpu_margin(input, &view, glossy, v as usize, *f);
            let text = format!(
                "pixel ({x}, {y}) subregion {sub} tile {tile:?} {cluster}: VPL {v} on the \
                 {side} only (CPU margin {margin:.1e})"
            );
            let grown = side == "CPU" && margin > 0.0 && margin <= BORDER + LANE_GROWTH;
            if margin.abs() <= BORDER || grown {
                border.push(text)
            } else {
                real.push(text)
            }
        }
        if !any {
            real.push(format!("pixel ({x}, {y}): same VPLs in another order"));
        }
    }
    (border, real)
}

#[test]
fn tiled_lists_match_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let culler = TiledCuller::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let mut longest_seen = 0;
    // Sizes with partial tiles and subregions of unequal size (72 x 50 with K = 4, 40 x 23
    // with K = 3); 320 x 180 with 11k VPLs gives lists of thousands of entries.
    for (size, k, rsm) in [
        ((96, 64), 1, 16),
        ((72, 50), 4, 16),
        ((40, 23), 3, 16),
        ((320, 180), 1, 32),
    ] {
        let (gbuffer, vpls) = frame(&scene, &camera, size, rsm);
        for delta in [1e-3f32, 1e-2] {
            let input = cull_input(&gbuffer, &camera, &vpls, delta, (k, 3));
            for (name, glossy) in [
                ("sphere", GlossyBound::Sphere),
                ("enclosing-sphere", GlossyBound::EnclosingSphere),
                ("ellipsoid", GlossyBound::Ellipsoid),
            ] {
                let cpu = slc_cull::culler(name.parse().unwrap())
                    .cull(&input)
                    .unwrap();
                let gpu = culler.cull(&ctx, &input, glossy).unwrap();
                let (border, diff) = differences(&input, glossy, &cpu, &gpu, |view, x, y| {
                    Some(half_z_frustum(&input, view, x, y))
                });
                let entries = cpu.indices.len();
                let longest = gpu
                    .offsets
                    .windows(2)
                    .map(|w| w[1] - w[0])
                    .max()
                    .unwrap_or(0);
                longest_seen = longest_seen.max(longest);
                eprintln!(
                    "{name} {size:?} K {k} delta {delta}: {} VPLs, {entries} CPU entries, {} GPU \
                     entries, {} borderline and {} other differing",
                    vpls.len(),
                    gpu.indices.len(),
                    border.len(),
                    diff.len()
                );
                for b in border.iter().take(10) {
                    eprintln!("  borderline: {b}");
                }
                assert!(
                    diff.is_empty(),
                    "{name} {size:?} K {k} delta {delta}: {} differing entries:\n{}",
                    diff.len(),
                    diff.iter().take(20).cloned().collect::<Vec<_>>().join("\n")
                );
                assert!(entries > 0);
            }
        }
    }
    // Lists longer than the 1024 entries tiled_cull.wesl keeps in workgroup memory: the
    // flushes in the middle of the loop were exercised.
    assert!(longest_seen > 1024, "longest list {longest_seen}");
}
