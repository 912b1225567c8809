//! Tests of scene settings files: the shipped files, overrides, lights and bad input.
use super::*;
use crate::builtin::builtin;
use crate::load::load_scene;

/// The settings files shipped in the repository's `scenes/` folder.
fn shipped() -> Vec<PathBuf> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| extension(p).as_deref() == Some("toml"))
        .collect();
    files.sort();
    files
}

/// The nearest surface along a ray: distance, face normal and material (a loop over all
/// triangles, Möller-Trumbore).
fn first_hit(scene: &Scene, origin: Vec3, dir: Vec3) -> Option<(f32, Vec3, &Material)> {
    let mut best: Option<(f32, Vec3, &Material)> = None;
    for m in &scene.meshes {
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let (e1, e2) = (b - a, c - a);
            let p = dir.cross(e2);
            let det = e1.dot(p);
            if det.abs() < 1e-12 {
                continue;
            }
            let s = origin - a;
            let u = s.dot(p) / det;
            let q = s.cross(e1);
            let v = dir.dot(q) / det;
            let d = e2.dot(q) / det;
            if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && d > 1e-4 && best.is_none_or(|h| d < h.0) {
                best = Some((d, e1.cross(e2).normalize(), &scene.materials[m.material]));
            }
        }
    }
    best
}

/// Whether `p` (normal `n`, seen from `eye`) gets light from some light, shadows included.
fn directly_lit(scene: &Scene, p: Vec3, n: Vec3, eye: Vec3) -> bool {
    let n = if n.dot(eye - p) < 0.0 { -n } else { n };
    scene.lights.iter().any(|l| {
        l.incident(p).is_some_and(|inc| {
            n.dot(inc.omega_i) > 0.0
                && first_hit(scene, p + 1e-3 * n, inc.omega_i)
                    .is_none_or(|h| h.0 > inc.distance - 2e-3)
        })
    })
}

#[test]
fn shipped_settings_load_and_light_what_their_camera_sees() {
    let files = shipped();
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    for expected in [
        "sponza",
        "cornell-mcguire-original",
        "cornell-mcguire-glossy",
        "cornell-mcguire-sphere",
        "cornell-mcguire-mirror",
        "cornell-gltf",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "{expected} in {names:?}"
        );
    }
    for (path, name) in files.iter().zip(&names) {
        let start = std::time::Instant::now();
        let scene = load_scene(path.to_str().unwrap()).unwrap();
        scene.validate_for_render().unwrap();
        assert_eq!(&scene.name, name);
        assert!(scene.lights.iter().all(Light::is_valid));
        let cam = scene.camera.clone().unwrap();
        let (lo, hi) = scene.bounds().unwrap();
        let margin = 2.0 * (hi - lo);
        assert!(
            cam.position.cmpge(lo - margin).all() && cam.position.cmple(hi + margin).all(),
            "{name}: camera {} far from bounds {lo}..{hi}",
            cam.position
        );
        let centre = first_hit(&scene, cam.position, cam.forward);
        assert!(centre.is_some(), "{name}: the centre ray hits nothing");
        // A 12 x 12 grid of primary rays (the renderer's default image is square): how
        // many see geometry, and directly lit geometry.
        let (mut seen, mut lit) = (0, 0);
        for j in 0..12 {
            for i in 0..12 {
                let dir = cam.ray_direction(i, j, 0.5, 0.5, 12, 12);
                if let Some((d, n, _)) = first_hit(&scene, cam.position, dir) {
                    seen += 1;
                    lit += directly_lit(&scene, cam.position + d * dir, n, cam.position) as u32;
                }
            }
        }
        eprintln!(
            "{name}: {} triangles, {seen}/144 rays hit, {lit} directly lit, centre at {:.2} ({}), {:?}",
            scene.triangle_count(),
            centre.unwrap().0,
            centre.unwrap().2.name,
            start.elapsed()
        );
        assert!(seen >= 72, "{name}: {seen}/144 primary rays hit geometry");
        assert!(lit >= 10, "{name}: {lit}/144 primary rays see lit geometry");
    }
}

