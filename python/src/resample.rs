//! `resample`: the spline interpolant of an array on a tensor grid of
//! points, one coordinate vector per axis (scipy's `zoom` and `shift`), by
//! the engine's separable evaluation ([`Interpolant::resample_grid_as`]:
//! `degree + 1` multiply-adds per output sample and axis), optionally a
//! partial derivative; and `affine`: at the points of an affine map of an
//! output grid ([`Interpolant::resample_affine_as`]). Both compute in
//! float64 from float64 or float32 samples and store float64 or float32
//! results (`out32`, each rounded once), or with `f32` float32 samples in
//! float32 (the `compute="float32"` opt-in).

use crate::error::engine_error;
use crate::interp::{Coefficients, interpolant, options, work_ns};
use crate::scipy_mode::point_rule;
use ndarray::ArrayViewD;
use numpy::{Element, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use splinelab::ndimage::interpolant::PointRule;
use splinelab::ndimage::samples::{Sample, Stored};
use splinelab::prelude::*;

/// The interpolant evaluated on the grid; the result (numpy's allocation,
/// huge pages where it can) has one axis per vector.
#[allow(clippy::too_many_arguments)]
fn resample_generic<'py, T, E, O>(
    py: Python<'py>,
    data: ArrayViewD<'_, E>,
    coordinates: &[PyReadonlyArray1<'py, f64>],
    opts: Options,
    how: Coefficients,
    deriv: &[u32],
    threads: Option<usize>,
    cval_outside: bool,
) -> PyResult<Bound<'py, PyAny>>
where
    T: Real + Copy + Send + Sync,
    E: Sample<T>,
    O: Stored<T> + Element,
{
    let axes: Vec<&[f64]> = coordinates
        .iter()
        .map(|c| c.as_slice())
        .collect::<Result<_, _>>()?;
    let shape: Vec<usize> = axes.iter().map(|x| x.len()).collect();
    // numpy's allocation (huge pages where it can); one it cannot
    // allocate is `MemoryError`, as scipy's.
    let result = crate::alloc::zeros::<O>(py, &shape)?;
    let mut view = result.readwrite();
    let out = view.as_slice_mut()?;
    // Separable: `degree + 1` multiply-adds per output sample and axis.
    let taps = (out.len() * axes.len()) as f64 * (f64::from(opts.degree) + 1.0);
    let work = work_ns(data.shape(), &opts, how, taps);
    let run = || {
        let f = interpolant::<T, E>(&data, opts, how)?;
        f.resample_grid_as(&axes, deriv, out)?;
        if cval_outside {
            // 0 for a derivative, as the constant beyond the grid has.
            let fill = if deriv.iter().any(|&k| k > 0) {
                0.0
            } else {
                opts.cval
            };
            fill_outside(out, &axes, data.shape(), O::store(&T::from_f64_exact(fill)));
        }
        Ok(())
    };
    crate::pool::run_detached(py, threads, work, run)?.map_err(engine_error)?;
    drop(view);
    Ok(result.into_any())
}

/// scipy's `constant` on a grid: `fill` in every slab of `out` (the grid's
/// values, C order) whose coordinate on some axis lies outside `[0, n − 1]`
/// of the input's `shape` (a NaN coordinate is not outside, as numpy's
/// comparisons have it).
fn fill_outside<O: Clone>(out: &mut [O], axes: &[&[f64]], shape: &[usize], fill: O) {
    let dims: Vec<usize> = axes.iter().map(|x| x.len()).collect();
    let Ok(mut grid) = ndarray::ArrayViewMutD::from_shape(dims, out) else {
        return;
    };
    for (a, (x, &n)) in axes.iter().zip(shape).enumerate() {
        let top = n as f64 - 1.0;
        for (i, &t) in x.iter().enumerate() {
            if t < 0.0 || t > top {
                grid.index_axis_mut(ndarray::Axis(a), i).fill(fill.clone());
            }
        }
    }
}

/// Values of the interpolant of `input` on the grid of per-axis coordinate
/// vectors: in float64 (float32 results with `out32`), or with `f32` in
/// float32 from a float32 array; with `cval_outside`, `cval` (0 for a
/// derivative) in the slabs of grid points outside the input on some axis
/// (scipy's `constant`).
#[pyfunction]
#[pyo3(signature = (input, coordinates, degree, mode, cval, tol, prefilter, deriv, threads, nan_policy="propagate", out32=false, filter_rule=None, f32=false, cval_outside=false))]
#[allow(clippy::too_many_arguments)]
pub fn resample<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    coordinates: Vec<PyReadonlyArray1<'py, f64>>,
    degree: u32,
    mode: &str,
    cval: f64,
    tol: Option<f64>,
    prefilter: bool,
    deriv: Vec<u32>,
    threads: Option<usize>,
    nan_policy: &str,
    out32: bool,
    filter_rule: Option<&str>,
    f32: bool,
    cval_outside: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let opts = options(degree, mode, cval, tol, nan_policy)?;
    let how = Coefficients::new(prefilter, filter_rule)?;
    let c = &coordinates;
    crate::dispatch_compute!(input, f32, out32, <T, O> a => {
        resample_generic::<T, _, O>(py, a, c, opts, how, &deriv, threads, cval_outside)
    })
}

