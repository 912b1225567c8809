//! Loader tests on the real scene files of `shared/` and on broken files written to a
//! temporary folder. Paths are relative to this crate: the repository's parent folder holds
//! `shared/`.
use crate::material::{MaterialAnisotropy, MaterialModel};
use crate::{load_scene, Light, Scene, SceneError};
use glam::{Vec2, Vec3};
use slc_bounds::Fresnel;
use std::path::PathBuf;

macro_rules! shared {
    ($rel:literal) => {
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/", $rel)
    };
}

/// A fresh, empty temporary folder for one test.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slc-core-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

fn material_named<'a>(scene: &'a Scene, name: &str) -> &'a crate::Material {
    scene
        .materials
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no material {name}"))
}

#[test]
fn reference_cornell_a() {
    let s = load_scene(shared!("reference/cornell-a/cornell-a.gltf")).unwrap();
    assert_eq!(s.name, "cornell-a");
    assert_eq!((s.meshes.len(), s.triangle_count()), (7, 2230));
    assert_eq!(s.report.skipped.total(), 0);
    assert!(s.report.warnings.is_empty(), "{:?}", s.report.warnings);
    assert_eq!(
        s.lights,
        vec![Light::Point {
            position: Vec3::new(0.0, 1.5, 0.0),
            intensity: Vec3::splat(5.0)
        }]
    );
    let cam = s.camera.as_ref().unwrap();
    assert!(
        close(cam.position, Vec3::new(0.0, 1.0, 3.4))
            && close(cam.forward, Vec3::NEG_Z)
            && close(cam.up, Vec3::Y)
    );
    assert!((cam.yfov - 0.6981317).abs() < 1e-6);
    assert_eq!((cam.znear, cam.zfar), (0.01, 100.0));

    let brdf = |mesh: &str| {
        let m = s.meshes.iter().find(|m| m.name.starts_with(mesh)).unwrap();
        s.materials[m.material].brdf_at(None, &s.textures)
    };
    let b = brdf("box");
    assert_eq!(b.kd, Vec3::ZERO);
    assert!(matches!(b.fresnel, Fresnel::Schlick(f0) if close(f0, Vec3::new(0.95, 0.64, 0.54))));
    assert!((b.alpha - 0.2).abs() < 1e-6);
    let f = brdf("floor");
    assert!(close(f.kd, Vec3::splat(0.7)) && f.alpha == 1.0);
    s.validate_for_render().unwrap();

    // Stored normals are the face normals; walls face into the room.
    let floor = s
        .meshes
        .iter()
        .find(|m| m.name.starts_with("floor"))
        .unwrap();
    assert!(floor
        .normals
        .as_ref()
        .unwrap()
        .iter()
        .all(|&n| close(n, Vec3::Y)));
    assert!(!s.materials.iter().any(|m| m.double_sided));
}

#[test]
fn cornell_gltf_binary_with_node_hierarchy() {
    let s = load_scene(shared!("scenes/cornell-gltf/cornell-box.glb")).unwrap();
    assert_eq!(s.name, "cornell-box");
    assert_eq!(s.triangle_count() + s.report.skipped.total(), 1040);
    assert!(s.lights.is_empty() && s.camera.is_none());
    assert_eq!(
        s.report.ignored["emission"],
        vec!["EmissiveMaterial".to_string()]
    );
    assert!(s
        .report
        .warnings
        .iter()
        .any(|w| w.contains("ignored: emission (EmissiveMaterial)")));
    // Suzanne: metallic 1 (the default), roughness 0.386, yellow base colour.
    let monkey = material_named(&s, "MonkeyMaterial");
    let b = monkey.brdf_at(None, &s.textures);
    assert_eq!(b.kd, Vec3::ZERO);
    assert!(matches!(b.fresnel, Fresnel::Schlick(f0) if close(f0, Vec3::new(1.0, 1.0, 0.0))));
    assert!((b.alpha - 0.3856209f32.powi(2)).abs() < 1e-5);
    assert!(monkey.double_sided);
    // The light quad is a grandchild of the floor: its world position adds three translations.
    let light = s
        .meshes
        .iter()
        .find(|m| m.name.starts_with("Cube.001"))
        .unwrap();
    let centre = light.positions.iter().sum::<Vec3>() / light.positions.len() as f32;
    let (lo, hi) = s.bounds().unwrap();
    assert!(centre.x.abs() < 0.05 && centre.z.abs() < 0.05, "{centre}");
    assert!(
        centre.y > lo.y + 0.8 * (hi.y - lo.y),
        "light at {centre}, scene {lo}..{hi}"
    );
    for m in &s.meshes {
        assert!(m
            .normals
            .as_ref()
            .unwrap()
            .iter()
            .all(|n| (n.length() - 1.0).abs() < 1e-4));
    }
}