#[test]
fn sponza_placements() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/sponza.toml");
    let scene = load_scene(path).unwrap();
    let floor = scene
        .materials
        .iter()
        .find(|m| m.name == "sp_00_pod")
        .unwrap();
    match &floor.model {
        MaterialModel::Direct {
            f0,
            alpha,
            kd_texture,
            ..
        } => {
            assert_eq!((*f0, *alpha), (Vec3::splat(0.04), 0.1));
            assert!(kd_texture.is_some());
        }
        other => panic!("{other:?}"),
    }
    // The camera stands in the courtyard: open sky above, the floor 1.6 below it.
    let cam = scene.camera.as_ref().unwrap();
    let (lo, hi) = scene.bounds().unwrap();
    assert!(cam.position.cmpgt(lo).all() && cam.position.cmplt(hi).all());
    assert!(first_hit(&scene, cam.position, Vec3::Y).is_none());
    let (down, _, m) = first_hit(&scene, cam.position, Vec3::NEG_Y).unwrap();
    assert_eq!(
        (m.name.as_str(), (down * 100.0).round()),
        ("sp_00_pod", 161.0)
    );
    // The spot is above the roof, and every ray of its outer cone passes the opening
    // (first hit below the roof's top at y 15.65); its axis lands on the courtyard floor.
    let Light::Spot {
        position,
        direction,
        outer_cone_angle,
        ..
    } = scene.lights[0]
    else {
        panic!("{:?}", scene.lights)
    };
    assert!(position.y > hi.y);
    let (d, _, m) = first_hit(&scene, position, direction).unwrap();
    let spot = position + d * direction;
    assert_eq!(m.name, "sp_00_pod");
    assert!((spot.y - 0.093).abs() < 1e-3 && spot.x.abs() < 10.8 && spot.z.abs() < 2.4);
    let (b1, b2) = direction.any_orthonormal_pair();
    for k in 0..32 {
        let phi = k as f32 / 32.0 * std::f32::consts::TAU;
        let (s, c) = outer_cone_angle.sin_cos();
        let dir = c * direction + s * (phi.cos() * b1 + phi.sin() * b2);
        let (d, _, _) = first_hit(&scene, position, dir).unwrap();
        assert!(
            (position + d * dir).y < 15.0,
            "cone ray {k} stops on the roof"
        );
    }
}

#[test]
fn cornell_lights_sit_just_under_their_lamp() {
    for (file, lamp) in [
        ("cornell-mcguire-original", "light"),
        ("cornell-mcguire-mirror", "light"),
        ("cornell-mcguire-glossy", "default grey"),
        ("cornell-mcguire-sphere", "light"),
        ("cornell-gltf", "EmissiveMaterial"),
    ] {
        let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes"))
            .join(format!("{file}.toml"));
        let scene = load_scene(path.to_str().unwrap()).unwrap();
        let Light::Point { position, .. } = scene.lights[0] else {
            panic!("{file}: {:?}", scene.lights)
        };
        let (d, _, m) = first_hit(&scene, position, Vec3::Y).unwrap();
        assert_eq!(m.name, lamp, "{file}");
        assert!(d > 0.04 && d < 0.06, "{file}: {d} below the lamp");
    }
}

/// The settings error for `text`, checked to name the settings file.
fn parse_error(text: &str) -> String {
    let path = Path::new("/settings/bad.toml");
    match Settings::parse(text, path) {
        Err(e @ SceneError::Settings { .. }) => {
            let message = e.to_string();
            assert!(message.starts_with("/settings/bad.toml: "), "{message}");
            message
        }
        other => panic!("{text}: {other:?}"),
    }
}

