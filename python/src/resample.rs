//! `resample`: the spline interpolant of a float64 or float32 array on a
//! tensor grid of points, one coordinate vector per axis (scipy's `zoom`
//! and `shift`), by the engine's separable evaluation
//! ([`Interpolant::resample_grid`]: `degree + 1` multiply-adds per output
//! sample and axis), optionally a partial derivative.

use crate::error::{engine_error, value_error};
use crate::pool::run_with;
use numpy::{
    Element, PyArrayDyn, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArrayDyn,
};
use pyo3::prelude::*;
use splinelab::ndimage::interpolant::PointRule;
use splinelab::prelude::*;

/// The interpolant (from samples, or from coefficients when `prefilter` is
/// false) evaluated on the grid; the result has one axis per vector.
fn resample_generic<'py, T>(
    py: Python<'py>,
    input: PyReadonlyArrayDyn<'py, T>,
    coordinates: Vec<PyReadonlyArray1<'py, f64>>,
    opts: Options,
    prefilter: bool,
    deriv: Vec<u32>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyArrayDyn<T>>>
where
    T: Real + Copy + Element + Send + Sync,
{
    let data = input.as_array();
    let axes: Vec<&[f64]> = coordinates
        .iter()
        .map(|c| c.as_slice())
        .collect::<Result<_, _>>()?;
    let shape: Vec<usize> = axes.iter().map(|x| x.len()).collect();
    // numpy's allocation (huge pages where it can) for the result; one it
    // cannot allocate is `MemoryError`.
    let result = crate::alloc::zeros::<T>(py, &shape)?;
    let mut view = result.readwrite();
    let out = view.as_slice_mut()?;
    let run = || {
        let f = crate::interp::interpolant(&data, opts, prefilter)?;
        f.resample_grid(&axes, &deriv, out)
    };
    py.detach(|| run_with(threads, run))?
        .map_err(engine_error)?;
    drop(view);
    Ok(result)
}

/// The float64 and float32 entry points, one generic body.
macro_rules! resample_fn {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        #[pyfunction]
        #[pyo3(signature = (input, coordinates, degree, mode, cval, tol, prefilter, deriv, threads, nan_policy="propagate"))]
        #[allow(clippy::too_many_arguments)]
        pub fn $name<'py>(
            py: Python<'py>,
            input: PyReadonlyArrayDyn<'py, $t>,
            coordinates: Vec<PyReadonlyArray1<'py, f64>>,
            degree: u32,
            mode: &str,
            cval: f64,
            tol: Option<f64>,
            prefilter: bool,
            deriv: Vec<u32>,
            threads: Option<usize>,
            nan_policy: &str,
        ) -> PyResult<Bound<'py, PyArrayDyn<$t>>> {
            let opts = crate::interp::options(degree, mode, cval, tol, nan_policy)?;
            resample_generic(py, input, coordinates, opts, prefilter, deriv, threads)
        }
    };
}

resample_fn!(
    resample_f64,
    f64,
    "Values of the float64 interpolant on the grid of per-axis coordinate vectors."
);
resample_fn!(
    resample_f32,
    f32,
    "Values of the float32 interpolant (computed in float32) on the grid of per-axis coordinate vectors."
);

/// The interpolant at the points `matrix · o + offset (+ shift)` of every
/// index `o` of an output of `out_shape` ([`Interpolant::resample_affine`]:
/// generated block by block, no coordinate array).
#[allow(clippy::too_many_arguments)]
fn affine_generic<'py, T>(
    py: Python<'py>,
    input: PyReadonlyArrayDyn<'py, T>,
    matrix: PyReadonlyArray2<'py, f64>,
    offset: PyReadonlyArray1<'py, f64>,
    out_shape: Vec<usize>,
    opts: Options,
    prefilter: bool,
    shift: f64,
    rule: &str,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyArrayDyn<T>>>
where
    T: Real + Copy + Element + Send + Sync,
{
    let rule = match rule {
        "fold" => PointRule::Fold,
        "cval-outside" => PointRule::CvalOutside,
        "wrap" => PointRule::WrapPeriodNMinus1,
        other => return Err(value_error(format!("unknown point rule {other:?}"))),
    };
    let data = input.as_array();
    let m = matrix.as_array();
    let m = m.as_standard_layout();
    let m = m
        .as_slice()
        .ok_or_else(|| value_error("matrix must be C-contiguous"))?;
    let offset = offset.as_slice()?;
    let result = crate::alloc::zeros::<T>(py, &out_shape)?;
    let mut view = result.readwrite();
    let out = view.as_slice_mut()?;
    let run = || {
        let f = crate::interp::interpolant(&data, opts, prefilter)?;
        f.resample_affine(m, offset, &out_shape, shift, rule, out)
    };
    py.detach(|| run_with(threads, run))?
        .map_err(engine_error)?;
    drop(view);
    Ok(result)
}

/// The float64 and float32 affine entry points, one generic body.
macro_rules! affine_fn {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        #[pyfunction]
        #[pyo3(signature = (input, matrix, offset, out_shape, degree, mode, cval, tol, prefilter, shift, rule, threads, nan_policy="propagate"))]
        #[allow(clippy::too_many_arguments)]
        pub fn $name<'py>(
            py: Python<'py>,
            input: PyReadonlyArrayDyn<'py, $t>,
            matrix: PyReadonlyArray2<'py, f64>,
            offset: PyReadonlyArray1<'py, f64>,
            out_shape: Vec<usize>,
            degree: u32,
            mode: &str,
            cval: f64,
            tol: Option<f64>,
            prefilter: bool,
            shift: f64,
            rule: &str,
            threads: Option<usize>,
            nan_policy: &str,
        ) -> PyResult<Bound<'py, PyArrayDyn<$t>>> {
            let opts = crate::interp::options(degree, mode, cval, tol, nan_policy)?;
            affine_generic(
                py, input, matrix, offset, out_shape, opts, prefilter, shift, rule, threads,
            )
        }
    };
}

affine_fn!(
    affine_f64,
    f64,
    "Values of the float64 interpolant at the points of an affine map of an output grid."
);
affine_fn!(
    affine_f32,
    f32,
    "Values of the float32 interpolant (computed in float32) at the points of an affine map of an output grid."
);
