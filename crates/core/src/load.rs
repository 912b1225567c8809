//! One entry point for every scene source: built-in names, scene files and scene settings.
use crate::builtin::{builtin, BUILTIN_NAMES};
use crate::error::SceneError;
use crate::file_read::recording;
use crate::gltf_loader::load_gltf;
use crate::obj_loader::load_obj;
use crate::scene::Scene;
use crate::settings::load_settings;
use std::ffi::OsStr;
use std::path::Path;

/// Loads a scene: a built-in name (see [`BUILTIN_NAMES`]) or a file path chosen by its
/// extension, case-insensitive: `.gltf` / `.glb` (glTF 2.0), `.obj` (OBJ + MTL) or `.toml`
/// (scene settings naming one of those files, see [`crate::settings`]). The scene is named by
/// the built-in name or the file's stem (for settings: the settings file's stem).
///
/// Errors: an unknown extension is [`SceneError::UnsupportedFormat`]; a spec without
/// extension that is neither a built-in name nor a file is [`SceneError::UnknownBuiltin`];
/// loader errors name the file; settings errors are [`SceneError::Settings`].
///
/// `spec` may be any path the OS takes, UTF-8 or not.
pub fn load_scene(spec: impl AsRef<OsStr>) -> Result<Scene, SceneError> {
    let spec = spec.as_ref();
    if let Some(scene) = spec.to_str().and_then(builtin) {
        return Ok(scene);
    }
    let path = Path::new(spec);
    if path.is_dir() {
        return Err(SceneError::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "a folder, not a scene file (give a .gltf, .glb, .obj or .toml file in it)",
            ),
        });
    }
    match extension(path).as_deref() {
        Some("toml") => load_settings(path),
        None if !path.is_file() => Err(SceneError::UnknownBuiltin {
            name: spec.to_string_lossy().into_owned(),
            available: BUILTIN_NAMES.join(", "),
        }),
        _ => load_scene_file(path),
    }
}

/// Loads a scene file chosen by its extension, case-insensitive: `.gltf` / `.glb` or `.obj`.
/// Neither built-in names nor settings files: this is what a settings file may name.
///
/// Defective triangles (non-finite vertices, indices past the end, zero area) are removed
/// with one warning giving their counts; a file that loses more than
/// [`MAX_DROPPED_SHARE`] of its triangles to non-finite vertices or bad indices is refused
/// ([`SceneError::Invalid`]): what is left would be a different scene.
pub fn load_scene_file(path: &Path) -> Result<Scene, SceneError> {
    let (loaded, files) = recording(|| match extension(path).as_deref() {
        Some("gltf" | "glb") => load_gltf(path),
        Some("obj") => load_obj(path),
        _ => Err(SceneError::UnsupportedFormat {
            path: path.to_path_buf(),
        }),
    });
    let mut scene = loaded?;
    scene.source = Some(path.to_path_buf());
    scene.report.files = files;
    scene.report.summarize_ignored();
    check_dropped(&mut scene)?;
    Ok(scene)
}

/// The largest share of a file's triangles that may be lost to non-finite vertices or
/// out-of-range indices: 10%. Zero-area triangles do not count (they cover no pixel).
pub const MAX_DROPPED_SHARE: f64 = 0.1;

/// Warns about the triangles the loader removed; refuses a scene that lost too many.
fn check_dropped(scene: &mut Scene) -> Result<(), SceneError> {
    let d = scene.report.skipped;
    if d.total() == 0 {
        return Ok(());
    }
    let all = scene.triangle_count() + d.total();
    scene.report.warnings.push(format!(
        "{} of {all} triangles removed: {} with a non-finite vertex, {} with a coordinate beyond ±{:e}, {} with an index past the end, {} of zero area",
        d.total(),
        d.non_finite,
        d.out_of_range,
        crate::mesh::MAX_COORDINATE,
        d.index_out_of_range,
        d.degenerate
    ));
    let broken = d.non_finite + d.out_of_range + d.index_out_of_range;
    if broken as f64 > MAX_DROPPED_SHARE * all as f64 {
        return Err(SceneError::Invalid {
            scene: scene.label(),
            message: format!(
                "{broken} of {all} triangles have non-finite vertices, coordinates beyond ±{:e} or indices past the end (more than {}%): the file is damaged",
                crate::mesh::MAX_COORDINATE,
                MAX_DROPPED_SHARE * 100.0
            ),
        });
    }
    Ok(())
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
