//! The keyword options of `render`, `compare`, `Scene.vpls` and `Scene.light_lists`, with the
//! command line's defaults and names (`slc render --help`), parsed once here into the
//! library's [`RenderSettings`]. An unknown name or a value of the wrong type is a
//! `TypeError`; a value out of its domain is an `SlcError` from the library's own validation.
use crate::error;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slc_core::frame::{
    DiffuseEmission, Importance, LightSampling, LobeSelection, Method, RenderSettings, Stochastic,
};
use slc_core::Strategy;

/// Where a frame is rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    Cpu,
    Gpu,
}

/// Every option name, in the order the stubs document them.
pub const NAMES: [&str; 20] = [
    "width",
    "height",
    "backend",
    "culling",
    "delta",
    "interleave",
    "seed",
    "shader",
    "rsm",
    "lobes",
    "denoise",
    "visibility",
    "spp",
    "metrics",
    "reference",
    "vsgls",
    "importance",
    "camera_vsgls",
    "vsgl_diffuse",
    "progress",
];

/// Parsed options.
#[derive(Clone, Debug)]
pub struct Options {
    pub settings: RenderSettings,
    pub backend: Backend,
    /// Show progress bars on stderr.
    pub progress: bool,
}

/// The value of `key` in `options`, if given and not `None`.
fn given<'py>(
    options: Option<&Bound<'py, PyDict>>,
    key: &str,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    Ok(options
        .map(|d| d.get_item(key))
        .transpose()?
        .flatten()
        .filter(|v| !v.is_none()))
}

/// A typed option, with `key` named in the error.
macro_rules! option {
    ($options:expr, $key:literal, $ty:ty, $default:expr) => {
        match given($options, $key)? {
            Some(v) => v.extract::<$ty>().map_err(|e| {
                PyTypeError::new_err(format!("{}: expected {}: {e}", $key, stringify!($ty)))
            })?,
            None => $default,
        }
    };
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

/// A culling strategy by name (`slc_core::Strategy`'s names).
pub fn strategy(name: &str) -> PyResult<Strategy> {
    name.parse().map_err(error)
}

impl Options {
    /// Parses `options`, refusing names outside [`NAMES`] and those in `not_here` (an option
    /// the calling function takes as an argument of its own).
    pub fn parse(options: Option<&Bound<'_, PyDict>>, not_here: &[&str]) -> PyResult<Self> {
        if let Some(d) = options {
            for key in d.keys() {
                let key: String = key.extract()?;
                if !NAMES.contains(&key.as_str()) || not_here.contains(&key.as_str()) {
                    let known: Vec<&str> = NAMES
                        .into_iter()
                        .filter(|n| !not_here.contains(n))
                        .collect();
                    return Err(PyTypeError::new_err(format!(
                        "unknown option '{key}'; the options are {}",
                        known.join(", ")
                    )));
                }
            }
        }
        let backend: String = option!(options, "backend", String, "cpu".into());
        let backend = choose(
            "backend",
            &backend,
            &[("cpu", Backend::Cpu), ("gpu", Backend::Gpu)],
        )?;
        let lobes: String = option!(options, "lobes", String, "both".into());
        let lobes = choose(
            "lobes",
            &lobes,
            &[
                ("both", LobeSelection::Both),
                ("diffuse", LobeSelection::Diffuse),
                ("glossy", LobeSelection::Glossy),
            ],
        )?;
        let settings = RenderSettings {
            width: option!(options, "width", u32, 512),
            height: option!(options, "height", u32, 512),
            rsm_resolution: option!(options, "rsm", u32, 64),
            seed: option!(options, "seed", u32, 0),
            method: Self::method(options)?,
            visibility: option!(options, "visibility", bool, false),
            spp: option!(options, "spp", u32, 1),
            lobes,
        };
        settings.validate().map_err(error)?;
        Ok(Self {
            settings,
            backend,
            progress: option!(options, "progress", bool, false),
        })
    }

    /// The stochastic estimate's options (culling, δ, K, denoise, metrics).
    pub fn stochastic(options: Option<&Bound<'_, PyDict>>) -> PyResult<Stochastic> {
        let culling: String = option!(options, "culling", String, "ellipsoid".into());
        Ok(Stochastic {
            delta: option!(options, "delta", f32, 1e-3),
            strategy: strategy(&culling)?,
            interleave: option!(options, "interleave", u32, 8),
            denoise: option!(options, "denoise", bool, true),
            metrics: option!(options, "metrics", bool, false),
        })
    }

    /// The method: a reference, VSGLs, or the stochastic estimate.
    fn method(options: Option<&Bound<'_, PyDict>>) -> PyResult<Method> {
        let shader: String = option!(options, "shader", String, "vpl".into());
        let reference: Option<String> = option!(options, "reference", Option<String>, None);
        match (shader.as_str(), reference.as_deref()) {
            ("vpl", None) => Ok(Method::Stochastic(Self::stochastic(options)?)),
            ("vpl", Some(r)) => choose(
                "reference",
                r,
                &[("vpl", Method::VplReference), ("path", Method::Path)],
            ),
            ("vsgl", None) => {
                let importance: String = option!(options, "importance", String, "flux".into());
                let camera_vsgls = option!(options, "camera_vsgls", u32, 1024);
                let diffuse: String = option!(options, "vsgl_diffuse", String, "clamped".into());
                Ok(Method::Vsgl(LightSampling {
                    count: option!(options, "vsgls", u32, 1024),
                    importance: choose(
                        "importance",
                        &importance,
                        &[
                            ("flux", Importance::Flux),
                            ("bidirectional", Importance::Bidirectional { camera_vsgls }),
                        ],
                    )?,
                    diffuse: choose(
                        "vsgl_diffuse",
                        &diffuse,
                        &[
                            (DiffuseEmission::ClampedCosine.name(), DiffuseEmission::ClampedCosine),
                            (DiffuseEmission::Sg.name(), DiffuseEmission::Sg),
                        ],
                    )?,
                }))
            }
            ("vsgl", Some(_)) => Err(PyValueError::new_err(
                "reference renders every VPL or paths, not VSGLs: leave out shader='vsgl' or reference",
            )),
            (other, _) => Err(PyValueError::new_err(format!(
                "shader: '{other}' is not one of vpl, vsgl"
            ))),
        }
    }
}
