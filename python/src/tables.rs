//! Python values as TOML values and back, so a camera or light given as a dict is read by the
//! settings file's own code (`slc_core::settings_tables`) and shown in the same form: numbers
//! (numpy's included), strings, bools, sequences (lists, tuples, numpy arrays) and dicts.
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyMapping, PyString};
use toml::{Table, Value};

/// `value` as a TOML value, or a `TypeError` naming `key` and what it cannot be.
pub fn to_toml(key: &str, value: &Bound<'_, PyAny>) -> PyResult<Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        if let Ok(i) = value.extract::<i64>() {
            return Ok(Value::Integer(i));
        }
    }
    if value.is_instance_of::<PyString>() {
        return Ok(Value::String(value.extract()?));
    }
    if let Ok(mapping) = value.cast::<PyMapping>() {
        return Ok(Value::Table(table(key, mapping.items()?.as_any())?));
    }
    // Floats, and numpy's scalars of either kind.
    if value.is_instance_of::<PyFloat>()
        || (value.hasattr("__float__")? && !value.hasattr("__len__")?)
    {
        return Ok(Value::Float(value.extract()?));
    }
    if let Ok(items) = value.try_iter() {
        return items
            .map(|item| to_toml(key, &item?))
            .collect::<PyResult<Vec<_>>>()
            .map(Value::Array);
    }
    let kind = value.get_type().name()?;
    Err(PyTypeError::new_err(format!(
        "{key}: a {kind} is not a number, string, bool, sequence or dict"
    )))
}

/// The (key, value) pairs `items` (of a dict) as a TOML table; keys must be strings.
pub fn table(key: &str, items: &Bound<'_, PyAny>) -> PyResult<Table> {
    items
        .try_iter()?
        .map(|pair| {
            let (k, v): (Bound<PyAny>, Bound<PyAny>) = pair?.extract()?;
            let name: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{key}: the keys must be strings")))?;
            let value = to_toml(&format!("{key}.{name}"), &v)?;
            Ok((name, value))
        })
        .collect()
}

/// A TOML value as a Python value (arrays as lists, tables as dicts).
pub fn to_py<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        Value::Float(f) => f.into_pyobject(py)?.into_any(),
        Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        Value::Array(a) => PyList::new(
            py,
            a.iter()
                .map(|v| to_py(py, v))
                .collect::<PyResult<Vec<_>>>()?,
        )?
        .into_any(),
        Value::Table(t) => table_to_py(py, t)?.into_any(),
    })
}

/// A TOML table as a dict.
pub fn table_to_py<'py>(py: Python<'py>, t: &Table) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in t {
        d.set_item(k, to_py(py, v)?)?;
    }
    Ok(d)
}
