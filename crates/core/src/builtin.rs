//! Scenes made in code.
//!
//! `default` is `cornell-glossy`: the room of `shared/reference/cornell-a` (room
//! `[-1,1]×[0,2]×[-1,1]` open at z = +1, one-sided walls facing into the room: white floor,
//! ceiling and back wall, red left wall, green right wall, kd 0.7 / 0.1, F0 0.04, α 1; point
//! light of 5 W/sr at (0, 1.5, 0); camera at (0, 1, 3.4) looking at (0, 1, 0), 40° vertical
//! field of view) with a rough copper panel (kd 0, F0 (0.95, 0.64, 0.54), α 0.15) leaning
//! towards the left wall and tilted so that a spot light's mirror reflection crosses the room
//! and lands on the green wall: a glossy caustic a diffuse-only method cannot produce. The spot
//! (120 W/sr, 6°-10° cone) sits high in the front right corner and aims at the panel; the point
//! light is dimmed to a 2 W/sr fill. A blue diffuse box stands near the back right corner.
use crate::camera::Camera;
use crate::light::Light;
use crate::material::Material;
use crate::scene::Scene;
use crate::shapes::{cuboid, quad};
use glam::{Quat, Vec3};

/// Names [`builtin`] knows; `default` is the same scene as `cornell-glossy`.
pub const BUILTIN_NAMES: &[&str] = &["default", "cornell-glossy"];

/// The built-in scene called `name`, or `None` if there is none (see [`BUILTIN_NAMES`]).
pub fn builtin(name: &str) -> Option<Scene> {
    match name {
        "default" | "cornell-glossy" => Some(cornell_glossy()),
        _ => None,
    }
}

/// Centre of the copper panel (its lowest corner is just above the floor).
const PANEL_CENTRE: Vec3 = Vec3::new(-0.6, 0.42, -0.3);
/// Direction (not normalized) the copper panel's front face points to: towards the green
/// wall and up towards the light, so that the light's mirror image lands on the green wall.
const PANEL_FACING: Vec3 = Vec3::new(1.0, 0.6, 0.2);
/// A narrow spot light high in the front right corner aims at the panel, so most glossy VPLs
/// sit on the copper and their caustic on the green wall is bright.
const SPOT_POSITION: Vec3 = Vec3::new(0.7, 1.9, 0.6);