#[test]
fn mcguire_cornell_box_obj() {
    let s = load_scene(shared!("scenes/cornell-mcguire/CornellBox-Original.obj")).unwrap();
    assert_eq!(s.name, "CornellBox-Original");
    // 18 quads.
    assert_eq!(s.triangle_count() + s.report.skipped.total(), 18 * 2);
    assert_eq!(s.meshes.len(), 8);
    assert!(s.lights.is_empty() && s.camera.is_none() && s.textures.is_empty());
    assert_eq!(s.materials.len(), 8);
    let left = material_named(&s, "leftWall");
    assert!(left.double_sided);
    assert!(!left.has_specular());
    let b = left.brdf_at(None, &s.textures);
    assert!(close(b.kd, Vec3::new(0.63, 0.065, 0.05)));
    assert!((b.alpha - (2.0f32 / 12.0).sqrt()).abs() < 1e-6); // Ns 10
    assert_eq!(s.report.ignored["emission"], vec!["light".to_string()]);
    assert!(
        s.report
            .warnings
            .iter()
            .any(|w| w.contains("ignored: emission (light)")),
        "{:?}",
        s.report.warnings
    );
    assert_eq!(s.report.warnings.len(), 1, "{:?}", s.report.warnings);
    assert!(matches!(
        s.validate_for_render(),
        Err(SceneError::NoLight { .. })
    ));
}

#[test]
fn sponza_with_textures() {
    let start = std::time::Instant::now();
    let s = load_scene(shared!("scenes/sponza/sponza.obj")).unwrap();
    eprintln!(
        "sponza: {:?}, {} triangles kept, skipped {:?}",
        start.elapsed(),
        s.triangle_count(),
        s.report.skipped
    );
    assert_eq!(s.triangle_count() + s.report.skipped.total(), 66_445);
    assert!(s.triangle_count() > 66_000);
    assert_eq!(
        s.report.skipped.index_out_of_range + s.report.skipped.non_finite,
        0
    );
    assert_eq!(s.materials.len(), 19);
    // 17 map_Kd statements name 10 distinct files; each is decoded once.
    assert_eq!(s.textures.len(), 10);
    assert!(s
        .textures
        .iter()
        .all(|t| t.width > 0 && t.texels.len() == (t.width * t.height) as usize));
    assert!(
        s.report.warnings.iter().all(|w| !w.contains("texture")),
        "{:?}",
        s.report.warnings
    );
    let textured = s
        .materials
        .iter()
        .filter(|m| {
            matches!(
                m.model,
                MaterialModel::Direct {
                    kd_texture: Some(_),
                    ..
                }
            )
        })
        .count();
    assert_eq!(textured, 17);
    let floor = material_named(&s, "sp_00_pod");
    let tex_mean = |uv| floor.brdf_at(Some(uv), &s.textures).kd;
    let kd = tex_mean(Vec2::new(0.3, 0.6));
    assert!(kd.min_element() > 0.0 && kd.max_element() < 1.0, "{kd}");
    assert!(s
        .meshes
        .iter()
        .all(|m| m.uvs.is_some() && m.normals.is_some()));
}

