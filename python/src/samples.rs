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

/// `$body` in the compute type and result type asked for, with `$a` the
/// samples' view and `$T`, `$O` type names bound to the compute and result
/// types: with `f32`, float32 samples in float32 into float32 (the
/// `compute="float32"` opt-in; another dtype is the extraction's error);
/// else float64 from float64 or float32 samples ([`with_samples!`]) into
/// float32 with `out32`, float64 without. The one dispatch of the entry
/// points (`map_coordinates`, `resample`, `affine`, `filter`).
///
/// `optional $input` takes an `Option` of the input: `$a` is then an
/// `Option` of the view, `None` (of `$O` elements) where there is no input.
#[macro_export]
macro_rules! dispatch_compute {
    // `$narrow` in float32, else `$wide` in float64 into float32 or float64.
    (@types $f32:expr, $out32:expr, $T:ident, $O:ident, $narrow:expr, $wide:expr) => {
        if $f32 {
            type $T = f32;
            type $O = f32;
            $narrow
        } else if $out32 {
            type $T = f64;
            type $O = f32;
            $wide
        } else {
            type $T = f64;
            type $O = f64;
            $wide
        }
    };
    (optional $input:expr, $f32:expr, $out32:expr, <$T:ident, $O:ident> $a:ident => $body:expr) => {{
        let input: Option<&pyo3::Bound<'_, pyo3::PyAny>> = $input;
        $crate::dispatch_compute!(@types $f32, $out32, $T, $O,
            {
                let r = input
                    .map(|a| a.extract::<numpy::PyReadonlyArrayDyn<'_, f32>>())
                    .transpose()?;
                let $a = r.as_ref().map(|r| r.as_array());
                $body
            },
            match input {
                None => {
                    let $a: Option<ndarray::ArrayViewD<'_, $O>> = None;
                    $body
                }
                Some(input) => $crate::with_samples!(input, v => {
                    let $a = Some(v);
                    $body
                }),
            })
    }};
    ($input:expr, $f32:expr, $out32:expr, <$T:ident, $O:ident> $a:ident => $body:expr) => {{
        let input: &pyo3::Bound<'_, pyo3::PyAny> = $input;
        $crate::dispatch_compute!(@types $f32, $out32, $T, $O,
            {
                let r = input.extract::<numpy::PyReadonlyArrayDyn<'_, f32>>()?;
                let $a = r.as_array();
                $body
            },
            $crate::with_samples!(input, $a => $body))
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