fn cornell_glossy() -> Scene {
    let wall = |name: &str, kd: Vec3| Material::direct(name, kd, Vec3::splat(0.04), 1.0);
    let materials = vec![
        wall("white", Vec3::splat(0.7)),
        wall("red", Vec3::new(0.7, 0.1, 0.1)),
        wall("green", Vec3::new(0.1, 0.7, 0.1)),
        Material::direct("copper", Vec3::ZERO, Vec3::new(0.95, 0.64, 0.54), 0.08),
        wall("blue", Vec3::new(0.2, 0.3, 0.8)),
    ];
    let (white, red, green, copper, blue) = (0, 1, 2, 3, 4);
    let (x2, y2, z2) = (2.0 * Vec3::X, 2.0 * Vec3::Y, 2.0 * Vec3::Z);
    // Panel axes: height along the panel's in-plane "up", width across, thickness along the normal.
    let n = PANEL_FACING.normalize();
    let up = (Vec3::Y - Vec3::Y.dot(n) * n).normalize();
    let panel_axes = [0.45 * up, 0.4 * n.cross(up), 0.02 * n];
    let turn = Quat::from_rotation_y(25f32.to_radians());
    let box_axes = [turn * Vec3::X * 0.2, Vec3::Y * 0.3, turn * Vec3::Z * 0.2];
    let meshes = vec![
        quad("floor", Vec3::new(-1.0, 0.0, 1.0), x2, -z2, white),
        quad("ceiling", Vec3::new(-1.0, 2.0, -1.0), x2, z2, white),
        quad("back", Vec3::new(-1.0, 0.0, -1.0), x2, y2, white),
        quad("left", Vec3::new(-1.0, 0.0, 1.0), -z2, y2, red),
        quad("right", Vec3::new(1.0, 0.0, -1.0), z2, y2, green),
        cuboid("copper panel", PANEL_CENTRE, panel_axes, copper),
        cuboid("blue box", Vec3::new(0.45, 0.3, -0.6), box_axes, blue),
    ];
    let camera = Camera::look_at(
        Vec3::new(0.0, 1.0, 3.4),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::Y,
        40f32.to_radians(),
    )
    .map(|c| Camera {
        znear: 0.01,
        zfar: 100.0,
        ..c
    });
    Scene {
        name: "cornell-glossy".into(),
        meshes,
        materials,
        textures: Vec::new(),
        lights: vec![
            Light::Spot {
                position: SPOT_POSITION,
                direction: (PANEL_CENTRE - SPOT_POSITION).normalize(),
                intensity: Vec3::splat(120.0),
                inner_cone_angle: 6f32.to_radians(),
                outer_cone_angle: 10f32.to_radians(),
            },
            Light::Point {
                position: Vec3::new(0.0, 1.5, 0.0),
                intensity: Vec3::splat(2.0),
            },
        ],
        camera,
        ..Scene::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::MaterialModel;

    /// Whether the open segment from `a` to `b` hits any triangle of the scene.
    fn occluded(scene: &Scene, a: Vec3, b: Vec3) -> bool {
        let d = b - a;
        scene
            .meshes
            .iter()
            .flat_map(|m| {
                m.triangles
                    .iter()
                    .map(move |t| t.map(|i| m.positions[i as usize]))
            })
            .any(|[p0, p1, p2]| {
                // Möller-Trumbore.
                let (e1, e2) = (p1 - p0, p2 - p0);
                let pv = d.cross(e2);
                let det = e1.dot(pv);
                if det.abs() < 1e-12 {
                    return false;
                }
                let s = a - p0;
                let u = s.dot(pv) / det;
                let q = s.cross(e1);
                let v = d.dot(q) / det;
                let t = e2.dot(q) / det;
                u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 1e-4 && t < 1.0 - 1e-4
            })
    }

    #[test]
    fn default_is_cornell_glossy_and_renderable() {
        let s = builtin("default").unwrap();
        assert_eq!(s, builtin("cornell-glossy").unwrap());
        assert_eq!(s.name, "cornell-glossy");
        assert!(builtin("nonexistent").is_none());
        s.validate_for_render().unwrap();
        assert_eq!(s.lights.len(), 2);
        let cam = s.camera.as_ref().unwrap();
        assert!((cam.forward - Vec3::NEG_Z).length() < 1e-6);
        assert!(s.has_specular());
        let metal = s.materials.iter().find(|m| {
            let b = m.brdf_at(None, &s.textures);
            b.kd == Vec3::ZERO
                && matches!(b.fresnel, slc_bounds::Fresnel::Schlick(f0) if f0.min_element() > 0.5)
        });
        assert!(
            matches!(metal.unwrap().model, MaterialModel::Direct { alpha, .. } if (0.05..=0.2).contains(&alpha))
        );
    }

    #[test]
    fn walls_face_into_the_room_and_objects_stay_inside_it() {
        let s = builtin("default").unwrap();
        let room_centre = Vec3::new(0.0, 1.0, 0.0);
        for m in &s.meshes {
            let normals = m.normals.as_ref().unwrap();
            for t in &m.triangles {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                let face = (b - a).cross(c - a).normalize();
                assert!(
                    t.iter()
                        .all(|&i| (normals[i as usize] - face).length() < 1e-5),
                    "{}",
                    m.name
                );
                if ["floor", "ceiling", "back", "left", "right"].contains(&m.name.as_str()) {
                    assert!(
                        face.dot(room_centre - (a + b + c) / 3.0) > 0.0,
                        "{} faces out of the room",
                        m.name
                    );
                }
            }
            let inside =
                |p: &Vec3| p.x.abs() <= 1.0 && (0.0..=2.0).contains(&p.y) && p.z.abs() <= 1.0;
            assert!(m.positions.iter().all(inside), "{} leaves the room", m.name);
        }
    }

    #[test]
    fn the_copper_panel_reflects_the_light_onto_the_visible_green_wall() {
        let s = builtin("default").unwrap();
        let Light::Spot {
            position: light,
            direction,
            outer_cone_angle,
            ..
        } = s.lights[0]
        else {
            panic!("a spot light aimed at the panel expected")
        };
        assert!(direction.dot((PANEL_CENTRE - light).normalize()) > outer_cone_angle.cos());
        let n = PANEL_FACING.normalize();
        let hit = PANEL_CENTRE + 0.02 * n; // centre of the panel's front face
        assert!(!occluded(&s, light, hit + 1e-3 * n));
        let incoming = (hit - light).normalize();
        let mirror = incoming - 2.0 * incoming.dot(n) * n;
        let t = (1.0 - hit.x) / mirror.x;
        assert!(t > 0.0);
        let spot = hit + t * mirror;
        assert!(
            (0.2..1.8).contains(&spot.y) && spot.z.abs() < 0.8,
            "caustic centre {spot}"
        );
        assert!(!occluded(&s, hit + 1e-3 * n, spot - 1e-3 * Vec3::X));
        let eye = s.camera.as_ref().unwrap().position;
        eprintln!("caustic centre {spot}");
        assert!(
            !occluded(&s, eye, spot - 1e-3 * Vec3::X),
            "the caustic is hidden from the camera"
        );
    }
}
