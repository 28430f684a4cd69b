//! Rust errors as Python exceptions: a `ValueError` with the Rust message
//! (bad values: degree, mode, tolerance, shapes, non-finite data), a
//! `MemoryError` where a work array or a result cannot be allocated (as
//! scipy raises where numpy cannot allocate its output), and a degree the
//! engine cannot compute as `splinelab.errors.OrderError` (a `ValueError`
//! that is also scipy's `RuntimeError` for orders it does not support).

use pyo3::exceptions::{PyMemoryError, PyValueError};
use pyo3::types::{PyAnyMethods, PyType};
use pyo3::{PyErr, Python};
use splinelab::ndimage::NdimageError;

pyo3::create_exception!(
    splinelab._splinelab,
    NonFiniteCoordinateError,
    PyValueError,
    "A coordinate is NaN or infinite (the engine evaluates finite points only; the Python layer gives scipy's values there)."
);

/// Any displayable Rust error as a `ValueError` with its message.
pub fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// An engine error as a Python exception: a non-finite coordinate as
/// [`NonFiniteCoordinateError`] (a `ValueError` the Python layer catches to
/// reproduce scipy's values at such points), an allocation the allocator
/// refused as `MemoryError`, anything else as [`value_error`].
pub fn engine_error(e: NdimageError) -> PyErr {
    match e {
        NdimageError::NonFiniteCoordinate(_) => NonFiniteCoordinateError::new_err(e.to_string()),
        NdimageError::OutOfMemory { .. } => PyMemoryError::new_err(e.to_string()),
        NdimageError::Degree(_) | NdimageError::DegreeRange { .. } => {
            family_error("OrderError", e.to_string())
        }
        e => value_error(e),
    }
}

/// An exception of the class `name` of `splinelab.errors` (the classes
/// that derive from both scipy's exception and this package's), carrying
/// `message`; a `ValueError` should that module not import.
fn family_error(name: &str, message: String) -> PyErr {
    Python::attach(|py| {
        let class = py
            .import("splinelab.errors")
            .and_then(|m| m.getattr(name))
            .and_then(|c| c.cast_into::<PyType>().map_err(PyErr::from));
        match class {
            Ok(ty) => PyErr::from_type(ty, message),
            Err(_) => PyValueError::new_err(message),
        }
    })
}

/// A NaN policy by name (`ValueError` naming the three choices otherwise).
pub fn nan_policy(name: &str) -> Result<splinelab::prelude::NanPolicy, PyErr> {
    name.parse().map_err(value_error)
}
