//! `slc-core` is what every part of slc shares: the scene model (meshes, materials, textures,
//! lights, camera), the loaders that make scenes from glTF 2.0 and OBJ + MTL files, the
//! built-in scenes, the VPL and frame-buffer types, the counter-based RNG, and the renderer
//! API every backend implements: the frame vocabulary ([`frame`]), the typed culling
//! strategies ([`Strategy`]), the backend trait ([`Renderer`]), the shaders ([`Shader`]) and
//! the frame loop ([`render()`]). It knows no rendering backend.
//!
//! The loaders (glTF, OBJ, settings files; they pull gltf, tobj, image and toml) are behind
//! the default feature `loaders`: an engine that makes its own scenes, G-buffers and VPLs
//! builds `slc-core` (and `slc-cull`) with `default-features = false`.
//!
//! ```
//! # #[cfg(feature = "loaders")] {
//! let scene = slc_core::load_scene("default")?;
//! println!("{}: {} triangles", scene.name, scene.triangle_count());
//! for light in &scene.lights {
//!     println!("  {light:?}");
//! }
//! assert!(scene.validate_for_render().is_ok());
//! # }
//! # Ok::<(), slc_core::SceneError>(())
//! ```
pub mod builtin;
pub mod camera;
pub mod culling;
pub mod error;
#[cfg(feature = "loaders")]
pub mod file_read;
pub mod frame;
pub mod framebuffer;
#[cfg(feature = "loaders")]
mod gltf_accessor;
#[cfg(feature = "loaders")]
pub mod gltf_document;
#[cfg(feature = "loaders")]
pub mod gltf_loader;
#[cfg(feature = "loaders")]
mod gltf_material;
#[cfg(feature = "loaders")]
mod gltf_mesh;
#[cfg(feature = "loaders")]
mod import_util;
pub mod light;
#[cfg(feature = "loaders")]
pub mod load;
pub mod material;
pub mod mesh;
#[cfg(feature = "loaders")]
pub mod obj_loader;
#[cfg(feature = "loaders")]
mod obj_stream;
pub mod progress;
pub mod render;
pub mod renderer;
pub mod rng;
pub mod rsm;
pub mod scene;
#[cfg(feature = "loaders")]
pub mod settings;
#[cfg(feature = "loaders")]
pub mod settings_tables;
pub mod shader;
pub mod shapes;
pub mod strategy;
mod subregions;
pub mod tangents;
pub mod texture;
#[cfg(feature = "loaders")]
mod texture_decode;
pub mod vpl;
pub mod vsgl;

#[cfg(all(test, feature = "loaders"))]
mod loader_tests;

pub use builtin::{builtin, BUILTIN_NAMES};
pub use camera::Camera;
pub use culling::{
    CpuCuller, CullError, CullInput, CullMetrics, Culler, Interleaving, LightLists, NO_LIST,
    TILE_SIZE,
};
pub use error::SceneError;
#[cfg(feature = "loaders")]
pub use file_read::MAX_INPUT_FILE_BYTES;
pub use frame::{RenderError, RenderSettings, RenderedFrame, Shaded, Timings};
pub use framebuffer::{GBuffer, GSample, Image};
pub use light::{one_minus_cos, Emitter, Incident, Light, SpotCone, MAX_RADIOMETRIC};
#[cfg(feature = "loaders")]
pub use load::{load_scene, load_scene_file, MAX_DROPPED_SHARE};
pub use material::{AlphaMask, Material, MaterialAnisotropy, MaterialModel, NormalMap, ALPHA_MIN};
pub use mesh::Mesh;
pub use progress::{Cancel, Monitor, Progress};
pub use render::{render, render_loaded};
pub use renderer::{BackendInfo, Capabilities, PreparedFrame, Renderer};
pub use scene::{LoadReport, Scene};
#[cfg(feature = "loaders")]
pub use settings::{load_settings, MaterialOverride, Settings};
pub use shader::{ShadeInput, Shader};
pub use strategy::{GlossyBound, Layout, Strategy, UnknownStrategy};
pub use subregions::{PerK, Subregions};
pub use texture::{Texture, TextureId};
pub use vpl::{Vpl, VplLobe};
