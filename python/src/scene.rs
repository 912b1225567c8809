//! The native scene behind `slc.Scene` (`slc/_scene.py`, which documents the options and
//! fills in their defaults): a scene loaded once and rendered many times with changed
//! settings; what each backend makes of it (the CPU's BVH, the GPU's device and buffers) is
//! kept between calls. Every call works on a worker thread without the GIL, stops on Ctrl-C
//! and reports its progress ([`crate::watch`]).
use crate::backend::{message, Job, Loaded, On};
use crate::error;
use crate::frame::{FrameData, PyFrame};
use crate::options::{strategies, Options, COMPARE, FRAME, LISTS, RENDER};
use crate::tables::{table, table_to_py};
use crate::watch::{watched, Reporter};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use slc_app::cpu_frames::CpuFrames;
use slc_app::reference::{all_vpl_reference, cpu_input};
use slc_core::culling::{Interleaving, LightLists, NO_LIST};
use slc_core::frame::{Method, RenderSettings, RenderedFrame, Stochastic};
use slc_core::settings_tables::{camera_from_table, camera_table, light_from_table, light_table};
use slc_core::shader::{frame_timings, ShadeInput, Shader as _};
use slc_core::{load_scene, MaterialOverride, PreparedFrame, Renderer, Scene, Strategy, VplLobe};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, PoisonError};

/// A scene and what the backends keep of it.
#[pyclass(name = "Scene", module = "slc._slc", frozen)]
pub struct PyScene {
    scene: Scene,
    /// Locked for the whole of a call (without the GIL): calls on one scene from several
    /// threads wait for each other.
    loaded: Mutex<Loaded>,
}

/// A whole frame (`Scene.render`).
struct RenderJob<'a> {
    options: &'a Options,
}

impl Job for RenderJob<'_> {
    type Output = FrameData;
    fn run<R: CpuFrames>(self, on: On<'_, R>) -> Result<FrameData, String> {
        let s = &self.options.settings;
        let frame =
            slc_core::render_loaded(on.r, on.scene, on.loaded, s, on.progress).map_err(message)?;
        FrameData::new(on.r, on.scene, s, frame)
    }
}

/// Every strategy on one prepared frame, with metrics, and the all-VPL reference
/// (`Scene.compare`).
struct CompareJob<'a> {
    options: &'a Options,
    base: Stochastic,
    /// The strategies to compare; `None`: every one the backend runs.
    strategies: Option<&'a [Strategy]>,
    reference: bool,
    /// The call's pixel-passes, set once the strategies are known.
    total: &'a AtomicU64,
}

