//! What a frame is rendered with: the method of indirect light and its parameters, shared by
//! every backend.
use super::counts::{CAMERA_VSGLS, HEIGHT, INTERLEAVE, RSM, SAMPLED_LIGHTS, SPP, WIDTH};
use super::error::RenderError;
use crate::strategy::Strategy;
use crate::vpl::VplLobe;

/// The stochastic estimate of eq. (3) as the paper renders it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stochastic {
    /// δ of eq. (2).
    pub delta: f32,
    pub strategy: Strategy,
    /// K of K x K interleaved sampling (1: off).
    pub interleave: u32,
    /// Cross bilateral filter after shading.
    pub denoise: bool,
    /// Measure true/false positives and misses by brute force (costs a full pass over pairs).
    pub metrics: bool,
}

impl Stochastic {
    /// The paper's setting (section 7): the ellipsoid bound with δ = 1e-3, 8 x 8
    /// interleaving and the cross bilateral filter, without metrics.
    pub const PAPER: Stochastic = Stochastic {
        delta: 1e-3,
        strategy: Strategy::Ellipsoid,
        interleave: 8,
        denoise: true,
        metrics: false,
    };
}

/// The importance `p(s)` sampled lights are drawn with (VSGL section 4.2-4.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Importance {
    /// `p(s) ∝ Φ_i (R_{d,i} + R_{s,i})`, the paper's default (section 4.2).
    Flux,
    /// Estimated with `camera_vsgls` VSGLs generated on the G-buffer (section 4.3), mixed with
    /// the flux importance.
    Bidirectional { camera_vsgls: u32 },
}

impl Importance {
    /// `flux` or `bidirectional`, as reports name it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Flux => "flux",
            Self::Bidirectional { .. } => "bidirectional",
        }
    }
}

/// How a VSGL's diffuse radiant intensity enters its incoming radiance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DiffuseEmission {
    /// The paper's (section 3.1.1 and eq. 5): the Toksvig-filtered SG `c_d G(ω; ξ_d, λ_d)`,
    /// multiplied with the position SG. The SG does not vanish beyond the cluster's horizon
    /// (`e^{−2.133}` = 12 % of its peak in the tangent plane of a flat cluster), which lights
    /// receivers beside and below the cluster that its VPLs cannot reach.
    Sg,
    /// The diffuse intensity of texels whose normals are distributed as a von Mises-Fisher
    /// lobe about `ξ_d` with the cluster's concentration κ: `I_d(ω) = Σ Φ R_d / π · E(κ,
    /// ξ_d·ω)`, the clamped cosine convolved with that lobe, evaluated towards the receiver
    /// along the position SG's axis, which then carries it: `L_in(ω) ≈ I_d(−ξ_μ) G(ω; ξ_μ,
    /// λ_σ)/(2πσ_v²)`. Exact for a single texel (its VPL's `kd/π max(cos, 0)`) and zero beyond
    /// the horizon of a flat cluster; it keeps the total `Σ Φ R_d`. It ignores the variation
    /// of `I_d` across the position SG, which matters only for large clusters seen from
    /// nearby.
    #[default]
    ClampedCosine,
}

impl DiffuseEmission {
    /// `sg` or `clamped`, as the command line and reports name it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Sg => "sg",
            Self::ClampedCosine => "clamped",
        }
    }
}

/// `count` lights sampled with `importance`; VSGLs, and the camera-side VSGLs of the
/// bidirectional importance, shade their diffuse lobes as `diffuse` says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightSampling {
    pub count: u32,
    pub importance: Importance,
    pub diffuse: DiffuseEmission,
}

/// Which lobes become VPLs (the paper's Table 2 measures diffuse-only and glossy-only runs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LobeSelection {
    Both,
    Diffuse,
    Glossy,
}

impl LobeSelection {
    /// Whether VPLs of `lobe` are made.
    pub fn wants(self, lobe: VplLobe) -> bool {
        matches!(
            (self, lobe),
            (LobeSelection::Both, _)
                | (LobeSelection::Diffuse, VplLobe::Diffuse)
                | (LobeSelection::Glossy, VplLobe::Glossy)
        )
    }

    /// How many VPLs a lit RSM texel makes at most: one per lobe selected.
    pub fn per_texel(self) -> u32 {
        match self {
            LobeSelection::Both => 2,
            LobeSelection::Diffuse | LobeSelection::Glossy => 1,
        }
    }
}

/// How indirect light is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Every VPL at every pixel with p = 1: the all-VPL reference.
    VplReference,
    /// The stochastic estimate with culling.
    Stochastic(Stochastic),
    /// Path-traced one-bounce reference (no VPLs).
    Path,
    /// Virtual spherical Gaussian lights sampled from the mipmapped RSMs (Tokuyoshi 2015).
    Vsgl(LightSampling),
    /// VPLs of texels sampled with the same importance and points as [`Method::Vsgl`], the
    /// equal-count VPL estimator.
    SampledVpls(LightSampling),
}

/// What to render.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// RSM resolution per face (texels per side).
    pub rsm_resolution: u32,
    pub seed: u32,
    pub method: Method,
    /// Shadow rays between VPLs and pixels (VPL methods; the path method always has
    /// visibility), or VSGL eq. 3's visibility to each VSGL's mean.
    pub visibility: bool,
    /// Passes averaged. With 1, primary rays go through pixel centres and RSM rays through
    /// texel centres (what a rasterizer does); with more, both are jittered, each pass with
    /// its own VPLs and ξ, so the average converges to the one-bounce solution (box pixel
    /// filter).
    pub spp: u32,
    pub lobes: LobeSelection,
}

impl RenderSettings {
    /// A `width` x `height` frame with RSM faces of `rsm_resolution`² texels, indirect light by
    /// `method`, and the rest as `slc render` has it by default: seed 0, no visibility, one
    /// pass, both lobes. Change a field with struct update syntax (`RenderSettings { seed: 3,
    /// ..RenderSettings::new(..) }`).
    pub fn new(width: u32, height: u32, rsm_resolution: u32, method: Method) -> Self {
        Self {
            width,
            height,
            rsm_resolution,
            seed: 0,
            method,
            visibility: false,
            spp: 1,
            lobes: LobeSelection::Both,
        }
    }

    /// Checks every number is in its domain ([`super::counts`]): the one check of settings
    /// every front end runs before any work.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |m: String| RenderError::Settings(m);
        WIDTH.check(self.width).map_err(bad)?;
        HEIGHT.check(self.height).map_err(bad)?;
        RSM.check(self.rsm_resolution).map_err(bad)?;
        SPP.check(self.spp).map_err(bad)?;
        if let Method::Stochastic(s) = self.method {
            if !(s.delta.is_finite() && s.delta > 0.0) {
                return Err(bad(format!(
                    "delta must be finite and positive (got {})",
                    s.delta
                )));
            }
            INTERLEAVE.check(s.interleave).map_err(bad)?;
        }
        if let Method::Vsgl(l) | Method::SampledVpls(l) = self.method {
            SAMPLED_LIGHTS.check(l.count).map_err(bad)?;
            if let Importance::Bidirectional { camera_vsgls } = l.importance {
                CAMERA_VSGLS.check(camera_vsgls).map_err(bad)?;
            }
            if self.lobes != LobeSelection::Both {
                return Err(bad(
                    "sampled lights (VSGLs) carry both lobes: the lobes must be both".into(),
                ));
            }
        }
        Ok(())
    }
}
