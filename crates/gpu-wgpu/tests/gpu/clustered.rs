//! GPU clustered culling (`clustered`, `clustered-sphere`, `clustered-enclosing-sphere`)
//! against `slc_cull`'s for identical inputs (the CPU's G-buffer and VPLs uploaded): every
//! pixel's light list must be the same list, entry for entry in the same (ascending) order.
//! A differing entry is reported with its pixel, subregion, tile, depth slice and VPL.
//!
//! Two kinds of difference are tolerated, both where f32 and f64 may decide differently, and
//! reported: an entry whose CPU f64 bound lies within `BORDER` of its cluster frustum's box,
//! or on the CPU only within `LANE_GROWTH` more (the rules of `tiled.rs`), and the entries
//! of a tile where a sample's slice key
//! t = ln(z / near) 32 / ln(far / near) lies within [`SLICE_BORDER`] of a slice boundary
//! and the GPU put it in the neighbouring slice. Every pixel's slice is compared with the
//! CPU's; any other slice difference fails.
use crate::common::{cull_input, gpu};
use crate::tiled::{cpu_depth, cpu_tile, differences, frame, grown_range, Frustum};
use slc_core::{builtin, CullInput, GBuffer, LightLists, Vpl, NO_LIST, TILE_SIZE};
use slc_cull::{CullView, GlossyBound};
use slc_gpu_wgpu::cull::clustered::records::CLUSTER_SLICES;
use slc_gpu_wgpu::cull::clustered::ClusteredCuller;
use slc_gpu_wgpu::cull::lists::read_lists;
use slc_gpu_wgpu::cull::ListCulling;
use slc_gpu_wgpu::device::buffers::read_back;
use slc_gpu_wgpu::GpuContext;
use std::collections::HashSet;

/// Distance of the CPU's f64 slice key from a slice boundary (in slices) within which the
/// GPU's f32 key may fall on the other side: the GPU's view depth errs by ~3e-7 relative and
/// its logarithms by a few ulps (Vulkan allows 3 ulp, or 2^-21 absolute near 1), which the
/// factor 32 / ln(far / near) (below 40 for any scene here) turns into less than 3e-5.
const SLICE_BORDER: f64 = 1e-4;

/// The CPU's exponential slicing (`crates/cull/src/tiled.rs` cull, `depth.rs`
/// DepthSplit::slices and key): the G-buffer's depth range in the f64 culling view.
pub struct CpuSlices {
    near: f64,
    scale: f64,
}

impl CpuSlices {
    pub fn new(input: &CullInput, view: &CullView) -> Self {
        let (near, far) = input
            .gbuffer
            .samples
            .iter()
            .flatten()
            .map(|g| view.to_view(g.position).z)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
                (a.min(z), b.max(z))
            });
        let log_ratio = (far / near).ln();
        let scale = if log_ratio > 0.0 {
            f64::from(CLUSTER_SLICES) / log_ratio
        } else {
            0.0
        };
        Self { near, scale }
    }

    /// The key value of depth `z` (its slice is the floor, clamped to 0..=31).
    pub fn key(&self, z: f64) -> f64 {
        (z / self.near).ln() * self.scale
    }

    pub fn slice(&self, z: f64) -> u32 {
        self.key(z)
            .floor()
            .clamp(0.0, f64::from(CLUSTER_SLICES - 1)) as u32
    }

    /// Whether the slice of `z` is decided within rounding.
    pub fn borderline(&self, z: f64) -> bool {
        let t = self.key(z);
        (t - t.round()).abs() <= SLICE_BORDER
    }
}

/// The CPU's f64 frustum of pixel (x, y)'s slice: the tile rectangle and the depth range of
/// the tile's samples in the same slice.
fn slice_frustum(
    input: &CullInput,
    view: &CullView,
    slices: &CpuSlices,
    x: u32,
    y: u32,
) -> (Frustum, String) {
    let (rect, zs) = cpu_tile(input, view, x, y);
    let slice = slices.slice(cpu_depth(input, view, x, y));
    let range = grown_range(zs.iter().filter(|&&z| slices.slice(z) == slice));
    ((rect, range), format!("slice {slice}"))
}

/// What one comparison found.
#[derive(Default)]
struct Found {
    border: Vec<String>,
    real: Vec<String>,
    /// Largest number of occupied slices in a tile.
    most_slices: usize,
}

