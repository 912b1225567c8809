//! What the rasterization tests share: the scenes (the built-in default, the glTF reference
//! room of `shared/reference/cornell-a`, textured Dabrovic Sponza from `shared/scenes`, the
//! normal-mapped, alpha-masked, double-sided `scenes/materials`), and the definition of edge
//! pixels.
//!
//! **Edge pixel** (of a ray-traced CPU G-buffer): a pixel whose 3 x 3 neighbourhood does not
//! lie on one surface: some neighbour differs in presence (sample or none), or its
//! geometric normal differs (dot < 1 − 1e-4), or it lies off the pixel's plane by more than
//! 1e-4 of the scene extent (a depth discontinuity or a crease), or its Fresnel kind, F0 or α
//! differ (a material boundary). There, the rasterizer and the ray tracer may pick different
//! triangles, since the pixel centre lies within a pixel of an edge; elsewhere both must see
//! the same surface. Two coplanar triangles of one material are not an edge (either choice
//! gives the same sample).
use glam::Vec3;
use slc_core::{load_scene, Camera, GBuffer, GSample, Light, Scene};

#[path = "../../../../tests/fixtures/scenes.rs"]
mod scenes;
pub use scenes::sponza;

/// The built-in default scene (`cornell-glossy`) and its camera.
pub fn default_scene() -> (Scene, Camera) {
    let scene = slc_core::builtin("default").unwrap();
    let camera = scene.camera_or_default();
    (scene, camera)
}

/// `shared/reference/cornell-a` (glTF, metallic-roughness materials, a point light, its own
/// camera).
pub fn cornell_a() -> (Scene, Camera) {
    with_its_camera(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/reference/cornell-a/cornell-a.gltf"
    ))
}

/// `scenes/materials` (glTF: a normal-mapped glossy floor with generated tangents, a
/// double-sided alpha-masked sheet, a point light, its own camera).
pub fn materials() -> (Scene, Camera) {
    with_its_camera(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/materials/materials.gltf"
    ))
}

/// `scenes/anisotropy` (glTF `KHR_materials_anisotropy`: a brushed floor with generated
/// tangents, a brushed panel with stored tangents and a rotated anisotropy).
pub fn anisotropy() -> (Scene, Camera) {
    with_its_camera(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/anisotropy/anisotropy.gltf"
    ))
}

/// A scene file and the camera it carries.
fn with_its_camera(path: &str) -> (Scene, Camera) {
    let scene = load_scene(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let camera = scene.camera_or_default();
    (scene, camera)
}

/// The default scene with its spot and point lights, a directional light and a wide spot.
pub fn lit_scene() -> Scene {
    let (mut scene, _) = default_scene();
    scene.lights.push(Light::Directional {
        direction: Vec3::new(0.3, -1.0, -0.4).normalize(),
        irradiance: Vec3::new(1.0, 0.8, 0.6),
    });
    scene.lights.push(Light::Spot {
        position: Vec3::new(-0.5, 1.8, 0.5),
        direction: Vec3::new(0.2, -1.0, -0.3).normalize(),
        intensity: Vec3::splat(3.0),
        inner_cone_angle: 60f32.to_radians(),
        outer_cone_angle: 85f32.to_radians(),
    });
    scene
}

/// The largest absolute coordinate of the scene, at least 1 (`GpuScene::extent`).
pub fn extent(scene: &Scene) -> f32 {
    let (lo, hi) = scene.bounds().unwrap();
    lo.abs().max(hi.abs()).max_element().max(1.0)
}

/// Whether `b` lies on the surface of `a` (see the module documentation).
fn same_surface(a: &GSample, b: &GSample, tolerance: f32) -> bool {
    a.geometric_normal.dot(b.geometric_normal) >= 1.0 - 1e-4
        && a.geometric_normal.dot(b.position - a.position).abs() <= tolerance
        && a.brdf.fresnel == b.brdf.fresnel
        && a.brdf.alpha == b.brdf.alpha
        && a.brdf.anisotropy.map(|x| x.alpha_t) == b.brdf.anisotropy.map(|x| x.alpha_t)
}

/// The edge pixels of a `width` x `height` grid of samples (see the module documentation),
/// `extent` the scene's size.
pub fn edge_pixels(g: &GBuffer, extent: f32) -> Vec<bool> {
    let (w, h) = (g.width as i64, g.height as i64);
    let at = |x: i64, y: i64| &g.samples[(y * w + x) as usize];
    let tolerance = 1e-4 * extent;
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let centre = at(x, y);
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w || ny >= h {
                        return false;
                    }
                    match (centre, at(nx, ny)) {
                        (Some(a), Some(b)) => !same_surface(a, b, tolerance),
                        (None, None) => false,
                        _ => true,
                    }
                })
            })
        })
        .collect()
}

/// The fraction of `true` entries.
pub fn fraction(flags: &[bool]) -> f64 {
    flags.iter().filter(|&&f| f).count() as f64 / flags.len().max(1) as f64
}
