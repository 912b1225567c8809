//! The keyword options of `render`, `compare`, `Scene.vpls` and `Scene.light_lists`, parsed
//! once here into the library's [`RenderSettings`]. Their names, defaults and meanings are
//! documented in one place, `slc/_options.py`, which fills in every default before calling
//! the native module: here every option of the method must be given (the lists below are
//! checked against the Python table by the tests). An unknown or missing name or a value of
//! the wrong type is a `TypeError`; a value out of its range or an unknown name of a choice
//! a `ValueError`; a value the library refuses an `SlcError` from its own validation.
use crate::error;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyString};
use slc_app::backends::Backend;
use slc_core::frame::counts::CAMERA_VSGLS;
use slc_core::frame::{
    DiffuseEmission, Importance, LightSampling, LobeSelection, Method, RenderSettings, Stochastic,
};
use slc_core::Strategy;

/// What a frame is made of: the options of `Scene.vpls`.
pub const FRAME: &[&str] = &["width", "height", "backend", "seed", "rsm", "lobes"];
/// `Scene.light_lists`.
pub const LISTS: &[&str] = &[
    "width",
    "height",
    "backend",
    "seed",
    "rsm",
    "lobes",
    "culling",
    "delta",
    "interleave",
];
/// `Scene.compare`: one pass, the strategies and the shader its own.
pub const COMPARE: &[&str] = &[
    "width",
    "height",
    "backend",
    "gpu_tiled",
    "seed",
    "rsm",
    "lobes",
    "delta",
    "interleave",
    "denoise",
    "visibility",
    "progress",
];
/// `Scene.render` and `slc.render`: every option.
pub const RENDER: &[&str] = &[
    "width",
    "height",
    "backend",
    "gpu_tiled",
    "seed",
    "rsm",
    "lobes",
    "culling",
    "delta",
    "interleave",
    "denoise",
    "visibility",
    "spp",
    "progress",
    "shader",
    "metrics",
    "reference",
    "vsgls",
    "importance",
    "camera_vsgls",
    "vsgl_diffuse",
];

/// Parsed options.
#[derive(Debug)]
pub struct Options {
    pub settings: RenderSettings,
    pub backend: Backend,
    /// The GPU's tiled strategies culled and shaded in one pass (`gpu_tiled="one-pass"`, the
    /// default) or through light lists (`"lists"`), as `--gpu-tiled`.
    pub one_pass: bool,
    /// Called as `progress(done, total)` with the pixel-passes finished, if given.
    pub progress: Option<Py<PyAny>>,
}

/// The options of one call: a dict holding exactly the names of one of the lists above.
#[derive(Clone, Copy)]
pub struct Given<'a, 'py>(Option<&'a Bound<'py, PyDict>>);

impl<'py> Given<'_, 'py> {
    /// The value of `key`, `None` where it is absent or `None`.
    fn get(&self, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        Ok(self
            .0
            .map(|d| d.get_item(key))
            .transpose()?
            .flatten()
            .filter(|v| !v.is_none()))
    }

    /// The value of `key`, which must be given and not `None`.
    fn required(&self, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match (self.get(key)?, self.0.map(|d| d.contains(key)).transpose()?) {
            (Some(v), _) => Ok(v),
            (None, Some(true)) => Err(PyTypeError::new_err(format!(
                "{key}: expected a value, got None"
            ))),
            (None, _) => Err(PyTypeError::new_err(format!("missing option '{key}'"))),
        }
    }

    /// A whole number of `key` in 0..=2³²−1: a `TypeError` for a bool, a float or another
    /// type, a `ValueError` for an integer out of the range.
    fn count(&self, key: &str) -> PyResult<u32> {
        let v = self.required(key)?;
        if v.is_instance_of::<PyBool>() || v.is_instance_of::<PyFloat>() {
            return Err(type_error(key, "an int", &v));
        }
        v.extract::<u32>().map_err(|_| {
            if v.hasattr("__index__").unwrap_or(false) {
                PyValueError::new_err(format!("{key}: {v} is outside 0..={}", u32::MAX))
            } else {
                type_error(key, "an int", &v)
            }
        })
    }

    /// A real number of `key` (an int or a float, not a bool).
    fn real(&self, key: &str) -> PyResult<f32> {
        let v = self.required(key)?;
        if v.is_instance_of::<PyBool>() || v.is_instance_of::<PyString>() {
            return Err(type_error(key, "a number", &v));
        }
        v.extract::<f32>()
            .map_err(|_| type_error(key, "a number", &v))
    }

    /// A bool of `key` (`True` or `False`, not another truthy value).
    fn flag(&self, key: &str) -> PyResult<bool> {
        let v = self.required(key)?;
        v.extract::<bool>()
            .map_err(|_| type_error(key, "a bool", &v))
    }

    /// A string of `key`, `None` where it is absent or `None`.
    fn text(&self, key: &str) -> PyResult<Option<String>> {
        self.get(key)?
            .map(|v| {
                v.extract::<String>()
                    .map_err(|_| type_error(key, "a str", &v))
            })
            .transpose()
    }

    /// A string of `key`, which must be given.
    fn required_text(&self, key: &str) -> PyResult<String> {
        let v = self.required(key)?;
        v.extract::<String>()
            .map_err(|_| type_error(key, "a str", &v))
    }
}

