//! Command-line options shared by `render`, `compare` and `sweep`.
use clap::builder::TypedValueParser;
use clap::{Args, ValueEnum};
use slc_app::backends::Backend;
use slc_core::frame::counts::{CAMERA_VSGLS, HEIGHT, INTERLEAVE, RSM, SAMPLED_LIGHTS, WIDTH};
use slc_core::frame::{
    Count, DiffuseEmission, Importance, LightSampling, LobeSelection, Method, RenderSettings,
    Stochastic,
};
use slc_core::shader::ShadeInput;
use slc_core::{load_scene, Renderer, Scene, Strategy};
use std::path::PathBuf;

/// How the GPU backend runs the tiled strategies (`sphere`, `enclosing-sphere`,
/// `ellipsoid`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum GpuTiled {
    /// Culled and shaded in one pass, the lists only in workgroup memory (the paper's Fig. 2).
    OnePass,
    /// Culled into light lists, then shaded by a second pass (the images are the same).
    Lists,
}

/// How the GPU backend rasterizes clustered-raster's bounding meshes conservatively.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum GpuConservative {
    /// By the adapter (`CONSERVATIVE_RASTERIZATION`), where it has it; else in software.
    Hardware,
    /// Each triangle drawn as the whole cells around it, kept where it meets them.
    Software,
}

/// The backend a command runs on, as `--backend`, `--gpu-tiled` and `--gpu-conservative`
/// chose it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackendChoice {
    pub backend: Backend,
    /// The GPU's tiled strategies culled and shaded in one pass.
    pub one_pass: bool,
    /// The GPU's conservative rasterization in hardware where the adapter has it.
    pub hardware_conservative: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Shader {
    /// VPLs with the stochastic estimate and culling (or a reference).
    Vpl,
    /// Virtual spherical Gaussian lights sampled from mipmapped RSMs (Tokuyoshi 2015); `slc render`,
    /// `slc compare` and `slc sweep` on either backend (`--backend gpu --visibility`:
    /// imperfect shadow maps; not in `compare`, whose VPLs have no visibility on the GPU).
    Vsgl,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ImportanceKind {
    /// p(s) ∝ Φ (R_d + R_s), the VSGL paper's default (section 4.2).
    Flux,
    /// Estimated with VSGLs generated on the G-buffer (section 4.3), mixed with 10 % flux.
    Bidirectional,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DiffuseKind {
    /// The diffuse intensity as the clamped cosine convolved with the cluster's normals: exact
    /// for one texel, nothing beyond a flat cluster's horizon.
    Clamped,
    /// The paper's Toksvig-filtered diffuse SG (section 3.1.1, eq. 5).
    Sg,
}

/// How sampled lights (VSGLs, or VPLs at equal count) are drawn from the RSMs and shaded.
#[derive(Args, Debug, Clone)]
pub struct ImportanceArgs {
    /// The importance VSGLs are sampled with.
    #[arg(long, value_enum, default_value_t = ImportanceKind::Flux)]
    pub vsgl_importance: ImportanceKind,
    #[arg(long, default_value_t = 1024, value_parser = count(CAMERA_VSGLS),
          help = CAMERA_VSGLS.help("VSGLs generated on the G-buffer to estimate the bidirectional importance"))]
    pub camera_vsgls: u32,
    /// The form of a VSGL's diffuse radiant intensity.
    #[arg(long, value_enum, default_value_t = DiffuseKind::Clamped)]
    pub vsgl_diffuse: DiffuseKind,
}

