//! `slc.Scene`: a scene loaded once and rendered many times with changed settings; what each
//! backend makes of it (the CPU's BVH, the GPU's device and buffers) is kept between calls.
//! Every call releases the GIL while it works.
use crate::backend::{Job, Loaded};
use crate::error;
use crate::frame::{FrameData, PyFrame};
use crate::options::{strategy, Options, COMPARE, FRAME, LISTS, RENDER};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slc_app::progress::bar_if;
use slc_app::reference::{all_vpl_reference, cpu_input};
use slc_core::culling::{Interleaving, LightLists, NO_LIST};
use slc_core::frame::{Method, RenderSettings, RenderedFrame, Stochastic};
use slc_core::shader::{frame_timings, ShadeInput, Shader as _};
use slc_core::{load_scene, MaterialOverride, PreparedFrame, Renderer, Scene, Strategy, VplLobe};
use slc_cpu_ref::{CpuFrames, CpuRenderer};
use std::sync::{Mutex, PoisonError};

/// A scene and what the backends keep of it.
#[pyclass(name = "Scene", module = "slc", frozen)]
pub struct PyScene {
    scene: Scene,
    /// What the scene was loaded from, for the reports' provenance.
    spec: Option<String>,
    /// Locked for the whole of a call (without the GIL): calls on one scene from several
    /// threads wait for each other.
    loaded: Mutex<Loaded>,
}

/// A whole frame (`Scene.render`).
struct RenderJob<'a> {
    spec: Option<&'a str>,
    options: &'a Options,
}

impl Job for RenderJob<'_> {
    type Output = FrameData;
    fn run<R: CpuFrames>(
        self,
        r: &R,
        scene: &Scene,
        loaded: &R::Scene,
    ) -> Result<FrameData, String> {
        let s = &self.options.settings;
        let bar = bar_if(
            self.options.progress,
            s.width as u64 * s.height as u64 * s.spp as u64,
            format!("rendering {} on the {}", scene.name, r.name()),
        );
        let frame = slc_core::render_loaded(r, scene, loaded, s, &|n| bar.inc(n))
            .map_err(|e| e.to_string())?;
        bar.finish_and_clear();
        FrameData::new(r, scene, self.spec, s, frame)
    }
}

/// Every strategy on one prepared frame, with metrics, and the all-VPL reference
/// (`Scene.compare`).
struct CompareJob<'a> {
    spec: Option<&'a str>,
    options: &'a Options,
    base: Stochastic,
    /// The strategies to compare; `None`: every one the backend runs.
    strategies: Option<&'a [Strategy]>,
    reference: bool,
}

impl Job for CompareJob<'_> {
    type Output = Vec<(&'static str, FrameData)>;
    fn run<R: CpuFrames>(
        self,
        r: &R,
        scene: &Scene,
        loaded: &R::Scene,
    ) -> Result<Self::Output, String> {
        let settings = &self.options.settings;
        let (seed, visibility) = (settings.seed, settings.visibility);
        let with = |method| RenderSettings {
            method,
            ..settings.clone()
        };
        let frame = |p: &R::Prepared, indirect, (timings, gpu_timings), metrics| {
            Ok::<_, String>(RenderedFrame {
                direct: p.direct().clone(),
                indirect,
                vpl_count: p.vpl_count().map_err(|e| e.to_string())?,
                timings,
                gpu_timings,
                metrics,
                sampled_lights: None,
                readback_bytes: None,
            })
        };
        let message = |e: slc_core::RenderError| e.to_string();
        let p = r.prepare(scene, loaded, settings, None).map_err(message)?;
        let mut out = Vec::new();
        if self.reference {
            let cpu_p = r.cpu_frame(scene, loaded, &p).map_err(message)?;
            let reference = all_vpl_reference(
                cpu_input(scene, &cpu_p, seed, visibility),
                self.options.progress,
            )?;
            let preparation = (p.timings().clone(), p.gpu_timings().cloned());
            let f = frame(&p, reference, preparation, None)?;
            let s = with(Method::VplReference);
            out.push((
                "reference_vpl",
                FrameData::new(&CpuRenderer::default(), scene, self.spec, &s, f)?,
            ));
        }
        let input = ShadeInput {
            scene,
            loaded,
            prepared: &p,
            seed,
            visibility,
        };
        let all: Vec<Strategy> = Strategy::every()
            .filter(|&s| r.capabilities().runs(s))
            .collect();
        for &strategy in self.strategies.unwrap_or(&all) {
            let st = Stochastic {
                strategy,
                metrics: true,
                ..self.base
            };
            let bar = bar_if(
                self.options.progress,
                settings.width as u64 * settings.height as u64,
                strategy.name().into(),
            );
            let shaded = st.shade(r, input, &|n| bar.inc(n)).map_err(message)?;
            bar.finish_and_clear();
            let timings = frame_timings(&p, &shaded);
            let f = frame(&p, shaded.indirect, timings, shaded.metrics)?;
            let s = with(Method::Stochastic(st));
            out.push((strategy.name(), FrameData::new(r, scene, self.spec, &s, f)?));
        }
        Ok(out)
    }
}

