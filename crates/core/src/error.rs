//! Errors of scene loading and validation.
use std::path::PathBuf;

/// Everything that can go wrong while loading or checking a scene. Every variant names the
/// file (or built-in scene) it concerns and what is wrong with it.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{path}: cannot read file: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: not a valid glTF 2.0 file: {message}")]
    Gltf { path: PathBuf, message: String },
    #[error("{path}: not a valid OBJ/MTL file: {message}")]
    Obj { path: PathBuf, message: String },
    #[error(
        "{path}: unsupported scene format (expected .gltf, .glb, .obj or .toml scene settings)"
    )]
    UnsupportedFormat { path: PathBuf },
    #[error("unknown built-in scene '{name}' (built-in scenes: {available})")]
    UnknownBuiltin { name: String, available: String },
    #[error("{scene}: the scene has no light (add a point, spot or directional light)")]
    NoLight { scene: String },
    #[error("{scene}: the scene has no triangles")]
    NoGeometry { scene: String },
    #[error("{scene}: {message}")]
    Invalid { scene: String, message: String },
    /// A scene settings file (`.toml`) that is malformed or asks for something invalid.
    #[error("{path}: invalid scene settings: {message}")]
    Settings { path: PathBuf, message: String },
}