impl Job for CompareJob<'_> {
    type Output = Vec<(&'static str, FrameData)>;
    fn run<R: CpuFrames>(self, on: On<'_, R>) -> Result<Self::Output, String> {
        let (r, scene, progress) = (on.r, on.scene, on.progress);
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
                vpl_count: p.vpl_count().map_err(message)?,
                timings,
                gpu_timings,
                metrics,
                sampled_lights: None,
                readback_bytes: None,
            })
        };
        let all: Vec<Strategy> = Strategy::every()
            .filter(|&s| r.capabilities().runs(s))
            .collect();
        let strategies = self.strategies.unwrap_or(&all);
        let frames = strategies.len() + usize::from(self.reference);
        let pixels = u64::from(settings.width) * u64::from(settings.height);
        self.total.store(pixels * frames as u64, Ordering::Relaxed);
        let p = on.prepare(settings)?;
        let mut out = Vec::new();
        if self.reference {
            let cpu_p = r.cpu_frame(scene, on.bvh, &p).map_err(message)?;
            let cpu = slc_cpu_ref::CpuRenderer::default();
            let input = cpu_input(scene, &cpu_p, seed, visibility);
            let reference = all_vpl_reference(input, progress)?;
            let preparation = (p.timings().clone(), p.gpu_timings().cloned());
            let f = frame(&p, reference, preparation, None)?;
            let s = with(Method::VplReference);
            out.push(("reference_vpl", FrameData::new(&cpu, scene, &s, f)?));
        }
        let input = ShadeInput {
            scene,
            loaded: on.loaded,
            prepared: &p,
            seed,
            visibility,
        };
        for &strategy in strategies {
            let st = Stochastic {
                strategy,
                metrics: true,
                ..self.base
            };
            let shaded = st.shade(r, input, progress).map_err(message)?;
            let timings = frame_timings(&p, &shaded);
            let f = frame(&p, shaded.indirect, timings, shaded.metrics)?;
            let s = with(Method::Stochastic(st));
            out.push((strategy.name(), FrameData::new(r, scene, &s, f)?));
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
    fn run<R: CpuFrames>(self, on: On<'_, R>) -> Result<VplColumns, String> {
        let p = on.prepare(&self.options.settings)?;
        let mut c = VplColumns::default();
        for v in p.vpls().map_err(message)? {
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
    fn run<R: CpuFrames>(self, on: On<'_, R>) -> Result<LightLists, String> {
        let settings = &self.options.settings;
        let p = on.prepare(settings)?;
        let cpu_p = on.r.cpu_frame(on.scene, on.bvh, &p).map_err(message)?;
        let s = self.stochastic;
        slc_cpu_ref::CpuRenderer::default()
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
    fn new(scene: Scene) -> Self {
        Self {
            scene,
            loaded: Mutex::default(),
        }
    }

    /// Runs `job` on the options' backend ([`watched`]: off the calling thread, stopped by
    /// Ctrl-C, its progress reported), after checking the scene can be rendered and the frame
    /// fits in memory; `total` is the call's pixel-passes.
    fn run<J: Job + Send>(
        &self,
        py: Python<'_>,
        options: &Options,
        total: &AtomicU64,
        job: J,
    ) -> PyResult<J::Output>
    where
        J::Output: Send,
    {
        slc_app::limits::check_frames(&self.scene, std::slice::from_ref(&options.settings))
            .map_err(error)?;
        let reporter = Reporter {
            callback: options.progress.as_ref(),
            total,
        };
        watched(py, reporter, |progress| {
            let mut loaded = self.loaded.lock().unwrap_or_else(PoisonError::into_inner);
            loaded.run(options, &self.scene, job, progress)
        })
    }

    /// A copy of this scene changed by `change`, which says what it set for the reports'
    /// warnings; the copy is loaded anew on its first render.
    fn changed(&self, change: impl FnOnce(&mut Scene) -> Result<String, String>) -> PyResult<Self> {
        let mut scene = self.scene.clone();
        let what = change(&mut scene).map_err(PyValueError::new_err)?;
        // Reports say the scene is not its files' alone.
        scene.report.warnings.push(format!("{what} from Python"));
        Ok(Self::new(scene))
    }
}

#[pymethods]
impl PyScene {
    /// A scene from a `.gltf`/`.glb`/`.obj` file, a `.toml` scene-settings file or a built-in
    /// name.
    #[new]
    fn py_new(spec: &str) -> PyResult<Self> {
        Ok(Self::new(load_scene(spec).map_err(error)?))
    }

    /// A scene from a file (`.gltf`, `.glb`, `.obj` or a `.toml` scene-settings file).
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        let scene = load_scene(&path).map_err(error)?;
        Ok(Self::new(scene))
    }

    /// A built-in scene.
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        let scene = slc_core::builtin(name).ok_or_else(|| {
            error(format!(
                "unknown built-in scene '{name}'; built-in scenes: {}",
                slc_core::BUILTIN_NAMES.join(", ")
            ))
        })?;
        Ok(Self::new(scene))
    }

    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    #[getter]
    fn triangles(&self) -> usize {
        self.scene.triangle_count()
    }

    /// The lights as settings-file tables.
    #[getter]
    fn lights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let tables = self
            .scene
            .lights
            .iter()
            .map(|l| table_to_py(py, &light_table(l)))
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, tables)
    }

    /// The camera as a settings-file table, or `None` (the renderer frames the scene).
    #[getter]
    fn camera<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        self.scene
            .camera
            .as_ref()
            .map(|c| table_to_py(py, &camera_table(c)))
            .transpose()
    }

    #[getter]
    fn materials(&self) -> Vec<String> {
        self.scene
            .materials
            .iter()
            .map(|m| m.name.clone())
            .collect()
    }

    #[getter]
    fn loads(&self) -> usize {
        self.loaded
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .loads()
    }

    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.report.warnings.clone()
    }

    #[getter]
    fn source(&self) -> Option<std::path::PathBuf> {
        self.scene.source.clone()
    }

    /// Every file the scene was read from.
    #[getter]
    fn files(&self) -> Vec<std::path::PathBuf> {
        self.scene.report.files.clone()
    }

    /// A copy with the materials `pattern` matches overridden, as a settings file's
    /// `[[materials]]` entry.
    #[pyo3(signature = (pattern, kd, f0, alpha, roughness, eta, double_sided, anisotropy_strength, anisotropy_rotation))]
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
        self.changed(|scene| {
            scene.override_materials(std::slice::from_ref(&o))?;
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
            Ok(format!(
                "materials '{pattern}' overridden: {}",
                set.join(", ")
            ))
        })
    }

    /// A copy with the camera a settings file's `[camera]` table gives.
    fn with_camera(&self, camera: &Bound<'_, PyDict>) -> PyResult<Self> {
        let camera = camera_from_table(table("camera", camera.items().as_any())?)
            .map_err(|e| PyValueError::new_err(format!("camera: {e}")))?;
        self.changed(|scene| {
            scene.camera = Some(camera);
            Ok("camera set".to_string())
        })
    }

    /// A copy whose lights are `lights` (settings-file `[[lights]]` tables), in place of the
    /// scene's (`replace`) or after them.
    fn with_lights(&self, lights: &Bound<'_, PyAny>, replace: bool) -> PyResult<Self> {
        let lights = lights
            .try_iter()?
            .enumerate()
            .map(|(i, light)| {
                let key = format!("lights[{i}]");
                let light = light?;
                let d = light.cast::<PyDict>().map_err(|_| {
                    pyo3::exceptions::PyTypeError::new_err(format!("{key}: expected a dict"))
                })?;
                light_from_table(table(&key, d.items().as_any())?)
                    .map_err(|e| PyValueError::new_err(format!("{key}: {e}")))
            })
            .collect::<PyResult<Vec<_>>>()?;
        if replace && lights.is_empty() {
            return Err(PyValueError::new_err(
                "lights: replacing the lights by none would leave the scene without light",
            ));
        }
        let count = lights.len();
        self.changed(|scene| {
            if replace {
                scene.lights.clear();
            }
            scene.lights.extend(lights);
            Ok(format!(
                "{count} light(s) {}",
                if replace { "set" } else { "added" }
            ))
        })
    }

    #[pyo3(signature = (**options))]
    fn render(&self, py: Python<'_>, options: Option<&Bound<'_, PyDict>>) -> PyResult<PyFrame> {
        let options = Options::parse(options, RENDER)?;
        let s = &options.settings;
        let total = AtomicU64::new(u64::from(s.width) * u64::from(s.height) * u64::from(s.spp));
        let data = self.run(py, &options, &total, RenderJob { options: &options })?;
        PyFrame::new(py, data)
    }

    #[pyo3(signature = (culling, reference, **options))]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        culling: Option<&Bound<'py, PyAny>>,
        reference: bool,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let parsed = Options::parse(options, COMPARE)?;
        let strategies = strategies(culling)?;
        let total = AtomicU64::new(0);
        let job = CompareJob {
            options: &parsed,
            base: Options::stochastic(options, COMPARE)?,
            strategies: strategies.as_deref(),
            reference,
            total: &total,
        };
        let frames = self.run(py, &parsed, &total, job)?;
        let out = PyDict::new(py);
        for (name, data) in frames {
            out.set_item(name, PyFrame::new(py, data)?)?;
        }
        Ok(out)
    }

    #[pyo3(signature = (**options))]
    fn vpls<'py>(
        &self,
        py: Python<'py>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let options = Options::parse(options, FRAME)?;
        let total = AtomicU64::new(0);
        let c = self.run(py, &options, &total, VplsJob { options: &options })?;
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

    #[pyo3(signature = (**options))]
    fn light_lists<'py>(
        &self,
        py: Python<'py>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let parsed = Options::parse(options, LISTS)?;
        let job = ListsJob {
            options: &parsed,
            stochastic: Options::stochastic(options, LISTS)?,
        };
        let total = AtomicU64::new(0);
        let lists = self.run(py, &parsed, &total, job)?;
        let s = &parsed.settings;
        let out = PyDict::new(py);
        out.set_item("offsets", PyArray1::from_vec(py, lists.offsets))?;
        out.set_item("indices", PyArray1::from_vec(py, lists.indices))?;
        let shape = [s.height as usize, s.width as usize];
        // Without second lists every pixel's shared list is NO_LIST.
        let shared = match lists.shared_list.is_empty() {
            true => vec![NO_LIST; lists.pixel_list.len()],
            false => lists.shared_list,
        };
        let pixels: Bound<'py, PyArray2<u32>> =
            PyArray1::from_vec(py, lists.pixel_list).reshape(shape)?;
        let shared: Bound<'py, PyArray2<u32>> = PyArray1::from_vec(py, shared).reshape(shape)?;
        out.set_item("lists", pixels)?;
        out.set_item("shared", shared)?;
        out.set_item("NO_LIST", NO_LIST)?;
        Ok(out)
    }
}