/// The VPLs of a prepared frame as columns (`Scene.vpls`).
#[derive(Default)]
struct VplColumns {
    position: Vec<f32>,
    normal: Vec<f32>,
    omega_i: Vec<f32>,
    flux: Vec<f32>,
    kd: Vec<f32>,
    alpha: Vec<f32>,
    glossy: Vec<bool>,
    id: Vec<u32>,
    xi: Vec<f32>,
}

struct VplsJob<'a> {
    options: &'a Options,
}

impl Job for VplsJob<'_> {
    type Output = VplColumns;
    fn run<R: CpuFrames>(
        self,
        r: &R,
        scene: &Scene,
        loaded: &R::Scene,
    ) -> Result<VplColumns, String> {
        let p = r
            .prepare(scene, loaded, &self.options.settings, None)
            .map_err(|e| e.to_string())?;
        let mut c = VplColumns::default();
        for v in p.vpls().map_err(|e| e.to_string())? {
            c.position.extend(v.position.to_array());
            c.normal.extend(v.normal.to_array());
            c.omega_i.extend(v.omega_i.to_array());
            c.flux.extend(v.flux.to_array());
            c.kd.extend(v.brdf.kd.to_array());
            c.alpha.push(v.brdf.alpha);
            c.glossy.push(v.lobe == VplLobe::Glossy);
            c.id.push(v.id);
            c.xi.push(v.xi);
        }
        Ok(c)
    }
}

/// The light lists of one strategy, culled on the CPU from the backend's frame
/// (`Scene.light_lists`).
struct ListsJob<'a> {
    options: &'a Options,
    stochastic: Stochastic,
}

impl Job for ListsJob<'_> {
    type Output = LightLists;
    fn run<R: CpuFrames>(
        self,
        r: &R,
        scene: &Scene,
        loaded: &R::Scene,
    ) -> Result<LightLists, String> {
        let message = |e: slc_core::RenderError| e.to_string();
        let settings = &self.options.settings;
        let p = r.prepare(scene, loaded, settings, None).map_err(message)?;
        let cpu_p = r.cpu_frame(scene, loaded, &p).map_err(message)?;
        let s = self.stochastic;
        CpuRenderer::default()
            .cull(
                &cpu_p,
                s.strategy,
                s.delta,
                Interleaving {
                    k: s.interleave,
                    seed: settings.seed,
                },
            )
            .map_err(message)
    }
}

impl PyScene {
    fn new(scene: Scene, spec: Option<String>) -> Self {
        Self {
            scene,
            spec,
            loaded: Mutex::default(),
        }
    }

    /// Runs `job` on the options' backend without the GIL, after checking the scene can be
    /// rendered and the frame fits in memory.
    fn run<J: Job + Send>(&self, py: Python<'_>, options: &Options, job: J) -> PyResult<J::Output>
    where
        J::Output: Send,
    {
        slc_app::limits::check_frames(&self.scene, std::slice::from_ref(&options.settings))
            .map_err(error)?;
        py.detach(|| {
            let mut loaded = self.loaded.lock().unwrap_or_else(PoisonError::into_inner);
            loaded.run(options, &self.scene, job)
        })
        .map_err(error)
    }
}

#[pymethods]
impl PyScene {
    /// A scene from a `.gltf`/`.glb`/`.obj` file, a `.toml` scene-settings file or a built-in
    /// name (`None`: the built-in default).
    #[new]
    #[pyo3(signature = (spec=None))]
    fn py_new(spec: Option<String>) -> PyResult<Self> {
        let scene = load_scene(spec.as_deref().unwrap_or("default")).map_err(error)?;
        Ok(Self::new(scene, spec))
    }

