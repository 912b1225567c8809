//! `slc._slc`, the native module of the Python package: scenes loaded once and rendered many
//! times (`scene`), frames as numpy arrays with their `report.json` as a dict (`frame`),
//! options from keyword arguments (`options`), camera and lights as settings-file tables
//! (`tables`), work off the calling thread that Ctrl-C stops (`watch`). It wraps the library
//! (the renderer API of `slc-core` on `slc-cpu-ref` and `slc-gpu-wgpu`), not the command
//! line; the Python layer (`slc/*.py`) documents the options and fills in their defaults.
mod backend;
mod frame;
mod options;
mod scene;
mod tables;
mod watch;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    slc,
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
    // numpy's C API is fetched on first use; fetched here, at import, a Ctrl-C during a
    // render cannot interrupt the fetch (it raised a PanicException there).
    numpy::PyArray1::<f32>::zeros(m.py(), 0, false);
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
    m.add("BUILTIN_SCENES", slc_core::BUILTIN_NAMES.to_vec())?;
    let methods = pyo3::types::PyDict::new(m.py());
    for (method, names) in [
        ("render", options::RENDER),
        ("compare", options::COMPARE),
        ("vpls", options::FRAME),
        ("light_lists", options::LISTS),
    ] {
        methods.set_item(method, names.to_vec())?;
    }
    // What the native methods take, checked against `slc/_options.py` by the tests.
    m.add("OPTION_NAMES", methods)?;
    Ok(())
}
