//! `slc-core` is what every part of slc shares: the scene model (meshes, materials, textures,
//! lights, camera), the loaders that make scenes from glTF 2.0 and OBJ + MTL files, the
//! built-in scenes, the VPL and frame-buffer types, and the counter-based RNG. It knows no
//! rendering backend.
//!
//! ```
//! let scene = slc_core::load_scene("default")?;
//! println!("{}: {} triangles", scene.name, scene.triangle_count());
//! for light in &scene.lights {
//!     println!("  {light:?}");
//! }
//! assert!(scene.validate_for_render().is_ok());
//! # Ok::<(), slc_core::SceneError>(())
//! ```
pub mod builtin;
pub mod camera;
pub mod culling;
pub mod error;
pub mod framebuffer;
pub mod gltf_loader;
mod gltf_material;
mod gltf_mesh;
mod import_util;
pub mod light;
pub mod load;
pub mod material;
pub mod mesh;
pub mod obj_loader;
pub mod rng;
pub mod scene;
pub mod settings;
pub mod shapes;
pub mod texture;
mod texture_decode;
pub mod vpl;

#[cfg(test)]
mod loader_tests;

pub use builtin::{builtin, BUILTIN_NAMES};
pub use camera::Camera;
pub use culling::{CullError, CullInput, Culler, Interleaving, LightLists, NO_LIST, TILE_SIZE};
pub use error::SceneError;
pub use framebuffer::{GBuffer, GSample, Image};
pub use light::{Incident, Light};
pub use load::{load_scene, load_scene_file};
pub use material::{Material, MaterialModel, ALPHA_MIN};
pub use mesh::Mesh;
pub use scene::{LoadReport, Scene};
pub use settings::{load_settings, MaterialOverride, Settings};
pub use texture::{Texture, TextureId};
pub use vpl::{Vpl, VplLobe};
