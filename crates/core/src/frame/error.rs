//! Why a frame could not be rendered.
use crate::culling::CullError;
use crate::error::SceneError;
use crate::renderer::Capabilities;

/// Errors of rendering, on any backend.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Bounds(#[from] slc_bounds::BoundsError),
    #[error(transparent)]
    Cull(#[from] CullError),
    #[error("invalid render settings: {0}")]
    Settings(String),
    /// The backend does not have what the settings ask for: `what` is the first thing it
    /// lacks, `needs` all the settings need (the backends whose capabilities cover it can
    /// render them; `slc_app::backends::message` names one).
    #[error("the {backend} backend does not support {what}")]
    Unsupported {
        backend: &'static str,
        what: String,
        needs: Capabilities,
    },
    /// A pass produced NaN or infinite pixels (an input whose products overflow f32).
    #[error("the {pass} pass produced {count} non-finite pixel(s) of {pixels} (NaN or infinity): some radiometric input overflows f32; lower the light's intensity or check the scene's values")]
    NonFinite {
        pass: &'static str,
        count: usize,
        pixels: usize,
    },
    /// The work was cancelled through its monitor ([`crate::progress::Cancel`]) before it was
    /// done; nothing it made is returned.
    #[error("cancelled")]
    Cancelled,
    /// A failure inside a backend (a GPU fault, an invalid VSGL input, ...).
    #[error(transparent)]
    Backend(Box<dyn std::error::Error + Send + Sync + 'static>),
}

impl RenderError {
    /// Wraps a backend's own error.
    pub fn backend(e: impl std::error::Error + Send + Sync + 'static) -> Self {
        Self::Backend(Box::new(e))
    }
}