/// `TypeError`: `key` wants `what`, got `v`'s type.
fn type_error(key: &str, what: &str, v: &Bound<'_, PyAny>) -> PyErr {
    let got = v
        .get_type()
        .name()
        .map_or_else(|_| "another type".to_string(), |n| n.to_string());
    PyTypeError::new_err(format!("{key}: expected {what}, got {got} ({v})"))
}

/// `value` as one of `choices` (name, value), or a `ValueError` listing them.
fn choose<T: Copy>(key: &str, value: &str, choices: &[(&str, T)]) -> PyResult<T> {
    choices
        .iter()
        .find(|(name, _)| *name == value)
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
            PyValueError::new_err(format!(
                "{key}: '{value}' is not one of {}",
                names.join(", ")
            ))
        })
}

/// A culling strategy by name (`slc_core::Strategy`'s names), or a `ValueError` naming them.
pub fn strategy(name: &str) -> PyResult<Strategy> {
    name.parse()
        .map_err(|e: slc_core::UnknownStrategy| PyValueError::new_err(e.to_string()))
}

/// The strategies of `compare(culling=...)`: a list (or other sequence) of names, not one
/// string; `None` for every strategy the backend runs.
pub fn strategies(culling: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<Strategy>>> {
    let Some(culling) = culling.filter(|c| !c.is_none()) else {
        return Ok(None);
    };
    if culling.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err(format!(
            "culling: expected a list of strategy names such as ['{culling}'], got the str \
             '{culling}'"
        )));
    }
    let names: Vec<String> = culling
        .extract()
        .map_err(|_| type_error("culling", "a list of strategy names", culling))?;
    names
        .iter()
        .map(|n| strategy(n))
        .collect::<PyResult<_>>()
        .map(Some)
}

impl Options {
    /// Parses `options`, refusing names outside `allowed` ([`FRAME`], [`LISTS`], [`COMPARE`]
    /// or [`RENDER`]: an option that would have no effect is an error, not ignored) and
    /// requiring each of them. Every value is checked, whether or not the method uses it.
    pub fn parse(options: Option<&Bound<'_, PyDict>>, allowed: &[&str]) -> PyResult<Self> {
        if let Some(d) = options {
            for key in d.keys() {
                let key: String = key.extract()?;
                if !allowed.contains(&key.as_str()) {
                    return Err(PyTypeError::new_err(format!(
                        "unknown option '{key}' here; the options are {}",
                        allowed.join(", ")
                    )));
                }
            }
        }
        let given = Given(options);
        let backend = choose(
            "backend",
            &given.required_text("backend")?,
            &Backend::ALL.map(|b| (b.name(), b)),
        )?;
        let one_pass = match given.text("gpu_tiled")? {
            None => true,
            Some(_) if backend != Backend::Gpu => {
                return Err(PyValueError::new_err(
                    "gpu_tiled chooses how the GPU backend culls; add backend='gpu'",
                ))
            }
            Some(t) => choose("gpu_tiled", &t, &[("one-pass", true), ("lists", false)])?,
        };
        let lobes = choose(
            "lobes",
            &given.required_text("lobes")?,
            &[
                ("both", LobeSelection::Both),
                ("diffuse", LobeSelection::Diffuse),
                ("glossy", LobeSelection::Glossy),
            ],
        )?;
        let uses = |key| allowed.contains(&key);
        let settings = RenderSettings {
            width: given.count("width")?,
            height: given.count("height")?,
            rsm_resolution: given.count("rsm")?,
            seed: given.count("seed")?,
            method: Self::method(given, allowed)?,
            visibility: uses("visibility") && given.flag("visibility")?,
            spp: if uses("spp") { given.count("spp")? } else { 1 },
            lobes,
        };
        settings.validate().map_err(error)?;
        let progress = match given.get("progress")? {
            None => None,
            Some(p) if p.is_instance_of::<PyBool>() && !p.is_truthy()? => None,
            Some(p) if p.is_callable() => Some(p.unbind()),
            Some(p) => {
                return Err(type_error(
                    "progress",
                    "a callable progress(done, total), False or None",
                    &p,
                ))
            }
        };
        Ok(Self {
            settings,
            backend,
            one_pass,
            progress,
        })
    }