    /// A scene from a file (`.gltf`, `.glb`, `.obj` or a `.toml` scene-settings file).
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        let spec = path.to_string_lossy().into_owned();
        let scene = load_scene(&path).map_err(error)?;
        Ok(Self::new(scene, Some(spec)))
    }

    /// A built-in scene (`slc.BUILTIN_SCENES`).
    #[staticmethod]
    #[pyo3(signature = (name="default"))]
    fn builtin(name: &str) -> PyResult<Self> {
        let scene = slc_core::builtin(name).ok_or_else(|| {
            error(format!(
                "unknown built-in scene '{name}'; built-in scenes: {}",
                slc_core::BUILTIN_NAMES.join(", ")
            ))
        })?;
        Ok(Self::new(scene, Some(name.to_string())))
    }

    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// Triangles the scene has.
    #[getter]
    fn triangles(&self) -> usize {
        self.scene.triangle_count()
    }

    /// Punctual lights the scene has.
    #[getter]
    fn lights(&self) -> usize {
        self.scene.lights.len()
    }

    /// A copy of the scene with the materials `pattern` matches overridden (as a settings
    /// file's `[[materials]]`: `pattern` is a name or a glob with `*`; kd and f0 in [0, 1],
    /// alpha or roughness = √alpha in (0, 1], eta above 0, glTF KHR_materials_anisotropy's
    /// strength in [0, 1] and rotation in radians). The copy is loaded anew on its first
    /// render; this scene is unchanged.
    #[pyo3(signature = (pattern, *, kd=None, f0=None, alpha=None, roughness=None, eta=None, double_sided=None, anisotropy_strength=None, anisotropy_rotation=None))]
    #[allow(clippy::too_many_arguments)]
    fn with_materials(
        &self,
        pattern: &str,
        kd: Option<[f32; 3]>,
        f0: Option<[f32; 3]>,
        alpha: Option<f32>,
        roughness: Option<f32>,
        eta: Option<f32>,
        double_sided: Option<bool>,
        anisotropy_strength: Option<f32>,
        anisotropy_rotation: Option<f32>,
    ) -> PyResult<Self> {
        let o = MaterialOverride::new(
            pattern,
            kd,
            f0,
            alpha,
            roughness,
            eta,
            double_sided,
            (anisotropy_strength, anisotropy_rotation),
        )
        .map_err(PyValueError::new_err)?;
        let mut scene = self.scene.clone();
        scene
            .override_materials(std::slice::from_ref(&o))
            .map_err(PyValueError::new_err)?;
        // Reports say the scene is not its file's alone.
        let set: Vec<String> = [
            kd.map(|v| format!("kd {v:?}")),
            f0.map(|v| format!("f0 {v:?}")),
            o.alpha.map(|v| format!("alpha {v}")),
            eta.map(|v| format!("eta {v}")),
            double_sided.map(|v| format!("double_sided {v}")),
            o.anisotropy
                .map(|a| format!("anisotropy {} at {} rad", a.strength, a.rotation)),
        ]
        .into_iter()
        .flatten()
        .collect();
        scene.report.warnings.push(format!(
            "materials '{pattern}' overridden from Python: {}",
            set.join(", ")
        ));
        Ok(Self::new(scene, self.spec.clone()))
    }

    /// Names of the scene's materials.
    #[getter]
    fn materials(&self) -> Vec<String> {
        self.scene
            .materials
            .iter()
            .map(|m| m.name.clone())
            .collect()
    }

    /// How many times a backend built its state of this scene (the CPU's BVH, the GPU's
    /// upload): once per backend used, however many frames were rendered.
    #[getter]
    fn loads(&self) -> usize {
        self.loaded
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .loads()
    }

