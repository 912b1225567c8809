//! The keyword options of `render`, `compare`, `Scene.vpls` and `Scene.light_lists`, with the
//! command line's defaults and names (`slc render --help`), parsed once here into the
//! library's [`RenderSettings`]. An unknown name or a value of the wrong type is a
//! `TypeError`; a value out of its domain is an `SlcError` from the library's own validation.
use crate::error;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt};
use slc_core::frame::counts::CAMERA_VSGLS;
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

/// What a frame is made of (the stubs' `FrameOptions`): the options of `Scene.vpls`.
pub const FRAME: &[&str] = &["width", "height", "backend", "seed", "rsm", "lobes"];
/// `Scene.light_lists` (`ListOptions`).
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
/// `Scene.compare` (`CompareOptions`): one pass, the strategies and the shader its own.
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
/// `Scene.render` and `slc.render` (`RenderOptions`): every option.
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
#[derive(Clone, Debug)]
pub struct Options {
    pub settings: RenderSettings,
    pub backend: Backend,
    /// The GPU's tiled strategies culled and shaded in one pass (`gpu_tiled="one-pass"`, the
    /// default) or through light lists (`"lists"`), as `--gpu-tiled`.
    pub one_pass: bool,
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

/// A typed option, with `key` named in the error: a `ValueError` for an integer out of the
/// type's range (a negative width, a seed above 2³² − 1), a `TypeError` for another type.
macro_rules! option {
    ($options:expr, $key:literal, $ty:ty, $default:expr) => {
        match given($options, $key)? {
            Some(v) => v.extract::<$ty>().map_err(|e| {
                let message = format!("{}: expected {}: {e}", $key, stringify!($ty));
                if v.is_instance_of::<PyInt>() && !v.is_instance_of::<PyBool>() {
                    PyValueError::new_err(message)
                } else {
                    PyTypeError::new_err(message)
                }
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

/// A culling strategy by name (`slc_core::Strategy`'s names), or a `ValueError` naming them.
pub fn strategy(name: &str) -> PyResult<Strategy> {
    name.parse()
        .map_err(|e: slc_core::UnknownStrategy| PyValueError::new_err(e.to_string()))
}

impl Options {
    /// Parses `options`, refusing names outside `allowed` ([`FRAME`], [`LISTS`], [`COMPARE`]
    /// or [`RENDER`]: an option that would have no effect is an error, not ignored). Every
    /// value is checked, whether or not the method uses it.
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
        let backend: String = option!(options, "backend", String, "cpu".into());
        let backend = choose(
            "backend",
            &backend,
            &[("cpu", Backend::Cpu), ("gpu", Backend::Gpu)],
        )?;
        let gpu_tiled: Option<String> = option!(options, "gpu_tiled", Option<String>, None);
        let one_pass = match gpu_tiled {
            None => true,
            Some(_) if backend != Backend::Gpu => {
                return Err(PyValueError::new_err(
                    "gpu_tiled chooses how the GPU backend culls; add backend='gpu'",
                ))
            }
            Some(t) => choose("gpu_tiled", &t, &[("one-pass", true), ("lists", false)])?,
        };
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
            one_pass,
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

    /// The method: a reference, VSGLs, or the stochastic estimate (every option of each
    /// parsed, so a bad value is refused whichever is chosen).
    fn method(options: Option<&Bound<'_, PyDict>>) -> PyResult<Method> {
        let stochastic = Self::stochastic(options)?;
        let sampling = Self::sampling(options)?;
        let shader: String = option!(options, "shader", String, "vpl".into());
        let reference: Option<String> = option!(options, "reference", Option<String>, None);
        let reference = reference
            .map(|r| {
                choose(
                    "reference",
                    &r,
                    &[("vpl", Method::VplReference), ("path", Method::Path)],
                )
            })
            .transpose()?;
        match (shader.as_str(), reference) {
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
    fn sampling(options: Option<&Bound<'_, PyDict>>) -> PyResult<LightSampling> {
        let importance: String = option!(options, "importance", String, "flux".into());
        // Checked whatever the importance, as the command line's --camera-vsgls is.
        let camera_vsgls = CAMERA_VSGLS
            .check(option!(options, "camera_vsgls", u32, 1024))
            .map_err(error)?;
        let diffuse: String = option!(options, "vsgl_diffuse", String, "clamped".into());
        Ok(LightSampling {
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
