//! A rendered frame for Python: the images as H×W×3 float32 numpy arrays (linear radiance),
//! the per-pixel light counts and false discovery rates where culling metrics were measured,
//! and the frame's `report.json` (the same content `slc render` writes) as a dict. It shows
//! itself in Jupyter (`_repr_png_`) and saves itself as an sRGB PNG or a layered EXR.
use crate::error;
use glam::Vec3;
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use slc_app::layers_exr::{write_layers_file, PixelMetrics};
use slc_app::output::to_srgb8;
use slc_app::report::{FrameFacts, Report};
use slc_core::frame::{RenderSettings, RenderedFrame};
use slc_core::{CullMetrics, Image, Renderer, Scene};
use std::path::{Path, PathBuf};

/// A frame computed without the GIL, before it becomes Python objects.
pub struct FrameData {
    direct: Image,
    indirect: Image,
    total: Image,
    metrics: Option<CullMetrics>,
    /// `report.json`'s content.
    report: String,
    /// Its provenance alone, for the header of a saved EXR.
    provenance: String,
}

impl FrameData {
    /// The frame `r` rendered of `scene` with `settings`.
    pub fn new<R: Renderer>(
        r: &R,
        scene: &Scene,
        settings: &RenderSettings,
        frame: RenderedFrame,
    ) -> Result<Self, String> {
        let total = frame.total();
        let images = [
            ("direct", &frame.direct),
            ("indirect", &frame.indirect),
            ("total", &total),
        ];
        let report = Report::new(&FrameFacts {
            device: &r.info(settings),
            scene,
            settings,
            method: settings.method,
            spp: settings.spp,
            vpl_count: frame.vpl_count,
            timings: std::slice::from_ref(&frame.timings),
            gpu_timings: frame.gpu_timings.as_ref(),
            metrics: frame.metrics.as_ref(),
            sampled_lights: frame.sampled_lights,
            images: &images,
            readback_bytes: frame.readback_bytes.as_ref(),
        });
        let json = |v| serde_json::to_string(v).map_err(|e| e.to_string());
        Ok(Self {
            provenance: json(&report.provenance)?,
            report: serde_json::to_string(&report).map_err(|e| e.to_string())?,
            direct: frame.direct,
            indirect: frame.indirect,
            total,
            metrics: frame.metrics,
        })
    }
}

/// One rendered frame.
#[pyclass(name = "Frame", module = "slc", frozen)]
pub struct PyFrame {
    /// Direct light, H×W×3 float32 (linear).
    #[pyo3(get)]
    direct: Py<PyArray3<f32>>,
    /// Indirect light (one bounce), H×W×3 float32.
    #[pyo3(get)]
    indirect: Py<PyArray3<f32>>,
    /// Direct plus indirect, H×W×3 float32.
    #[pyo3(get)]
    total: Py<PyArray3<f32>>,
    /// VPLs each pixel was shaded with, H×W uint32; `None` unless metrics were measured.
    #[pyo3(get)]
    lights: Option<Py<PyArray2<u32>>>,
    /// False discovery rate of each pixel's list, H×W float32; `None` unless metrics were
    /// measured.
    #[pyo3(get)]
    fdr: Option<Py<PyArray2<f32>>>,
    /// The frame's `report.json` as a dict.
    #[pyo3(get)]
    report: Py<PyAny>,
    /// The report's provenance as JSON, for saved EXRs.
    provenance: String,
}

/// `image` as an H×W×3 array.
fn rgb(py: Python<'_>, image: &Image) -> PyResult<Py<PyArray3<f32>>> {
    let flat: Vec<f32> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
    let (h, w) = (image.height as usize, image.width as usize);
    Ok(PyArray1::from_vec(py, flat).reshape([h, w, 3])?.unbind())
}

/// Row-major per-pixel values as an H×W array.
fn plane<T: numpy::Element + Copy>(
    py: Python<'_>,
    values: &[T],
    (w, h): (u32, u32),
) -> PyResult<Py<PyArray2<T>>> {
    Ok(PyArray1::from_slice(py, values)
        .reshape([h as usize, w as usize])?
        .unbind())
}

/// An H×W×3 array (as the frame holds it, or as its user changed it) as an image.
fn image_of(array: &Bound<'_, PyArray3<f32>>) -> PyResult<Image> {
    let &[h, w, 3] = array.shape() else {
        return Err(PyValueError::new_err(format!(
            "an image must be H×W×3, not {:?}",
            array.shape()
        )));
    };
    let values = array.to_vec()?;
    Ok(Image {
        width: w as u32,
        height: h as u32,
        pixels: values
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect(),
    })
}

/// PNG bytes of an 8-bit sRGB picture.
fn png_bytes(picture: &image::RgbImage) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    picture
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| format!("cannot encode a PNG: {e}"))?;
    Ok(png)
}