    /// What the loader dropped or ignored, as sentences.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.report.warnings.clone()
    }

    /// The file the scene came from, or `None`.
    #[getter]
    fn source(&self) -> Option<std::path::PathBuf> {
        self.scene.source.clone()
    }

    /// Renders a frame with the keyword options of `slc.render`.
    #[pyo3(signature = (**options))]
    fn render(&self, py: Python<'_>, options: Option<&Bound<'_, PyDict>>) -> PyResult<PyFrame> {
        let options = Options::parse(options, RENDER)?;
        let spec = self.spec.clone();
        let job = RenderJob {
            spec: spec.as_deref(),
            options: &options,
        };
        let data = self.run(py, &options, job)?;
        PyFrame::new(py, data)
    }

    /// Every strategy of `culling` (default: every one the backend runs) on the same
    /// G-buffer, VPLs and ξ, each with its culling metrics, and (with `reference`) every VPL with p = 1 as `"reference_vpl"`. Returns a
    /// dict from name to `Frame`.
    #[pyo3(signature = (culling=None, reference=true, **options))]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        culling: Option<Vec<String>>,
        reference: bool,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let parsed = Options::parse(options, COMPARE)?;
        let strategies = culling
            .map(|names| {
                names
                    .iter()
                    .map(|n| strategy(n))
                    .collect::<PyResult<Vec<_>>>()
            })
            .transpose()?;
        let base = Options::stochastic(options)?;
        let spec = self.spec.clone();
        let job = CompareJob {
            spec: spec.as_deref(),
            options: &parsed,
            base,
            strategies: strategies.as_deref(),
            reference,
        };
        let frames = self.run(py, &parsed, job)?;
        let out = PyDict::new(py);
        for (name, data) in frames {
            out.set_item(name, PyFrame::new(py, data)?)?;
        }
        Ok(out)
    }

    /// The VPLs of the frame the options describe, as a dict of numpy arrays (one row per
    /// VPL): `position`, `normal`, `omega_i` (towards where the photon came from), `flux`,
    /// `kd` (N×3 float32), `alpha` (GGX roughness), `xi` (the Russian-roulette number)
    /// (N float32), `glossy` (N bool: the glossy lobe, else the diffuse one), `id` (N uint32).
    #[pyo3(signature = (**options))]
    fn vpls<'py>(
        &self,
        py: Python<'py>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let options = Options::parse(options, FRAME)?;
        let c = self.run(py, &options, VplsJob { options: &options })?;
        let out = PyDict::new(py);
        let n = c.alpha.len();
        for (key, column) in [
            ("position", c.position),
            ("normal", c.normal),
            ("omega_i", c.omega_i),
            ("flux", c.flux),
            ("kd", c.kd),
        ] {
            out.set_item(key, PyArray1::from_vec(py, column).reshape([n, 3])?)?;
        }
        out.set_item("alpha", PyArray1::from_vec(py, c.alpha))?;
        out.set_item("xi", PyArray1::from_vec(py, c.xi))?;
        out.set_item("glossy", PyArray1::from_vec(py, c.glossy))?;
        out.set_item("id", PyArray1::from_vec(py, c.id))?;
        Ok(out)
    }

    /// The light lists the options' strategy (`culling`, `delta`, `interleave`) builds for the
    /// frame, culled on the CPU: `lists` is the list of each pixel (H×W uint32, `NO_LIST`
    /// where the pixel has none), list l holds the VPL indices (rows of `Scene.vpls`)
    /// `indices[offsets[l]:offsets[l + 1]]`.
    #[pyo3(signature = (**options))]
    fn light_lists<'py>(
        &self,
        py: Python<'py>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let parsed = Options::parse(options, LISTS)?;
        let job = ListsJob {
            options: &parsed,
            stochastic: Options::stochastic(options)?,
        };
        let lists = self.run(py, &parsed, job)?;
        let s = &parsed.settings;
        let out = PyDict::new(py);
        out.set_item("offsets", PyArray1::from_vec(py, lists.offsets))?;
        out.set_item("indices", PyArray1::from_vec(py, lists.indices))?;
        let pixels: Bound<'py, PyArray2<u32>> = PyArray1::from_vec(py, lists.pixel_list)
            .reshape([s.height as usize, s.width as usize])?;
        out.set_item("lists", pixels)?;
        out.set_item("NO_LIST", NO_LIST)?;
        Ok(out)
    }

    fn __repr__(&self) -> String {
        format!(
            "<slc.Scene '{}': {} triangles, {} lights>",
            self.scene.name,
            self.scene.triangle_count(),
            self.scene.lights.len()
        )
    }
}