#[test]
fn invalid_settings_are_errors_naming_the_file() {
    let spot = |keys: &str| {
        format!("scene = \"a.obj\"\n[[lights]]\ntype = \"spot\"\nposition = [0, 5, 0]\nintensity = 1\n{keys}\n")
    };
    let camera = |keys: &str| format!("scene = \"a.obj\"\n[camera]\n{keys}\n");
    let material = |keys: &str| format!("scene = \"a.obj\"\n[[materials]]\n{keys}\n");
    let cases = [
        ("scene = \"a.obj\"\nlight = 1\n".to_string(), "unknown field `light`"),
        ("scene = \"a.obj\"\nscene = \"b.obj\"\n".into(), "duplicate key"),
        ("scene = \n".into(), "line 1"),
        ("replace_lights = false\n".into(), "missing field `scene`"),
        ("scene = \"a.fbx\"\n".into(), "'a.fbx' is not a .gltf, .glb or .obj file"),
        ("scene = \"other.toml\"\n".into(), "not a .gltf, .glb or .obj file"),
        ("scene = \"a.obj\"\nreplace_lights = true\n".into(), "without light"),
        (camera("position = [0, 0, 0]\ntarget = [0, 0, -1]\nfov = 40"), "unknown field `fov`"),
        (camera("position = [0, 0, 0]\ntarget = [0, 0, -1]\nyfov_deg = 0"), "yfov_deg 0 is outside (0, 180)"),
        (camera("position = [0, 0, 0]\ntarget = [0, 0, -1]\nyfov_deg = 180"), "yfov_deg 180"),
        (camera("position = [0, 0, 0]\ntarget = [0, 0, 0]\nyfov_deg = 40"), "[camera]: target equals position"),
        (camera("position = [0, 0, 0]\ntarget = [0, 1, 0]\nyfov_deg = 40"), "up is parallel"),
        (camera("position = [0, 0, 0]\ntarget = [0, 0, -1]\nyfov_deg = 40\nznear = 0"), "znear 0"),
        (camera("position = [0, 0, 0]\ntarget = [0, 0, -1]\nyfov_deg = 40\nznear = 2\nzfar = 1"), "znear 2 and zfar 1"),
        (camera("position = [0, nan, 0]\ntarget = [0, 0, -1]\nyfov_deg = 40"), "position [0, NaN, 0] is not finite"),
        (spot("direction = [0, -1, 0]\nintensty = 2"), "unknown field `intensty`"),
        (spot("direction = [0, -1, 0]\nouter_cone_deg = 120"), "[[lights]] #1: outer_cone_deg 120 is outside (0, 90]"),
        (spot("direction = [0, -1, 0]\nouter_cone_deg = 0"), "outer_cone_deg 0"),
        (spot("direction = [0, -1, 0]\ninner_cone_deg = 30\nouter_cone_deg = 20"), "inner_cone_deg 30 is outside [0, outer_cone_deg = 20]"),
        (spot("direction = [0, -1, 0]\ninner_cone_deg = -1"), "inner_cone_deg -1"),
        (spot("direction = [0, -1, 0]\ntarget = [0, 0, 0]"), "exactly one of direction and target"),
        (spot(""), "exactly one of direction and target"),
        (spot("direction = [0, 0, 0]"), "direction is the zero vector"),
        (spot("target = [0, 5, 0]"), "target equals position"),
        ("scene = \"a.obj\"\n[[lights]]\ntype = \"area\"\n".into(), "unknown variant `area`"),
        ("scene = \"a.obj\"\n[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = -1\n".into(), "intensity [-1, -1, -1] must be finite and at least 0"),
        ("scene = \"a.obj\"\n[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = inf\n".into(), "must be finite"),
        ("scene = \"a.obj\"\n[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = [1, 2]\n".into(), "a number or an array of three numbers"),
        ("scene = \"a.obj\"\n[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\n".into(), "missing field `intensity`"),
        ("scene = \"a.obj\"\n[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = 1\n[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 0]\nirradiance = 1\n".into(), "[[lights]] #2: direction is the zero vector"),
        (material("name = \"floor\"\nroughnes = 0.5"), "unknown field `roughnes`"),
        (material("name = \"floor\""), "'floor' sets nothing"),
        (material("name = \"\"\nalpha = 0.5"), "name is empty"),
        (material("name = \"floor\"\nalpha = 0"), "'floor': alpha 0 is outside (0, 1]"),
        (material("name = \"floor\"\nalpha = 1.5"), "alpha 1.5 is outside (0, 1]"),
        (material("name = \"floor\"\nroughness = -0.1"), "roughness -0.1"),
        (material("name = \"floor\"\nalpha = 0.1\nroughness = 0.3"), "not both"),
        (material("name = \"floor\"\nkd = 1.5"), "kd [1.5, 1.5, 1.5] is outside [0, 1]"),
        (material("name = \"floor\"\nf0 = [0.1, -0.1, 0.1]"), "f0 [0.1, -0.1, 0.1]"),
        (material("name = \"floor\"\neta = 0"), "eta 0 must be above 0 and at most 1e4"),
        // The issue's case: 1e20 passed, then the direct pass failed blaming the light.
        (material("name = \"floor\"\neta = 1e20"), "eta 100000000000000000000 must be above 0 and at most 1e4"),
        (material("name = \"floor\"\neta = inf"), "eta inf must be"),
        (material("name = \"floor\"\ndouble_sided = 1"), "invalid type"),
    ];
    for (text, expected) in cases {
        let message = parse_error(&text);
        assert!(message.contains(expected), "{text}\n-> {message}");
    }
}

