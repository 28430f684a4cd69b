//! Results allocated by numpy, where a refusal is Python's `MemoryError`
//! (numpy's `_ArrayMemoryError`, as scipy raises for the same call) or
//! numpy's `ValueError` for a size beyond `intp`: `numpy.zeros` called
//! through Python. The `numpy` crate's `PyArray::zeros` panics instead
//! ("PyObject pointer is null", a `PanicException` that `except Exception`
//! does not catch). Same memory as before: numpy's allocator, which asks
//! for transparent huge pages and zeroes lazily.

use numpy::{Element, PyArrayDyn};
use pyo3::prelude::*;

/// A new C-ordered array of zeros of `shape` and element type `T`.
pub fn zeros<'py, T: Element>(
    py: Python<'py>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let numpy = py.import("numpy")?;
    let array = numpy.call_method1("zeros", (shape.to_vec(), numpy::dtype::<T>(py)))?;
    Ok(array.cast_into::<PyArrayDyn<T>>()?)
}