#[test]
fn missing_files_are_io_errors_naming_the_path() {
    for spec in [
        "/nonexistent/dir/scene.gltf",
        "/nonexistent/dir/scene.glb",
        "/nonexistent/dir/scene.obj",
    ] {
        match load_scene(spec) {
            Err(e @ SceneError::Io { .. }) => assert!(e.to_string().contains(spec), "{e}"),
            other => panic!("{spec}: {other:?}"),
        }
    }
}

/// Writes `tri.gltf` (one triangle (0,0,0), (1,0,0), (0,1,0) with normals `normal`, under
/// `node`'s transform, with `material`) and `tri.bin` to `dir`; returns the glTF path.
fn write_triangle_gltf(
    dir: &std::path::Path,
    node: &str,
    normal: Vec3,
    material: &str,
    extra: &str,
) -> String {
    let mut bin: Vec<u8> = Vec::new();
    for p in [Vec3::ZERO, Vec3::X, Vec3::Y]
        .into_iter()
        .chain([normal; 3])
    {
        p.to_array()
            .iter()
            .for_each(|c| bin.extend(c.to_le_bytes()));
    }
    [0u16, 1, 2, 0]
        .iter()
        .for_each(|i| bin.extend(i.to_le_bytes()));
    std::fs::write(dir.join("tri.bin"), &bin).unwrap();
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "buffers": [{{"uri": "tri.bin", "byteLength": 80}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 72}}, {{"buffer": 0, "byteOffset": 72, "byteLength": 6}}],
  "accessors": [
    {{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"}},
    {{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}}],
  "meshes": [{{"name": "tri", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 0}}]}}],
  "materials": [{material}],
  "nodes": [{node}],
  "scenes": [{{"nodes": [0]}}], "scene": 0{extra}}}"#
    );
    let path = dir.join("tri.gltf");
    std::fs::write(&path, json).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn gltf_transforms_mirroring_and_missing_texture() {
    let dir = temp_dir("gltf-transform");
    let material = r#"{"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0.01},
        "extensions": {"KHR_materials_ior": {"ior": 1.33}}}"#;
    let extra = r#", "textures": [{"source": 0}], "images": [{"uri": "missing.png"}]"#;
    let n = Vec3::new(1.0, 0.0, 1.0).normalize();
    // Mirrored in x and stretched in y: winding flips, normals by the inverse transpose.
    let path = write_triangle_gltf(
        &dir,
        r#"{"mesh": 0, "scale": [-1, 2, 1]}"#,
        n,
        material,
        extra,
    );
    let s = load_scene(&path).unwrap();
    let m = &s.meshes[0];
    let [a, b, c] = m.triangles[0].map(|i| m.positions[i as usize]);
    assert!(close(b - a, -Vec3::X) || close(c - a, -Vec3::X));
    assert!(
        (b - a).cross(c - a).z > 0.0,
        "mirroring must keep the face's front towards +z"
    );
    assert!(m.positions.contains(&Vec3::new(0.0, 2.0, 0.0)));
    assert!(close(
        m.normals.as_ref().unwrap()[0],
        Vec3::new(-1.0, 0.0, 1.0).normalize()
    ));
    let warnings = s.report.warnings.join("\n");
    assert!(
        warnings.contains("missing.png") && warnings.contains("factor"),
        "{warnings}"
    );
    assert!(warnings.contains("alpha"), "{warnings}");
    assert!(s.textures.is_empty());
    let brdf = s.materials[0].brdf_at(Some(Vec2::splat(0.5)), &s.textures);
    assert!(close(brdf.kd, Vec3::new(0.2, 0.4, 0.6)));
    assert_eq!(brdf.alpha, crate::ALPHA_MIN);
    assert_eq!(s.materials[0].eta, Some(1.33));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gltf_lights_and_camera_from_nodes() {
    let dir = temp_dir("gltf-lights");
    // The root turns its children by -90 degrees about +x: their -z becomes -y, +y becomes -z.
    let nodes = r#"{"children": [1, 2, 3, 4], "rotation": [-0.70710677, 0, 0, 0.70710677], "translation": [0, 1, 0]},
        {"mesh": 0},
        {"translation": [0, 0, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"camera": 0, "extensions": {"KHR_lights_punctual": {"light": 2}}}"#;
    let extra = r#", "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "spot", "color": [1, 0.5, 0], "intensity": 4, "spot": {"outerConeAngle": 0.5}},
            {"type": "directional", "intensity": 2},
            {"type": "point", "intensity": 3, "range": 10}]}}"#;
    let path = write_triangle_gltf(&dir, nodes, Vec3::Z, "{}", extra);
    let s = load_scene(&path).unwrap();
    assert_eq!(s.lights.len(), 3);
    match &s.lights[0] {
        Light::Spot {
            position,
            direction,
            intensity,
            inner_cone_angle: inner,
            outer_cone_angle: outer,
        } => {
            assert!(close(*position, Vec3::Y) && close(*direction, Vec3::NEG_Y));
            assert_eq!(
                (*intensity, *inner, *outer),
                (Vec3::new(4.0, 2.0, 0.0), 0.0, 0.5)
            );
        }
        l => panic!("{l:?}"),
    }
    assert!(
        matches!(s.lights[1], Light::Directional { direction, irradiance } if close(direction, Vec3::NEG_Y) && irradiance == Vec3::splat(2.0))
    );
    assert!(matches!(s.lights[2], Light::Point { intensity, .. } if intensity == Vec3::splat(3.0)));
    assert!(s.report.warnings.iter().any(|w| w.contains("range")));
    let cam = s.camera.as_ref().unwrap();
    assert!(
        close(cam.forward, Vec3::NEG_Y)
            && close(cam.up, Vec3::NEG_Z)
            && close(cam.position, Vec3::Y)
    );
    assert_eq!((cam.yfov, cam.znear), (0.5, 0.1));
    // The triangle is placed by the root too: its vertex (0, 1, 0) goes to (0, 0, -1) + (0, 1, 0),
    // its +z normal to +y.
    let tri = &s.meshes[0];
    assert!(tri
        .positions
        .iter()
        .any(|&p| close(p, Vec3::new(0.0, 1.0, -1.0))));
    assert!(close(tri.normals.as_ref().unwrap()[0], Vec3::Y));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn broken_gltf_files_are_errors_not_panics() {
    let dir = temp_dir("gltf-broken");
    let expect_gltf_error =
        |path: &std::path::Path, needle: &str| match load_scene(path.to_str().unwrap()) {
            Err(e @ SceneError::Gltf { .. }) => {
                let text = e.to_string();
                let names_file = text.contains(path.to_str().unwrap());
                assert!(names_file && text.contains(needle), "{needle}: {text}");
            }
            other => panic!("{}: {other:?}", path.display()),
        };
    let malformed = dir.join("malformed.gltf");
    std::fs::write(
        &malformed,
        r#"{"asset": {"version": "2.0"}, "nodes": [ {"mesh": "#,
    )
    .unwrap();
    expect_gltf_error(&malformed, "");
    let glb = dir.join("garbage.glb");
    std::fs::write(&glb, b"glTF\x02\x00\x00\x00garbage").unwrap();
    expect_gltf_error(&glb, "");
    // A GLB header whose length is below its own size (the gltf crate would underflow).
    std::fs::write(&glb, b"glTF\x02\x00\x00\x00\x04\x00\x00\x00").unwrap();
    expect_gltf_error(&glb, "GLB header");

    let path = PathBuf::from(write_triangle_gltf(
        &dir,
        r#"{"mesh": 0}"#,
        Vec3::Z,
        "{}",
        "",
    ));
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(dir.join("tri.bin")).unwrap();
    expect_gltf_error(&path, "tri.bin");
    // A buffer shorter than its byteLength.
    std::fs::write(dir.join("tri.bin"), [0u8; 8]).unwrap();
    expect_gltf_error(&path, "byteLength");
    write_triangle_gltf(&dir, r#"{"mesh": 0}"#, Vec3::Z, "{}", "");

    let indices = r#""count": 3, "type": "SCALAR""#;
    let edits = [
        // An accessor reaching past its buffer view, or of the wrong type.
        (indices, r#""count": 4000, "type": "SCALAR""#, "do not fit"),
        (indices, r#""count": 3, "type": "VEC2""#, "indices"),
        (indices, r#""count": 0, "type": "SCALAR""#, "no elements"),
        (
            r#""byteOffset": 36, "#,
            r#""byteOffset": 18446744073709551600, "#,
            "do not fit",
        ),
        // Out-of-range indices: one the gltf crate's own validation would panic on.
        (
            r#""POSITION": 0"#,
            r#""POSITION": 9"#,
            "POSITION names no accessor",
        ),
        (r#""NORMAL": 1"#, r#""NORMAL": 9"#, "validation"),
        (r#""nodes": [0]"#, r#""nodes": [7]"#, "validation"),
    ];
    for (from, to, needle) in edits {
        assert!(text.contains(from), "{from}");
        std::fs::write(&path, text.replace(from, to)).unwrap();
        expect_gltf_error(&path, needle);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gltf_odd_but_valid_structure_gives_warnings() {
    let dir = temp_dir("gltf-odd");
    // A node that is its own child and holds a camera whose type names a projection it does
    // not describe; a points primitive; a primitive without material (the glTF default); a
    // texture whose image has no source.
    let node = r#"{"mesh": 0, "children": [0], "camera": 0}"#;
    let material = r#"{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}"#;
    let extra = r#", "textures": [{"source": 0}], "images": [{"name": "nothing"}],
        "cameras": [{"type": "perspective", "orthographic": {"xmag": 1, "ymag": 1, "zfar": 9, "znear": 1}}]"#;
    let path = write_triangle_gltf(&dir, node, Vec3::Z, material, extra);
    let text = std::fs::read_to_string(&path).unwrap().replace(
        r#", "material": 0}]"#,
        r#", "material": 0}, {"attributes": {"POSITION": 0}, "mode": 0}, {"attributes": {"POSITION": 0}}]"#,
    );
    std::fs::write(&path, text).unwrap();
    let s = load_scene(&path).unwrap();
    assert_eq!(s.triangle_count(), 2);
    assert!(s.camera.is_none() && s.textures.is_empty());
    let warnings = s.report.warnings.join("\n");
    for needle in ["twice", "Points", "perspective cameras", "'nothing'"] {
        assert!(warnings.contains(needle), "{needle}: {warnings}");
    }
    assert_eq!(s.materials.len(), 2);
    assert_eq!(
        s.materials[s.meshes[1].material].name,
        "glTF default material"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn obj_defects_are_skipped_and_counted() {
    let dir = temp_dir("obj-defects");
    let obj = dir.join("defects.obj");
    std::fs::write(
        &obj,
        "mtllib nowhere.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv 2 0 0\nv 0 inf 0\n\
         vt 0 0\nvt 1 0\nvt 0 1\nvt 0 0\nvt 0 0\nvt 0 0\n\
         f 1/1 2/2 3/3\nf 1/1 2/2 4/4\nf 1/1 2/2 5/5\nf 1/1 5/5 2/2\nf 1/1 2/2 6/6\n",
    )
    .unwrap();
    // Two of five triangles have non-finite vertices: the file is refused as damaged.
    match load_scene(obj.to_str().unwrap()) {
        Err(e @ SceneError::Invalid { .. }) => {
            let e = e.to_string();
            assert!(
                e.contains("defects.obj") && e.contains("2 of 5 triangles"),
                "{e}"
            )
        }
        other => panic!("{other:?}"),
    }
    // The loader itself removes and counts them.
    let s = crate::obj_loader::load_obj(&obj).unwrap();
    assert_eq!(s.triangle_count(), 1);
    assert_eq!(
        (s.report.skipped.non_finite, s.report.skipped.degenerate),
        (2, 2)
    );
    assert!(
        s.report.warnings.iter().any(|w| w.contains("nowhere.mtl")),
        "{:?}",
        s.report.warnings
    );
    let m = &s.materials[s.meshes[0].material];
    assert!(m.double_sided && !m.has_specular());
    assert!(close(m.brdf_at(None, &s.textures).kd, Vec3::splat(0.5)));
    // v is flipped: OBJ (0, 1) is the top-left of the image, stored as (0, 0).
    assert_eq!(s.meshes[0].uvs.as_ref().unwrap()[2], Vec2::new(0.0, 0.0));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn obj_material_mapping_and_missing_texture() {
    let dir = temp_dir("obj-materials");
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl textured\nKd 0.3 0.4 0.5\nmap_Kd tex/missing.png\n\
         newmtl glossy\nKd 0.1 0.1 0.1\nKs 0.9 1.5 0.5\nNs 98\n\
         newmtl mirror\nKd 0 0 0\nKs 1 1 1\nNs 1e9\n\
         newmtl short\nKd 0.25\nKs\nKe 1 2 # comment\n",
    )
    .unwrap();
    let obj = dir.join("m.obj");
    std::fs::write(
        &obj,
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
         g a\nusemtl textured\nf 1/1 2/2 3/3\ng b\nusemtl glossy\nf 1/1 2/2 3/3\ng c\nusemtl mirror\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let s = load_scene(obj.to_str().unwrap()).unwrap();
    assert_eq!(s.meshes.len(), 3);
    let warnings = s.report.warnings.join("\n");
    assert!(
        warnings.contains("missing.png") && warnings.contains("factor alone"),
        "{warnings}"
    );
    assert!(
        warnings.contains("'mirror'") && warnings.contains("alpha"),
        "{warnings}"
    );
    let textured = material_named(&s, "textured").brdf_at(Some(Vec2::splat(0.5)), &s.textures);
    assert!(close(textured.kd, Vec3::new(0.3, 0.4, 0.5)));
    let glossy = material_named(&s, "glossy").brdf_at(None, &s.textures);
    assert!(matches!(glossy.fresnel, Fresnel::Schlick(f0) if close(f0, Vec3::new(0.9, 1.0, 0.5))));
    assert!((glossy.alpha - (2.0f32 / 100.0).sqrt()).abs() < 1e-6); // Ns 98
    assert_eq!(
        material_named(&s, "mirror")
            .brdf_at(None, &s.textures)
            .alpha,
        crate::ALPHA_MIN
    );
    // Colours with fewer than three values repeat the last one; an empty one is dropped.
    let short = material_named(&s, "short");
    assert!(close(
        short.brdf_at(None, &s.textures).kd,
        Vec3::splat(0.25)
    ));
    assert!(!short.has_specular());
    // Its `Ke 1 2` (padded, not refused) is listed as ignored emission.
    assert_eq!(s.report.ignored["emission"], vec!["short".to_string()]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn malformed_obj_is_an_error_naming_the_file() {
    let dir = temp_dir("obj-malformed");
    let obj = dir.join("bad.obj");
    std::fs::write(&obj, "v 0 0 0\nf 1 2 3\n").unwrap();
    match load_scene(obj.to_str().unwrap()) {
        Err(e @ SceneError::Obj { .. }) => assert!(e.to_string().contains("bad.obj"), "{e}"),
        other => panic!("{other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gltf_ignored_features_are_listed_once() {
    let dir = temp_dir("gltf-ignored");
    let material = r#"{"name": "coat", "alphaMode": "BLEND", "emissiveFactor": [1, 0.5, 0],
        "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}, "KHR_materials_sheen": {}, "KHR_materials_ior": {"ior": 1.5}}}"#;
    let extra = r#", "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_ior", "KHR_materials_variants"]"#;
    let path = write_triangle_gltf(&dir, r#"{"mesh": 0}"#, Vec3::Z, material, extra);
    let s = load_scene(&path).unwrap();
    let coat = vec!["coat".to_string()];
    let expected: Vec<(&str, Vec<String>)> = vec![
        ("KHR_materials_clearcoat", coat.clone()),
        ("KHR_materials_sheen", coat.clone()),
        ("KHR_materials_variants", vec!["the file".to_string()]),
        ("alphaMode BLEND (drawn opaque)", coat.clone()),
        ("emission", coat),
    ];
    let got: Vec<(&str, Vec<String>)> = s
        .report
        .ignored
        .iter()
        .map(|(k, v)| (k.as_str(), v.clone()))
        .collect();
    assert_eq!(got, expected);
    let summaries: Vec<&String> = s
        .report
        .warnings
        .iter()
        .filter(|w| w.contains("not modelled"))
        .collect();
    assert_eq!(summaries.len(), 1, "{:?}", s.report.warnings);
    assert!(
        summaries[0].contains("KHR_materials_clearcoat (coat)"),
        "{}",
        summaries[0]
    );
    assert!(s.materials[0].alpha_mask.is_none());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `scenes/materials/materials.gltf`: a normal-mapped glossy floor without tangents, a
/// double-sided alpha-masked sheet.
#[test]
fn gltf_normal_maps_masks_and_double_sided() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/materials/materials.gltf"
    );
    let s = load_scene(path).unwrap();
    assert!(s.report.ignored.is_empty(), "{:?}", s.report.ignored);
    let floor = material_named(&s, "floor_material");
    let map = floor.normal_map.expect("the floor's normalTexture");
    assert_eq!(map.scale, 1.0);
    assert!(floor.alpha_mask.is_none() && !floor.double_sided);
    let sheet = material_named(&s, "sheet_material");
    let mask = sheet.alpha_mask.expect("the sheet's MASK");
    assert_eq!((mask.cutoff, mask.factor), (0.5, 1.0));
    assert!(sheet.double_sided && sheet.normal_map.is_none());
    // The coverage texture is the alpha channel: holes (0) on a 16-texel grid, 1 between.
    let coverage = &s.textures[mask.texture.unwrap()];
    let at = |u: f32, v: f32| coverage.sample(Vec2::new(u, v)).x;
    assert_eq!(at(8.5 / 64.0, 8.5 / 64.0), 0.0);
    assert_eq!(at(0.5 / 64.0, 0.5 / 64.0), 1.0);
    assert!(sheet.cuts(Some(Vec2::new(8.5 / 64.0, 8.5 / 64.0)), &s.textures));
    assert!(!sheet.cuts(Some(Vec2::new(0.5 / 64.0, 0.5 / 64.0)), &s.textures));
    // MikkTSpace tangents were generated for the floor in glTF's convention: T = dp/du = +x,
    // w = +1 (the bitangent N x T = -z points towards decreasing v, the image's up).
    let floor_mesh = s.meshes.iter().find(|m| m.name == "floor").unwrap();
    let tangents = floor_mesh.tangents.as_ref().expect("generated tangents");
    assert_eq!(tangents.len(), floor_mesh.positions.len());
    for t in tangents {
        assert!(close(t.truncate(), Vec3::X) && t.w == 1.0, "{t}");
    }
    // Meshes without a normal map get none.
    assert!(s
        .meshes
        .iter()
        .filter(|m| s.materials[m.material].normal_map.is_none())
        .all(|m| m.tangents.is_none()));
}

#[test]
fn obj_map_d_is_a_cutout_and_bump_maps_are_listed() {
    let dir = temp_dir("obj-map-d");
    // A grey 2x1 map_d: black (cut) on the left, white (kept) on the right.
    image::GrayImage::from_raw(2, 1, vec![0, 255])
        .unwrap()
        .save(dir.join("mask.png"))
        .unwrap();
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl leaf\nKd 0.2 0.6 0.2\nd 0.8\nmap_d mask.png\nmap_Bump bump.png\n\
         newmtl glass\nKd 1 1 1\nd 0.3\n",
    )
    .unwrap();
    let obj = dir.join("m.obj");
    std::fs::write(
        &obj,
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
         g a\nusemtl leaf\nf 1/1 2/2 3/3\ng b\nusemtl glass\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let s = load_scene(obj.to_str().unwrap()).unwrap();
    let leaf = material_named(&s, "leaf");
    let mask = leaf.alpha_mask.expect("map_d");
    assert_eq!((mask.cutoff, mask.factor), (0.5, 0.8));
    assert!(leaf.cuts(Some(Vec2::new(0.25, 0.5)), &s.textures));
    assert!(!leaf.cuts(Some(Vec2::new(0.75, 0.5)), &s.textures));
    // d alone is transparency, not a cut-out: drawn opaque, listed.
    assert!(material_named(&s, "glass").alpha_mask.is_none());
    assert_eq!(
        s.report.ignored["transparency d < 1 (drawn opaque)"],
        vec!["glass".to_string()]
    );
    assert_eq!(
        s.report.ignored["bump map (map_Bump)"],
        vec!["leaf".to_string()]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gltf_anisotropy_is_read() {
    let dir = temp_dir("gltf-anisotropy");
    let read = |ext: &str| {
        let material = format!(
            r#"{{"name": "brushed", "extensions": {{"KHR_materials_anisotropy": {ext}}}}}"#
        );
        let extra = r#", "extensionsUsed": ["KHR_materials_anisotropy"], "extensionsRequired": ["KHR_materials_anisotropy"]"#;
        let path = write_triangle_gltf(&dir, r#"{"mesh": 0}"#, Vec3::Z, &material, extra);
        load_scene(&path).unwrap()
    };
    let s = read(r#"{"anisotropyStrength": 0.6, "anisotropyRotation": 0.5}"#);
    assert_eq!(
        s.materials[0].anisotropy,
        Some(MaterialAnisotropy {
            strength: 0.6,
            rotation: 0.5
        })
    );
    assert!(s.report.ignored.is_empty(), "{:?}", s.report.ignored);
    // Without texture coordinates no tangents can be generated: said, and drawn isotropic.
    let warnings = s.report.warnings.join("\n");
    assert!(warnings.contains("anisotropy is not applied"), "{warnings}");
    assert!(s.meshes[0].tangents.is_none());
    // Defaults (strength 0: isotropic), a clamped strength, the texture listed as ignored.
    assert_eq!(read("{}").materials[0].anisotropy, None);
    let s = read(r#"{"anisotropyStrength": 2, "anisotropyTexture": {"index": 0}}"#);
    assert_eq!(
        s.materials[0].anisotropy,
        Some(MaterialAnisotropy {
            strength: 1.0,
            rotation: 0.0
        })
    );
    assert!(s
        .report
        .warnings
        .join("\n")
        .contains("anisotropyStrength 2"));
    assert!(s
        .report
        .ignored
        .contains_key("KHR_materials_anisotropy anisotropyTexture"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The issue's file: a small glTF that places one 20,000-triangle mesh 20,000 times (4e8
/// triangles, about 150 GiB of meshes and BVH) is refused before any buffer is read, not by
/// an allocation that aborts the process. (Its POSITION has no buffer view: the file is 2 MB
/// of nodes.)
#[test]
fn instances_beyond_memory_are_refused_before_reading() {
    let need = crate::frame::memory::geometry_bytes(20_000 * 60_000, 20_000 * 20_000);
    if crate::frame::memory::available_memory().is_none_or(|a| a >= need) {
        eprintln!("notice: this machine has room for 4e8 triangles; the case is not checked");
        return;
    }
    let nodes: Vec<String> = (0..20_000).map(|_| r#"{"mesh":0}"#.to_string()).collect();
    let roots: Vec<String> = (0..20_000).map(|i| i.to_string()).collect();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[{}]}}],"nodes":[{}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "accessors":[{{"componentType":5126,"type":"VEC3","count":60000,"min":[0,0,0],"max":[1,1,1]}}]}}"#,
        roots.join(","),
        nodes.join(",")
    );
    let dir = temp_dir("instances");
    let path = dir.join("instances.gltf");
    std::fs::write(&path, json).unwrap();
    let e = load_scene(&path).unwrap_err().to_string();
    assert!(
        e.contains("20000 mesh placement(s) make 400000000 triangles") && e.contains("more than"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