#[test]
fn overrides_lights_and_camera_apply() {
    let text = r#"
        scene = "room.glb"
        [camera]
        position = [0, 1, 3]
        target = [0, 1, 0]
        yfov_deg = 50
        [[lights]]
        type = "spot"
        position = [0, 1.9, 0]
        direction = [0, -1, 0]
        intensity = [1, 2, 3]
        outer_cone_deg = 90
        [[materials]]
        name = "white"
        kd = 0.5
        alpha = 0.3
        [[materials]]
        name = "*ee*"
        roughness = 0.5
        double_sided = true
        [[materials]]
        name = "c*"
        alpha = 1e-4
        eta = 1.5
    "#;
    let settings = Settings::parse(text, Path::new("/x/glossy room.toml")).unwrap();
    assert_eq!(settings.scene, Path::new("/x/room.glb"));
    assert!(settings.replace_lights);
    let mut scene = builtin("default").unwrap();
    settings.apply(&mut scene).unwrap();
    assert_eq!(scene.name, "glossy room");
    assert_eq!(scene.camera.as_ref().unwrap().yfov, 50f32.to_radians());
    assert_eq!(scene.lights.len(), 1);
    assert!(
        scene.lights[0].is_valid(),
        "a 90 degree cone is a valid spot"
    );
    assert!(scene.validate_for_render().is_ok());
    let brdf = |name: &str| {
        let m = scene.materials.iter().find(|m| m.name == name).unwrap();
        (m.brdf_at(None, &[]), m.eta, m.double_sided)
    };
    let (white, _, _) = brdf("white");
    assert_eq!((white.kd, white.alpha), (Vec3::splat(0.5), 0.3));
    let (green, _, green_two_sided) = brdf("green");
    assert_eq!(
        (green.kd, green.alpha, green_two_sided),
        (Vec3::new(0.1, 0.7, 0.1), 0.25, true)
    );
    let (copper, eta, _) = brdf("copper");
    assert_eq!((copper.alpha, eta), (ALPHA_MIN, Some(1.5)));
    assert!(scene.report.warnings.iter().any(|w| w.contains("'copper'")));
    let (red, _, red_two_sided) = brdf("red");
    assert_eq!((red.alpha, red_two_sided), (1.0, false));
}

#[test]
fn lights_are_replaced_added_or_kept() {
    let point = "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = 2\n";
    let count = |text: &str| {
        let mut scene = builtin("default").unwrap();
        let settings = Settings::parse(text, Path::new("s.toml")).unwrap();
        settings.apply(&mut scene).unwrap();
        scene.lights.len()
    };
    let own = builtin("default").unwrap().lights.len();
    assert_eq!(count("scene = \"a.obj\"\n"), own);
    assert_eq!(count(&format!("scene = \"a.obj\"\n{point}{point}")), 2);
    let added = format!("scene = \"a.obj\"\nreplace_lights = false\n{point}");
    assert_eq!(count(&added), own + 1);
    assert_eq!(count("scene = \"a.obj\"\nreplace_lights = false\n"), own);
}