    /// The stochastic estimate's options (culling, δ, K, denoise, metrics) among `allowed`:
    /// those a method does not take are the estimate's defaults (for `compare`, the strategies
    /// come from its own argument and metrics are always measured).
    pub fn stochastic(
        options: Option<&Bound<'_, PyDict>>,
        allowed: &[&str],
    ) -> PyResult<Stochastic> {
        let given = Given(options);
        let uses = |key| allowed.contains(&key);
        let strategy = match uses("culling") {
            true => strategy(&given.required_text("culling")?)?,
            false => Strategy::None,
        };
        Ok(Stochastic {
            delta: given.real("delta")?,
            strategy,
            interleave: given.count("interleave")?,
            denoise: !uses("denoise") || given.flag("denoise")?,
            metrics: uses("metrics") && given.flag("metrics")?,
        })
    }

    /// The method: a reference, VSGLs, or the stochastic estimate (every option of each
    /// parsed, so a bad value is refused whichever is chosen). Without `delta` (`vpls`, which
    /// prepares a frame and shades nothing) the method is the unculled estimate, which every
    /// backend runs.
    fn method(given: Given, allowed: &[&str]) -> PyResult<Method> {
        if !allowed.contains(&"delta") {
            return Ok(Method::Stochastic(Stochastic {
                delta: 1e-3,
                strategy: Strategy::None,
                interleave: 1,
                denoise: false,
                metrics: false,
            }));
        }
        let stochastic = Self::stochastic(given.0, allowed)?;
        if !allowed.contains(&"shader") {
            return Ok(Method::Stochastic(stochastic));
        }
        let sampling = Self::sampling(given)?;
        let reference = given
            .text("reference")?
            .map(|r| {
                choose(
                    "reference",
                    &r,
                    &[("vpl", Method::VplReference), ("path", Method::Path)],
                )
            })
            .transpose()?;
        match (given.required_text("shader")?.as_str(), reference) {
            ("vpl", None) => Ok(Method::Stochastic(stochastic)),
            ("vpl", Some(r)) => Ok(r),
            ("vsgl", None) => Ok(Method::Vsgl(sampling)),
            ("vsgl", Some(_)) => Err(PyValueError::new_err(
                "reference renders every VPL or paths, not VSGLs: leave out shader='vsgl' or \
                 reference",
            )),
            (other, _) => Err(PyValueError::new_err(format!(
                "shader: '{other}' is not one of vpl, vsgl"
            ))),
        }
    }

    /// The sampled lights' options (`shader="vsgl"`).
    fn sampling(given: Given) -> PyResult<LightSampling> {
        // Checked whatever the importance, as the command line's --camera-vsgls is.
        let camera_vsgls = CAMERA_VSGLS
            .check(given.count("camera_vsgls")?)
            .map_err(error)?;
        Ok(LightSampling {
            count: given.count("vsgls")?,
            importance: choose(
                "importance",
                &given.required_text("importance")?,
                &[
                    ("flux", Importance::Flux),
                    ("bidirectional", Importance::Bidirectional { camera_vsgls }),
                ],
            )?,
            diffuse: choose(
                "vsgl_diffuse",
                &given.required_text("vsgl_diffuse")?,
                &[
                    (
                        DiffuseEmission::ClampedCosine.name(),
                        DiffuseEmission::ClampedCosine,
                    ),
                    (DiffuseEmission::Sg.name(), DiffuseEmission::Sg),
                ],
            )?,
        })
    }
}
