//! Sylva's Python module, `sylva._sylva`: thin bindings over the library's pipelines. The
//! `sylva` package around it (`python/sylva`) gives them their Python shape: keyword
//! arguments, dicts, pandas frames and the Dask driver.
//!
//! Every long call lets go of the GIL, so Python threads (and Blender's interface) go on while
//! a tree grows. Every error becomes a `sylva.SylvaError` carrying Sylva's message.

mod city;
mod model;
mod street;

use pyo3::create_exception;
use pyo3::prelude::*;

create_exception!(
    _sylva,
    SylvaError,
    pyo3::exceptions::PyException,
    "Sylva cannot do what was asked; the message says which file, parameter or value, and what is allowed."
);

/// Any error as a `SylvaError` with its message (and its causes, as the CLI prints them).
pub(crate) fn error(e: impl std::fmt::Display) -> PyErr {
    SylvaError::new_err(e.to_string())
}

/// JSON text as Python objects (dicts, lists, numbers), through Python's own `json`.
pub(crate) fn to_python<'py>(
    py: Python<'py>,
    value: &serde_json::Value,
) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?
        .call_method1("loads", (value.to_string(),))
}

#[pymodule]
fn _sylva(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SylvaError", m.py().get_type::<SylvaError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    model::register(m)?;
    city::register(m)?;
    street::register(m)?;
    Ok(())
}
