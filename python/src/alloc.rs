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
use ndarray::ArrayViewMutD;
use numpy::npyffi::{PY_ARRAY_API, npy_intp};
use numpy::{Element, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;

/// A result array just allocated by [`zeros`], not yet seen by Python:
/// its elements are lent to Rust without numpy's borrow tracking (a
/// hash-map insertion and removal per array, about 5 % of a small call,
/// issue 50). Sound because nothing else can reach the array: this value
/// holds the only reference until [`Fresh::into_any`] hands it to Python,
/// and `&mut self` makes each loan exclusive.
pub struct Fresh<'py, T>(Bound<'py, PyArrayDyn<T>>);

impl<'py, T: Element> Fresh<'py, T> {
    /// The elements in C order.
    pub fn slice_mut(&mut self) -> &mut [T] {
        // SAFETY: the array is C-contiguous (`PyArray_Zeros`, `fortran`
        // 0) and no other reference to it exists (type documentation).
        #[allow(unsafe_code)]
        let slice = unsafe { self.0.as_slice_mut() };
        slice.unwrap_or_default()
    }

    /// The elements as an array view.
    pub fn view_mut(&mut self) -> ArrayViewMutD<'_, T> {
        // SAFETY: as for `slice_mut`.
        #[allow(unsafe_code)]
        unsafe {
            self.0.as_array_mut()
        }
    }

    /// The array, for Python.
    pub fn into_any(self) -> Bound<'py, PyAny> {
        self.0.into_any()
    }
}

/// A new C-ordered array of zeros of `shape` and element type `T`.
pub fn zeros<'py, T: Element>(py: Python<'py>, shape: &[usize]) -> PyResult<Fresh<'py, T>> {
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
    Ok(Fresh(array.cast_into::<PyArrayDyn<T>>()?))
}