impl ImportanceArgs {
    /// `count` lights with this importance.
    pub fn sampling(&self, count: u32) -> LightSampling {
        LightSampling {
            count,
            importance: match self.vsgl_importance {
                ImportanceKind::Flux => Importance::Flux,
                ImportanceKind::Bidirectional => Importance::Bidirectional {
                    camera_vsgls: self.camera_vsgls,
                },
            },
            diffuse: match self.vsgl_diffuse {
                DiffuseKind::Clamped => DiffuseEmission::ClampedCosine,
                DiffuseKind::Sg => DiffuseEmission::Sg,
            },
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Lobes {
    /// Diffuse and glossy VPLs.
    Both,
    /// Diffuse VPLs only (spheres in every strategy), as the paper's Table 2, upper half.
    Diffuse,
    /// Glossy VPLs only, as the paper's Table 2, lower half.
    Glossy,
}

/// A scene as the command line names it: a path the OS takes (UTF-8 or not) or a built-in
/// name; it reads as its text (lossy where the path is not UTF-8) in reports.
#[derive(Debug, Clone)]
pub struct SceneSpec {
    pub path: PathBuf,
    text: String,
}

impl SceneSpec {
    /// A clap value parser: any argument the OS passes.
    pub fn parser() -> impl clap::builder::TypedValueParser<Value = SceneSpec> {
        clap::builder::OsStringValueParser::new().map(|s| SceneSpec {
            text: s.to_string_lossy().into_owned(),
            path: PathBuf::from(s),
        })
    }

    /// The scene `spec` names (`None`: the built-in default), its loader warnings printed.
    pub fn load(spec: Option<&SceneSpec>) -> Result<Scene, String> {
        let name = spec.map_or(std::ffi::OsStr::new("default"), |s| s.path.as_os_str());
        let scene = load_scene(name).map_err(|e| e.to_string())?;
        for w in &scene.report.warnings {
            eprintln!("warning: {}: {w}", scene.label());
        }
        Ok(scene)
    }
}

impl std::ops::Deref for SceneSpec {
    type Target = str;
    fn deref(&self) -> &str {
        &self.text
    }
}

/// What a frame is made of: the scene, the image, the VPLs.
#[derive(Args, Debug, Clone)]
pub struct FrameArgs {
    /// A .gltf/.glb/.obj file, a .toml scene-settings file, or a built-in scene name; none
    /// renders the built-in default.
    #[arg(value_parser = SceneSpec::parser())]
    pub scene: Option<SceneSpec>,
    #[arg(long, default_value_t = 512, value_parser = count(WIDTH), help = WIDTH.help("Image width in pixels"))]
    pub width: u32,
    #[arg(long, default_value_t = 512, value_parser = count(HEIGHT), help = HEIGHT.help("Image height in pixels"))]
    pub height: u32,
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
    /// With `--backend gpu`: the tiled strategies culled and shaded in one pass (the default)
    /// or culled into light lists and shaded by a second pass, to compare the two.
    #[arg(long, value_enum)]
    pub gpu_tiled: Option<GpuTiled>,
    /// With `--backend gpu`: clustered-raster's conservative rasterization in hardware (the
    /// default, where the adapter has it) or in software, to compare the two (the same lists).
    #[arg(long, value_enum)]
    pub gpu_conservative: Option<GpuConservative>,
    #[arg(long, value_enum, default_value_t = Shader::Vpl)]
    pub shader: Shader,
    #[arg(long, default_value_t = 64, value_parser = count(RSM),
          help = RSM.help("Reflective-shadow-map resolution per face (a point light has six faces; each texel makes a diffuse and a glossy VPL)"))]
    pub rsm: u32,
    /// Seed of ξ, interleaving and sampling: an unsigned 32-bit integer (0..=4294967295).
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Exposure of the PNG previews in stops (each PNG shows the linear image times
    /// 2^exposure); the EXR files are never scaled.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = stops)]
    pub exposure: f32,
    /// Which VPL lobes to generate.
    #[arg(long, value_enum, default_value_t = Lobes::Both)]
    pub lobes: Lobes,
    /// Shadow rays between every listed VPL and pixel (`--shader vsgl`: to each VSGL's mean;
    /// `--backend gpu --shader vsgl`: imperfect shadow maps instead of rays).
    #[arg(long)]
    pub visibility: bool,
}

/// A clap value parser of a count: a whole number in its range.
pub fn count(c: Count) -> impl Fn(&str) -> Result<u32, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let v: u32 = s
            .trim()
            .parse()
            .map_err(|e| format!("{e}: {} is a whole number in {c}", c.what))?;
        c.check(v)
    }
}

/// A clap value parser of δ: a finite number above 0.
pub fn positive(s: &str) -> Result<f32, String> {
    let v: f32 = s.trim().parse().map_err(|e| format!("{e}"))?;
    (v.is_finite() && v > 0.0)
        .then_some(v)
        .ok_or_else(|| format!("{v} is not a finite number above 0"))
}

/// An exposure in stops: a number in [-64, 64].
pub fn stops(s: &str) -> Result<f32, String> {
    let v: f32 = s.trim().parse().map_err(|e| format!("{e}"))?;
    (-64.0..=64.0)
        .contains(&v)
        .then_some(v)
        .ok_or_else(|| format!("{v} is not in [-64, 64] stops"))
}

impl FrameArgs {
    /// The backend `--backend`, `--gpu-tiled` and `--gpu-conservative` choose; either of the
    /// last two without the GPU backend is an error.
    pub fn backend_choice(&self) -> Result<BackendChoice, String> {
        if self.backend != Backend::Gpu && self.gpu_tiled.is_some() {
            return Err("--gpu-tiled chooses how the GPU backend culls; add --backend gpu".into());
        }
        if self.backend != Backend::Gpu && self.gpu_conservative.is_some() {
            return Err(
                "--gpu-conservative chooses how the GPU backend rasterizes; add --backend gpu"
                    .into(),
            );
        }
        Ok(BackendChoice {
            backend: self.backend,
            one_pass: self.gpu_tiled != Some(GpuTiled::Lists),
            hardware_conservative: self.gpu_conservative != Some(GpuConservative::Software),
        })
    }

