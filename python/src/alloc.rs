//! Results allocated by numpy, where a refusal is Python's `MemoryError`
//! (numpy's `_ArrayMemoryError`, as scipy raises for the same call) or
//! numpy's `ValueError` for a size beyond `intp`: numpy's own
//! `PyArray_Zeros`, the function behind `numpy.zeros`, called through its
//! C API. The `numpy` crate's `PyArray::zeros` panics instead ("PyObject
//! pointer is null", a `PanicException` that `except Exception` does not
//! catch); calling `numpy.zeros` through Python gives the same array but
//! costs a module lookup, a list and numpy's argument parsing, about a
//! tenth of a small call (issue 50). Same memory as `numpy.zeros`: numpy's
//! allocator, which asks for transparent huge pages and zeroes lazily.

use crate::error::value_error;
use numpy::npyffi::{PY_ARRAY_API, npy_intp};
use numpy::{Element, PyArrayDescrMethods, PyArrayDyn};
use pyo3::prelude::*;

/// A new C-ordered array of zeros of `shape` and element type `T`.
pub fn zeros<'py, T: Element>(
    py: Python<'py>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let mut dims = shape
        .iter()
        .map(|&n| npy_intp::try_from(n))
        .collect::<Result<Vec<npy_intp>, _>>()
        .map_err(|_| {
            value_error("array is too big; `arr.size * arr.dtype.itemsize` is larger than the maximum possible size.")
        })?;
    let descr = T::get_dtype(py).into_dtype_ptr();
    // numpy refuses more axes than it supports (ValueError), as
    // `numpy.zeros`. SAFETY: `dims` holds `shape.len()` extents
    // and outlives the call; `descr` is a new reference, which
    // `PyArray_Zeros` steals (also when it fails). It returns a new
    // reference or null with a Python exception set, which
    // `from_owned_ptr_or_err` takes.
    #[allow(unsafe_code)]
    let array = unsafe {
        let ptr = PY_ARRAY_API.PyArray_Zeros(
            py,
            shape.len() as std::os::raw::c_int,
            dims.as_mut_ptr(),
            descr,
            0,
        );
        Bound::from_owned_ptr_or_err(py, ptr)?
    };
    Ok(array.cast_into::<PyArrayDyn<T>>()?)
}
