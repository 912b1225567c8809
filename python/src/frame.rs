//! A rendered frame for Python: the images as H×W×3 float32 numpy arrays (linear radiance),
//! the per-pixel light counts and false discovery rates where culling metrics were measured,
//! and the frame's `report.json` (the same content `slc render` writes) as a dict.
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use slc_app::report::{FrameFacts, Report};
use slc_core::frame::{RenderSettings, RenderedFrame};
use slc_core::{CullMetrics, Image, Renderer, Scene};

/// A frame computed without the GIL, before it becomes Python objects.
pub struct FrameData {
    direct: Image,
    indirect: Image,
    total: Image,
    metrics: Option<CullMetrics>,
    /// `report.json`'s content.
    report: String,
}

impl FrameData {
    /// The frame `r` rendered of `scene` (named by `spec`) with `settings`.
    pub fn new<R: Renderer>(
        r: &R,
        scene: &Scene,
        spec: Option<&str>,
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
            spec,
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
        Ok(Self {
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
        })
    }
}

#[pymethods]
impl PyFrame {
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