/// Where the points of an affine resampling come from.
struct AffineMap<'a> {
    matrix: &'a [f64],
    offset: &'a [f64],
    out_shape: Vec<usize>,
    shift: f64,
    rule: PointRule,
}

impl<'a> AffineMap<'a> {
    fn new(
        matrix: &'a [f64],
        offset: &'a PyReadonlyArray1<'_, f64>,
        out_shape: Vec<usize>,
        shift: f64,
        rule: &str,
    ) -> PyResult<AffineMap<'a>> {
        let rule = point_rule(rule)?;
        Ok(AffineMap {
            matrix,
            offset: offset.as_slice()?,
            out_shape,
            shift,
            rule,
        })
    }
}

/// The interpolant at the points `matrix · o + offset (+ shift)` of every
/// index `o` of an output of `out_shape` ([`Interpolant::resample_affine_as`]:
/// generated block by block, no coordinate array).
fn affine_generic<'py, T, E, O>(
    py: Python<'py>,
    data: ArrayViewD<'_, E>,
    map: &AffineMap<'_>,
    opts: Options,
    how: Coefficients,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>>
where
    T: Real + Copy + Send + Sync,
    E: Sample<T>,
    O: Stored<T> + Element,
{
    let result = crate::alloc::zeros::<O>(py, &map.out_shape)?;
    let mut view = result.readwrite();
    let out = view.as_slice_mut()?;
    let taps = out.len() as f64 * (f64::from(opts.degree) + 1.0).powi(data.ndim() as i32);
    let work = work_ns(data.shape(), &opts, how, taps);
    let run = || {
        let f = interpolant::<T, E>(&data, opts, how)?;
        let m = map;
        f.resample_affine_as(m.matrix, m.offset, &m.out_shape, m.shift, m.rule, out)
    };
    crate::pool::run_detached(py, threads, work, run)?.map_err(engine_error)?;
    drop(view);
    Ok(result.into_any())
}

/// Values of the interpolant of `input` at the points of an affine map of
/// an output grid: in float64 (float32 results with `out32`), or with
/// `f32` in float32 from a float32 array.
#[pyfunction]
#[pyo3(signature = (input, matrix, offset, out_shape, degree, mode, cval, tol, prefilter, shift, rule, threads, nan_policy="propagate", out32=false, filter_rule=None, f32=false))]
#[allow(clippy::too_many_arguments)]
pub fn affine<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
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
    out32: bool,
    filter_rule: Option<&str>,
    f32: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let opts = options(degree, mode, cval, tol, nan_policy)?;
    let how = Coefficients::new(prefilter, filter_rule)?;
    let m = matrix.as_array();
    let m = m.as_standard_layout();
    let map = AffineMap::new(
        m.as_slice().unwrap_or_default(),
        &offset,
        out_shape,
        shift,
        rule,
    )?;
    crate::dispatch_compute!(input, f32, out32, <T, O> a => {
        affine_generic::<T, _, O>(py, a, &map, opts, how, threads)
    })
}