#[test]
fn an_override_matching_nothing_fails_without_changing_the_scene() {
    let text = "scene = \"room.obj\"\n[[materials]]\nname = \"white\"\nalpha = 0.2\n[[materials]]\nname = \"marble*\"\nalpha = 0.2\n";
    let settings = Settings::parse(text, Path::new("/s/marble.toml")).unwrap();
    let mut scene = builtin("default").unwrap();
    let e = settings.apply(&mut scene).unwrap_err();
    let message = e.to_string();
    assert!(matches!(e, SceneError::Settings { .. }));
    assert!(message.starts_with("/s/marble.toml: "), "{message}");
    assert!(message.contains("[[materials]] #2: 'marble*' matches no material of /s/room.obj (its materials: white, red, green, copper, blue)"), "{message}");
    assert_eq!(scene, builtin("default").unwrap());
}

#[test]
fn metallic_roughness_materials_are_overridden() {
    let metal = || Material {
        name: "head".into(),
        model: MaterialModel::MetallicRoughness {
            base_color: Vec3::new(1.0, 0.8, 0.0),
            base_color_texture: Some(0),
            metallic: 1.0,
            roughness: 0.5,
            metallic_roughness_texture: None,
        },
        eta: None,
        double_sided: true,
        normal_map: None,
        alpha_mask: None,
        anisotropy: None,
    };
    let o = |alpha, f0| MaterialOverride {
        pattern: "head".into(),
        kd: None,
        f0,
        alpha,
        eta: None,
        double_sided: None,
        anisotropy: None,
    };
    // alpha alone keeps the model and sets roughness = sqrt(alpha).
    let mut m = metal();
    assert!(o(Some(0.04), None).apply_to(&mut m).is_empty());
    assert!(
        matches!(m.model, MaterialModel::MetallicRoughness { roughness, .. } if (roughness - 0.2).abs() < 1e-6)
    );
    // f0 turns it into kd, F0, alpha from its factors, then sets F0.
    let mut m = metal();
    assert!(o(None, Some(Vec3::splat(0.5))).apply_to(&mut m).is_empty());
    assert_eq!(
        m.model,
        MaterialModel::Direct {
            kd: Vec3::ZERO,
            kd_texture: Some(0),
            f0: Vec3::splat(0.5),
            alpha: 0.25
        }
    );
    // Without f0, the base-colour texture of a metal no longer tints F0: a warning says so.
    let mut m = metal();
    let kd = MaterialOverride {
        kd: Some(Vec3::ONE),
        ..o(None, None)
    };
    assert_eq!(kd.apply_to(&mut m).len(), 1);
}

/// An anisotropy override sets the material's (strength 0 removes it), is validated, and the
/// meshes that lack tangents for it get generated ones.
#[test]
fn anisotropy_overrides() {
    let text = |body: &str| format!("scene = \"x.obj\"\n[[materials]]\nname = \"floor\"\n{body}\n");
    let read = |body: &str| Settings::parse(&text(body), Path::new("s.toml"));
    let ok = read("anisotropy_strength = 0.8\nanisotropy_rotation = 0.5").unwrap();
    assert_eq!(
        ok.materials[0].anisotropy,
        Some(MaterialAnisotropy {
            strength: 0.8,
            rotation: 0.5
        })
    );
    for (body, error) in [
        ("anisotropy_strength = 1.5", "anisotropy_strength 1.5"),
        ("anisotropy_rotation = 0.5", "needs anisotropy_strength"),
        ("anisotropy_strength = -0.1", "anisotropy_strength -0.1"),
    ] {
        let e = read(body).unwrap_err().to_string();
        assert!(e.contains(error), "{body}: {e}");
    }
    // On a scene: the quad has texture coordinates but no tangents.
    let mut scene = crate::builtin("default").unwrap();
    let name = scene.materials[0].name.clone();
    let meshes: Vec<usize> = (0..scene.meshes.len())
        .filter(|&i| scene.meshes[i].material == 0)
        .collect();
    assert!(!meshes.is_empty());
    let o = MaterialOverride::new(&name, None, None, None, None, None, None, (Some(0.5), None))
        .unwrap();
    scene.override_materials(std::slice::from_ref(&o)).unwrap();
    assert_eq!(
        scene.materials[0].anisotropy,
        Some(MaterialAnisotropy {
            strength: 0.5,
            rotation: 0.0
        })
    );
    for i in meshes {
        let m = &scene.meshes[i];
        assert!(
            m.tangents.is_some() || m.uvs.is_none(),
            "mesh {} has texture coordinates but no tangents",
            m.name
        );
        if m.uvs.is_none() {
            assert!(scene
                .report
                .warnings
                .iter()
                .any(|w| w.contains("anisotropy is not applied")));
        }
    }
    let off = MaterialOverride::new(&name, None, None, None, None, None, None, (Some(0.0), None))
        .unwrap();
    scene
        .override_materials(std::slice::from_ref(&off))
        .unwrap();
    assert_eq!(scene.materials[0].anisotropy, None);
}

