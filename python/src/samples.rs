//! The element types the float64 entry points read and write: samples of
//! float64 or float32 (read as they lie, any strides, widened exactly into
//! float64 by the engine as it reads them) and results of float64 or
//! float32 (rounded once from float64 as the engine stores them). The
//! Python layer passes native-order float64/float32 arrays (other dtypes
//! converted first).

/// `$body` with `$a` the input's read-only `ndarray` view of its own
/// element type (float64 or float32); a `TypeError` for another dtype.
#[macro_export]
macro_rules! with_samples {
    ($input:expr, $a:ident => $body:expr) => {{
        let input = $input;
        if let Ok(r) = input.extract::<numpy::PyReadonlyArrayDyn<'_, f64>>() {
            let $a = r.as_array();
            $body
        } else if let Ok(r) = input.extract::<numpy::PyReadonlyArrayDyn<'_, f32>>() {
            let $a = r.as_array();
            $body
        } else {
            Err($crate::samples::unsupported(input))
        }
    }};
}

/// The `TypeError` of an array the float64 entry points do not read.
pub fn unsupported(input: &pyo3::Bound<'_, pyo3::PyAny>) -> pyo3::PyErr {
    use pyo3::types::PyAnyMethods;
    let dtype = input
        .getattr("dtype")
        .and_then(|d| d.str().map(|s| s.to_string()))
        .unwrap_or_else(|_| "no dtype".into());
    pyo3::exceptions::PyTypeError::new_err(format!(
        "expected a native float64 or float32 array, got {dtype}"
    ))
}
