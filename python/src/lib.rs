//! `slc._slc`, the native module of the Python package: scenes loaded once and rendered many
//! times ([`scene::PyScene`]), frames as numpy arrays with their `report.json` as a dict
//! ([`frame::PyFrame`]), options from keyword arguments ([`options::Options`]). It wraps the
//! library (the renderer API of `slc-core` on `slc-cpu-ref` and `slc-gpu-wgpu`), not the
//! command line.
mod backend;
mod frame;
mod options;
mod scene;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    _slc,
    SlcError,
    PyException,
    "An error of slc: a scene that cannot be loaded or rendered, settings out of their domain."
);

/// A library error as a Python exception with the library's message.
pub(crate) fn error(e: impl std::fmt::Display) -> PyErr {
    SlcError::new_err(e.to_string())
}

#[pymodule]
fn _slc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::PyScene>()?;
    m.add_class::<frame::PyFrame>()?;
    m.add("SlcError", m.py().get_type::<SlcError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add(
        "STRATEGIES",
        slc_core::Strategy::every()
            .map(|s| s.name())
            .collect::<Vec<_>>(),
    )?;
    Ok(())
}
