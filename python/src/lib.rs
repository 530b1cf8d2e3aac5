//! `import honeycomb`: the library's front door for Python.
//!
//! Only translation: Python values into the front door's types ([`Surface`], [`BaseMesh`],
//! [`Options`], [`PipelineOptions`], a [`Progress`]) and an [`Outcome`] back as numpy arrays
//! and dicts. Keyword options go to [`Options`] through serde, so their names, defaults and
//! checks are the library's.

mod functions;
mod inputs;
mod progress;
mod result;
mod session;

use functions::{optimize, pipeline, read};
use honeycomb::Error;
use pyo3::exceptions::{
    PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;
use result::HoneycombResult;
use session::PyEditSession;

pyo3::create_exception!(
    honeycomb,
    Cancelled,
    pyo3::exceptions::PyException,
    "The progress callback returned False: the work stopped before its next iteration."
);

/// The library's error as the Python exception that fits it.
pub(crate) fn py_err(e: Error) -> PyErr {
    let message = e.to_string();
    match e {
        Error::Option { .. }
        | Error::Parameter(_)
        | Error::Mesh(_)
        | Error::Unsuited(_)
        | Error::Parse { .. } => PyValueError::new_err(message),
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(message)
        }
        Error::Io { .. } => PyOSError::new_err(message),
        Error::Cancelled => PyKeyboardInterrupt::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}

#[pymodule]
#[pyo3(name = "honeycomb")]
fn honeycomb_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pipeline, m)?)?;
    m.add_function(wrap_pyfunction!(optimize, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_class::<HoneycombResult>()?;
    m.add_class::<PyEditSession>()?;
    m.add("Cancelled", m.py().get_type::<Cancelled>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