/// Writes `path` completely or not at all: `make` writes a hidden file beside it (created
/// first, so a folder that is not there is an `OSError`), which is renamed over `path` once
/// written.
fn write_whole(path: &Path, make: impl FnOnce(&Path) -> Result<(), String>) -> PyResult<()> {
    let name = path
        .file_name()
        .ok_or_else(|| PyValueError::new_err(format!("{}: not a file name", path.display())))?;
    let staged = path.with_file_name(format!(
        ".{}.slc-{}.tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let os_error = |e: std::io::Error| {
        PyErr::from(std::io::Error::new(
            e.kind(),
            format!("{}: {e}", path.display()),
        ))
    };
    std::fs::File::create(&staged).map_err(os_error)?;
    let written = make(&staged)
        .map_err(|e| error(format!("{}: {e}", path.display())))
        .and_then(|()| std::fs::rename(&staged, path).map_err(os_error));
    if written.is_err() {
        let _ = std::fs::remove_file(&staged);
    }
    written
}

impl PyFrame {
    /// The Python objects of `data` (with the GIL).
    pub fn new(py: Python<'_>, data: FrameData) -> PyResult<Self> {
        let size = (data.direct.width, data.direct.height);
        let m = data.metrics.as_ref();
        Ok(Self {
            direct: rgb(py, &data.direct)?,
            indirect: rgb(py, &data.indirect)?,
            total: rgb(py, &data.total)?,
            lights: m
                .map(|m| plane(py, &m.lights_per_pixel, size))
                .transpose()?,
            fdr: m.map(|m| plane(py, &m.fdr_per_pixel, size)).transpose()?,
            report: py
                .import("json")?
                .call_method1("loads", (data.report,))?
                .unbind(),
            provenance: data.provenance,
        })
    }

    /// The layer `name` of the frame.
    fn layer(&self, py: Python<'_>, name: &str) -> PyResult<Image> {
        let array = match name {
            "direct" => &self.direct,
            "indirect" => &self.indirect,
            "total" => &self.total,
            other => {
                return Err(PyValueError::new_err(format!(
                    "layer: '{other}' is not one of direct, indirect, total"
                )))
            }
        };
        image_of(array.bind(py))
    }
}

#[pymethods]
impl PyFrame {
    /// A preview for Jupyter and IPython: the total image as an 8-bit sRGB PNG, linear
    /// radiance clamped to [0, 1] (as `slc render`'s `total.png`).
    fn _repr_png_<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let total = self.layer(py, "total")?;
        let png = png_bytes(&to_srgb8(&total, 0.0)).map_err(error)?;
        Ok(PyBytes::new(py, &png))
    }

    /// Saves the frame, written completely or not at all, as its suffix says:
    ///
    /// - ``.png``: one layer (``layer``: ``"total"``, ``"direct"`` or ``"indirect"``) as
    ///   8-bit sRGB, the linear values times 2**``exposure`` clamped to [0, 1];
    /// - ``.exr``: every layer in one file for tev and scripts (``direct``, ``indirect``,
    ///   ``total``, linear float, and ``metrics`` with channels ``lights`` and ``fdr`` where
    ///   they were measured), the report's provenance in the header attribute
    ///   ``slc.provenance``; ``layer`` and ``exposure`` do not apply.
    ///
    /// Raises ``ValueError`` for another suffix or layer, ``OSError`` when the file cannot be
    /// put in place, ``SlcError`` when it cannot be encoded.
    #[pyo3(signature = (path, layer=None, exposure=0.0))]
    fn save(
        &self,
        py: Python<'_>,
        path: PathBuf,
        layer: Option<&str>,
        exposure: f32,
    ) -> PyResult<()> {
        let suffix = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match suffix.as_deref() {
            Some("png") => {
                if !exposure.is_finite() {
                    return Err(PyValueError::new_err(format!(
                        "exposure: {exposure} is not finite"
                    )));
                }
                let picture = to_srgb8(&self.layer(py, layer.unwrap_or("total"))?, exposure);
                write_whole(&path, |staged| {
                    picture
                        .save_with_format(staged, image::ImageFormat::Png)
                        .map_err(|e| format!("cannot write PNG: {e}"))
                })
            }
            Some("exr") => {
                if layer.is_some() || exposure != 0.0 {
                    return Err(PyValueError::new_err(
                        "an EXR holds every layer, linear: leave out layer and exposure",
                    ));
                }
                let [direct, indirect, total] =
                    ["direct", "indirect", "total"].map(|n| self.layer(py, n));
                let (direct, indirect, total) = (direct?, indirect?, total?);
                let images = [
                    ("direct", &direct),
                    ("indirect", &indirect),
                    ("total", &total),
                ];
                let lights = self
                    .lights
                    .as_ref()
                    .map(|l| l.bind(py).to_vec())
                    .transpose()?;
                let fdr = self.fdr.as_ref().map(|f| f.bind(py).to_vec()).transpose()?;
                let metrics = lights
                    .as_deref()
                    .zip(fdr.as_deref())
                    .map(|(lights, fdr)| PixelMetrics { lights, fdr });
                write_whole(&path, |staged| {
                    write_layers_file(staged, &images, metrics, &self.provenance)
                })
            }
            other => Err(PyValueError::new_err(format!(
                "save: give a .png or .exr path, not {}",
                other.map_or_else(|| "one without suffix".to_string(), |s| format!(".{s}"))
            ))),
        }
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let report = self.report.bind(py);
        Ok(format!(
            "<slc.Frame {}x{} of {} on {}>",
            report.get_item("width")?,
            report.get_item("height")?,
            report.get_item("scene")?,
            report.get_item("adapter")?
        ))
    }
}