    /// Loads the scene, printing its loader warnings.
    pub fn load(&self) -> Result<Scene, String> {
        SceneSpec::load(self.scene.as_ref())
    }

    /// Loads the scene and checks it can be rendered (geometry, a valid light).
    pub fn load_renderable(&self) -> Result<Scene, String> {
        let scene = self.load()?;
        scene.validate_for_render().map_err(|e| e.to_string())?;
        Ok(scene)
    }

    /// What a shader reads of `prepared` on `r`, with this frame's seed and visibility.
    pub fn input<'a, R: Renderer>(
        &self,
        scene: &'a Scene,
        loaded: &'a R::Scene,
        prepared: &'a R::Prepared,
    ) -> ShadeInput<'a, R> {
        ShadeInput {
            scene,
            loaded,
            prepared,
            seed: self.seed,
            visibility: self.visibility,
        }
    }

    /// Render settings for `method`, one pass.
    pub fn settings(&self, method: Method, spp: u32) -> RenderSettings {
        RenderSettings {
            width: self.width,
            height: self.height,
            rsm_resolution: self.rsm,
            seed: self.seed,
            method,
            visibility: self.visibility,
            spp,
            lobes: self.lobes.selection(),
        }
    }
}

impl Lobes {
    /// The lobes as the renderer selects them.
    pub fn selection(self) -> LobeSelection {
        match self {
            Lobes::Both => LobeSelection::Both,
            Lobes::Diffuse => LobeSelection::Diffuse,
            Lobes::Glossy => LobeSelection::Glossy,
        }
    }
}

/// A culling strategy named on the command line.
pub fn strategy(name: &str) -> Result<Strategy, String> {
    name.parse()
        .map_err(|e: slc_core::UnknownStrategy| e.to_string())
}

/// The help of a `--culling` option: what it takes (`what`), then every strategy's name
/// ([`Strategy::names`], the one list of them).
pub fn culling_help(what: &str) -> String {
    format!("{what}: {}", Strategy::names().join(", "))
}

/// The culling strategies named on the command line, in their order.
pub fn strategies(names: &[String]) -> Result<Vec<Strategy>, String> {
    names.iter().map(|n| strategy(n)).collect()
}

/// Interleaving and denoising of the stochastic estimate, shared by every command.
#[derive(Args, Debug, Clone)]
pub struct PipelineArgs {
    #[arg(long, default_value_t = 8, value_parser = count(INTERLEAVE),
          help = INTERLEAVE.help("K of K x K interleaved sampling (1 turns it off)"))]
    pub interleave: u32,
    /// Skip the cross bilateral filter.
    #[arg(long)]
    pub no_denoise: bool,
}

impl PipelineArgs {
    /// The stochastic estimate with these options.
    pub fn stochastic(&self, delta: f32, strategy: Strategy, metrics: bool) -> Stochastic {
        Stochastic {
            delta,
            strategy,
            interleave: self.interleave,
            denoise: !self.no_denoise,
            metrics,
        }
    }
}

/// The estimate of indirect light: the culling strategy and δ of the VPL shader, the VSGL
/// count of the VSGL shader (`render` and `view`).
#[derive(Args, Debug, Clone)]
pub struct EstimateArgs {
    #[arg(long, default_value_t = 1024, value_parser = count(SAMPLED_LIGHTS),
          help = SAMPLED_LIGHTS.help("With --shader vsgl: the number of VSGLs sampled from the RSMs"))]
    pub vsgls: u32,
    // The help names every strategy (`culling_help`).
    #[arg(long, default_value = "ellipsoid", help = culling_help("Culling strategy, one of"))]
    pub culling: String,
    /// δ of eq. (2), in the units of I / l² (W sr⁻¹ m⁻²): larger culls more and adds variance
    /// (a finite number above 0).
    #[arg(long, default_value_t = 1e-3, value_parser = positive)]
    pub delta: f32,
}

impl EstimateArgs {
    /// The method `shader` estimates indirect light with: VSGLs sampled with `importance`, or
    /// the stochastic VPL estimate with `pipeline` (and culling metrics with `metrics`).
    pub fn method(
        &self,
        shader: Shader,
        pipeline: &PipelineArgs,
        importance: &ImportanceArgs,
        metrics: bool,
    ) -> Result<Method, String> {
        Ok(match shader {
            Shader::Vsgl => Method::Vsgl(importance.sampling(self.vsgls)),
            Shader::Vpl => Method::Stochastic(pipeline.stochastic(
                self.delta,
                strategy(&self.culling)?,
                metrics,
            )),
        })
    }
}
