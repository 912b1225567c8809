//! The scene model of slc.
pub mod camera;
pub mod error;
pub mod framebuffer;
pub mod light;
pub mod material;
pub mod mesh;
pub mod rng;
pub mod scene;
pub mod texture;
pub mod vpl;

pub use camera::Camera;
pub use error::SceneError;
pub use framebuffer::{GBuffer, GSample, Image};
pub use light::{Incident, Light};
pub use material::{Material, MaterialModel, ALPHA_MIN};
pub use mesh::Mesh;
pub use scene::{LoadReport, Scene};
pub use texture::{Texture, TextureId};
pub use vpl::{Vpl, VplLobe};