/// The GPU's clustered lists for `input` against the CPU's, slices and entries.
fn compare(ctx: &GpuContext, culler: &ClusteredCuller, input: &CullInput, name: &str) -> Found {
    let glossy = match name {
        "clustered" => GlossyBound::Ellipsoid,
        "clustered-sphere" => GlossyBound::Sphere,
        _ => GlossyBound::EnclosingSphere,
    };
    let cpu = slc_cull::culler(name.parse().unwrap()).cull(input).unwrap();
    let on_gpu = culler.cull_on_gpu(ctx, input, glossy).unwrap();
    let raw: Vec<u32> =
        read_back(ctx, "pixel lists", &on_gpu.pixel_list, cpu.pixel_list.len()).unwrap();
    let gpu = read_lists(ctx, &on_gpu).unwrap();
    let (w, h, k) = (
        input.gbuffer.width,
        input.gbuffer.height,
        input.interleaving.k,
    );
    let view = CullView::new(input.camera, w, h).unwrap();
    let slices = CpuSlices::new(input, &view);
    let mut found = Found::default();
    // Tiles (GPU tile ids) whose slices differ within rounding, and each tile's slices.
    let mut reclustered = HashSet::new();
    let mut occupied = std::collections::HashMap::<u32, u32>::new();
    for (p, (&list, g)) in raw.iter().zip(&input.gbuffer.samples).enumerate() {
        let (x, y) = (p as u32 % w, p as u32 / w);
        let Some(_) = g else {
            if list != NO_LIST {
                found
                    .real
                    .push(format!("pixel ({x}, {y}) has no sample but list {list}"));
            }
            continue;
        };
        let (tile, gpu_slice) = (list / CLUSTER_SLICES, list % CLUSTER_SLICES);
        *occupied.entry(tile).or_default() |= 1 << gpu_slice;
        let z = cpu_depth(input, &view, x, y);
        let cpu_slice = slices.slice(z);
        if list == NO_LIST || gpu_slice != cpu_slice {
            let text = format!(
                "pixel ({x}, {y}) tile {:?}: slice {gpu_slice} on the GPU, {cpu_slice} on the \
                 CPU (key {:.7})",
                ((x / k) / TILE_SIZE, (y / k) / TILE_SIZE),
                slices.key(z)
            );
            if list != NO_LIST && slices.borderline(z) {
                reclustered.insert(tile);
                found.border.push(text);
            } else {
                found.real.push(text);
            }
        }
    }
    found.most_slices = occupied
        .values()
        .map(|m| m.count_ones() as usize)
        .max()
        .unwrap_or(0);
    let (border, real) = differences(input, glossy, &cpu, &gpu, |view, x, y| {
        let list = raw[(y * w + x) as usize];
        (!reclustered.contains(&(list / CLUSTER_SLICES)))
            .then(|| slice_frustum(input, view, &slices, x, y))
    });
    found.border.extend(border);
    found.real.extend(real);
    assert_eq!(cpu.pixel_list.len(), gpu.pixel_list.len());
    found
}

/// Blanks a rectangle and every 7th pixel of `g` (sky: no sample).
fn with_sky(g: &GBuffer) -> GBuffer {
    let mut g = g.clone();
    let w = g.width as usize;
    for (p, s) in g.samples.iter_mut().enumerate() {
        let (x, y) = (p % w, p / w);
        if p % 7 == 3 || (x < w / 3 && y < 9) {
            *s = None;
        }
    }
    g
}

