//! One entry point for every scene source: built-in names, scene files and scene settings.
use crate::builtin::{builtin, BUILTIN_NAMES};
use crate::error::SceneError;
use crate::gltf_loader::load_gltf;
use crate::obj_loader::load_obj;
use crate::scene::Scene;
use crate::settings::load_settings;
use std::path::Path;

/// Loads a scene: a built-in name (see [`BUILTIN_NAMES`]) or a file path chosen by its
/// extension, case-insensitive: `.gltf` / `.glb` (glTF 2.0), `.obj` (OBJ + MTL) or `.toml`
/// (scene settings naming one of those files, see [`crate::settings`]). The scene is named by
/// the built-in name or the file's stem (for settings: the settings file's stem).
///
/// Errors: an unknown extension is [`SceneError::UnsupportedFormat`]; a spec without
/// extension that is neither a built-in name nor a file is [`SceneError::UnknownBuiltin`];
/// loader errors name the file; settings errors are [`SceneError::Settings`].
pub fn load_scene(spec: &str) -> Result<Scene, SceneError> {
    if let Some(scene) = builtin(spec) {
        return Ok(scene);
    }
    let path = Path::new(spec);
    match extension(path).as_deref() {
        Some("toml") => load_settings(path),
        None if !path.is_file() => Err(SceneError::UnknownBuiltin {
            name: spec.to_string(),
            available: BUILTIN_NAMES.join(", "),
        }),
        _ => load_scene_file(path),
    }
}

/// Loads a scene file chosen by its extension, case-insensitive: `.gltf` / `.glb` or `.obj`.
/// Neither built-in names nor settings files: this is what a settings file may name.
pub fn load_scene_file(path: &Path) -> Result<Scene, SceneError> {
    match extension(path).as_deref() {
        Some("gltf" | "glb") => load_gltf(path),
        Some("obj") => load_obj(path),
        _ => Err(SceneError::UnsupportedFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// The file extension in lower case.
pub(crate) fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_names() {
        for name in BUILTIN_NAMES {
            assert!(!load_scene(name).unwrap().meshes.is_empty());
        }
        match load_scene("cornell-glosy") {
            Err(e @ SceneError::UnknownBuiltin { .. }) => {
                assert!(e.to_string().contains("default, cornell-glossy"))
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn unsupported_extensions() {
        for spec in ["scene.fbx", "/nonexistent/scene.ply", "archive.tar.gz"] {
            assert!(
                matches!(load_scene(spec), Err(SceneError::UnsupportedFormat { .. })),
                "{spec}"
            );
        }
        // An existing file without extension is not a built-in name either.
        let dir = std::env::temp_dir().join(format!("slc-core-load-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("no_extension");
        std::fs::write(&file, "x").unwrap();
        assert!(matches!(
            load_scene(file.to_str().unwrap()),
            Err(SceneError::UnsupportedFormat { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn extensions_are_case_insensitive() {
        for spec in [
            "/nonexistent/a.GLTF",
            "/nonexistent/a.Glb",
            "/nonexistent/a.OBJ",
            "/nonexistent/a.TOML",
        ] {
            assert!(
                matches!(load_scene(spec), Err(SceneError::Io { .. })),
                "{spec}"
            );
        }
    }
}