#[test]
fn files_that_are_missing_or_broken_are_errors_naming_them() {
    let dir = std::env::temp_dir().join(format!("slc-core-settings-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let missing_settings = dir.join("absent.toml");
    assert!(matches!(
        load_scene(missing_settings.to_str().unwrap()),
        Err(SceneError::Io { path, .. }) if path == missing_settings
    ));
    for (file, text, expected) in [
        (
            "missing.toml",
            "scene = \"nowhere/room.obj\"\n",
            "nowhere/room.obj not found",
        ),
        (
            "described.toml",
            "scene = \"nowhere/room.obj\"\nscene_source = \"the room of X (CC BY); get it at Y\"\n",
            "nowhere/room.obj not found: the room of X (CC BY); get it at Y",
        ),
        (
            "broken.toml",
            "scene = \"room.obj\"\n[camera\n",
            "TOML parse error",
        ),
    ] {
        let path = dir.join(file);
        std::fs::write(&path, text).unwrap();
        match load_scene(path.to_str().unwrap()) {
            Err(e @ SceneError::Settings { .. }) => {
                let message = e.to_string();
                assert!(
                    message.starts_with(&format!("{}: ", path.display())),
                    "{message}"
                );
                assert!(message.contains(expected), "{message}");
            }
            other => panic!("{file}: {other:?}"),
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every file a scene was read from is listed once, in the order read: the settings file,
/// the OBJ, its material library and the textures it names.
#[test]
fn a_scene_lists_every_file_it_was_read_from() {
    let settings = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/sponza.toml"
    ));
    let scene = load_scene(settings.to_str().unwrap()).unwrap();
    let files = &scene.report.files;
    assert_eq!(files[0], settings);
    assert!(files[1].ends_with("sponza/sponza.obj") && files[2].ends_with("sponza/sponza.mtl"));
    let textures = &files[3..];
    assert!(
        textures.len() >= 10
            && textures
                .iter()
                .all(|f| f.extension().is_some_and(|e| e.eq_ignore_ascii_case("jpg"))),
        "{files:?}"
    );
    let mut unique = files.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), files.len());
    assert!(builtin("default").unwrap().report.files.is_empty());
}

#[test]
fn globs() {
    for (pattern, name, matches) in [
        ("sp_00_pod", "sp_00_pod", true),
        ("sp_00_po", "sp_00_pod", false),
        ("sp_00_pod", "sp_00_po", false),
        ("sp_*", "sp_00_pod", true),
        ("*pod", "sp_00_pod", true),
        ("*_00_*", "sp_00_pod", true),
        ("sp*pod*", "sp_00_pod", true),
        ("*", "", true),
        ("", "", true),
        ("a*a", "a", false),
        ("a*b*c", "abc", true),
        ("a*b*c", "acb", false),
        ("**", "x", true),
    ] {
        assert_eq!(glob_match(pattern, name), matches, "{pattern} {name}");
    }
}