#[test]
fn clustered_lists_match_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let culler = ClusteredCuller::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    let mut most_slices = 0;
    // Partial tiles and unequal subregions (72 x 50 with K = 4, 40 x 23 with K = 3), sky
    // pixels, images smaller than K, one pixel, no VPLs; 1,000 VPLs and more give each tile
    // several chunks of 256 bounds, 320 x 180 with 11k VPLs lists of thousands of entries.
    for (size, k, rsm, sky, no_vpls) in [
        ((96, 64), 1, 16, false, false),
        ((72, 50), 4, 16, false, false),
        ((40, 23), 3, 16, true, false),
        ((61, 37), 1, 16, true, false),
        ((3, 2), 4, 4, false, false),
        ((1, 1), 1, 4, false, false),
        ((40, 23), 3, 8, true, true),
        ((320, 180), 1, 32, false, false),
    ] {
        let (gbuffer, vpls) = frame(&scene, &camera, size, rsm);
        let gbuffer = if sky { with_sky(&gbuffer) } else { gbuffer };
        let vpls: Vec<Vpl> = if no_vpls { Vec::new() } else { vpls };
        for delta in [1e-3f32, 1e-2] {
            let input = cull_input(&gbuffer, &camera, &vpls, delta, (k, 3));
            for name in [
                "clustered",
                "clustered-sphere",
                "clustered-enclosing-sphere",
            ] {
                let found = compare(&ctx, &culler, &input, name);
                most_slices = most_slices.max(found.most_slices);
                eprintln!(
                    "{name} {size:?} K {k} delta {delta} sky {sky}: {} VPLs, {} borderline and \
                     {} other differences, at most {} slices in a tile",
                    vpls.len(),
                    found.border.len(),
                    found.real.len(),
                    found.most_slices
                );
                for b in found.border.iter().take(10) {
                    eprintln!("  borderline: {b}");
                }
                assert!(
                    found.real.is_empty(),
                    "{name} {size:?} K {k} delta {delta}: {} differences:\n{}",
                    found.real.len(),
                    found
                        .real
                        .iter()
                        .take(20)
                        .cloned()
                        .collect::<Vec<_>>()
                        .join("\n")
                );
            }
        }
    }
    // The per-slice tests ran: some tile had many slices.
    assert!(most_slices >= 4, "at most {most_slices} slices in a tile");
}

/// Each pixel's list, or what differs, for two list sets that must be identical.
fn exact_differences(input: &CullInput, cpu: &LightLists, gpu: &LightLists) -> Vec<String> {
    let (w, k) = (input.gbuffer.width, input.interleaving.k);
    (0..cpu.pixel_list.len())
        .filter(|&p| cpu.for_pixel(p) != gpu.for_pixel(p))
        .map(|p| {
            let (a, b) = (cpu.for_pixel(p), gpu.for_pixel(p));
            let (x, y) = (p as u32 % w, p as u32 / w);
            let cpu_only: Vec<_> = a.iter().filter(|v| !b.contains(v)).collect();
            let gpu_only: Vec<_> = b.iter().filter(|v| !a.contains(v)).collect();
            format!(
                "pixel ({x}, {y}) subregion {}: VPLs {cpu_only:?} on the CPU only, {gpu_only:?} \
                 on the GPU only ({} and {} entries)",
                (y % k) * k + x % k,
                a.len(),
                b.len()
            )
        })
        .collect()
}

/// No culling: every pixel's list is its subregion's VPLs, exactly the CPU's.
#[test]
fn unculled_lists_match_the_cpu() {
    let Some(ctx) = gpu() else { return };
    let culler = slc_gpu_wgpu::cull::none::NoneCuller::new(&ctx).unwrap();
    let scene = builtin("default").unwrap();
    let camera = scene.camera_or_default();
    for (size, k, sky, no_vpls) in [
        ((96, 64), 1, false, false),
        ((72, 50), 4, true, false),
        ((40, 23), 3, true, false),
        ((3, 2), 4, false, false),
        ((1, 1), 1, false, false),
        ((40, 23), 3, false, true),
    ] {
        let (gbuffer, vpls) = frame(&scene, &camera, size, 16);
        let gbuffer = if sky { with_sky(&gbuffer) } else { gbuffer };
        let vpls: Vec<Vpl> = if no_vpls { Vec::new() } else { vpls };
        let input = cull_input(&gbuffer, &camera, &vpls, 1e-3, (k, 9));
        let cpu = slc_cull::culler(slc_core::Strategy::None)
            .cull(&input)
            .unwrap();
        let gpu = culler.cull(&ctx, &input).unwrap();
        let diff = exact_differences(&input, &cpu, &gpu);
        eprintln!(
            "none {size:?} K {k} sky {sky}: {} VPLs, {} entries, {} differing pixels",
            vpls.len(),
            cpu.indices.len(),
            diff.len()
        );
        assert!(
            diff.is_empty(),
            "none {size:?} K {k}: {} differing pixels:\n{}",
            diff.len(),
            diff.iter().take(20).cloned().collect::<Vec<_>>().join("\n")
        );
        assert_eq!(gpu.pixel_list.len(), cpu.pixel_list.len());
    }
}
