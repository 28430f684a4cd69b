//! `resample`: the spline interpolant of an array on a tensor grid of
//! points, one coordinate vector per axis (scipy's `zoom` and `shift`), by
//! the engine's separable evaluation ([`Interpolant::resample_grid_as`]:
//! `degree + 1` multiply-adds per output sample and axis), optionally a
//! partial derivative; and `affine`: at the points of an affine map of an
//! output grid ([`Interpolant::resample_affine_as`]). Both compute in
//! float64 from float64 or float32 samples and store float64 or float32
//! results (`out32`, each rounded once), or with `f32` float32 samples in
//! float32 (the `compute="float32"` opt-in).

use crate::coefficients::Coefficients;
use crate::common::{CommonCall, exact, may_be_local, per_axis};
use crate::error::engine_error;
use crate::interp::{interpolant, options, work_ns};
use crate::scipy_mode::point_rule;
use ndarray::ArrayViewD;
use numpy::{
    Element, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArray,
};
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
    axes: &[&[f64]],
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
    let shape: Vec<usize> = axes.iter().map(|x| x.len()).collect();
    // numpy's allocation (huge pages where it can); one it cannot
    // allocate is `MemoryError`, as scipy's.
    let mut result = crate::alloc::zeros::<O>(py, &shape)?;
    let out = result.slice_mut();
    // Separable: `degree + 1` multiply-adds per output sample and axis.
    let taps = (out.len() * axes.len()) as f64 * (f64::from(opts.degree) + 1.0);
    let work = work_ns(data.shape(), &opts, how, taps);
    let run = || {
        let f = interpolant::<T, E>(&data, opts, how)?;
        f.resample_grid_as(axes, deriv, out)?;
        if cval_outside {
            // 0 for a derivative, as the constant beyond the grid has.
            let fill = if deriv.iter().any(|&k| k > 0) {
                0.0
            } else {
                opts.cval
            };
            fill_outside(out, axes, data.shape(), O::store(&T::from_f64_exact(fill)));
        }
        Ok(())
    };
    crate::pool::run_detached(py, threads, work, run)?.map_err(engine_error)?;
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
    let axes: Vec<&[f64]> = coordinates
        .iter()
        .map(|c| c.as_slice())
        .collect::<Result<_, _>>()?;
    let c = &axes;
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
    let mut result = crate::alloc::zeros::<O>(py, &map.out_shape)?;
    let out = result.slice_mut();
    let taps = out.len() as f64 * (f64::from(opts.degree) + 1.0).powi(data.ndim() as i32);
    let work = work_ns(data.shape(), &opts, how, taps);
    let run = || {
        let f = interpolant::<T, E>(&data, opts, how)?;
        let m = map;
        f.resample_affine_as(m.matrix, m.offset, &m.out_shape, m.shift, m.rule, out)
    };
    crate::pool::run_detached(py, threads, work, run)?.map_err(engine_error)?;
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

/// `splinelab.shift`'s common call in one step (issue 50): the settings
/// of [`CommonCall`], a float64 or float32 array (exactly `numpy.ndarray`,
/// not empty), `shift` one real or one per axis ([`per_axis`]); the
/// shifted array in a new array of the input's dtype, as the full call
/// gives it (scipy's `NI_ZoomShift` coordinates `k + (-shift)`, the same
/// operation as numpy's in `_zoom_shift_coordinates`, then the separable
/// resampling). `None` for any other call (the Python layer's).
#[pyfunction]
pub fn shift_common<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    shift: &Bound<'py, PyAny>,
    settings: &Bound<'py, PyAny>,
) -> Option<Bound<'py, PyAny>> {
    grid_call(py, input, settings, &|_, shape| {
        let shifts = per_axis(shift, shape.len())?;
        let axes = shape.iter().zip(&shifts);
        Some(
            axes.map(|(&n, &s)| (0..n).map(|k| k as f64 + -s).collect())
                .collect(),
        )
    })
}

/// Per-axis coordinate vectors of a grid call, from its settings and the
/// samples' shape (`None`: not a common call).
type AxesOf<'a> = dyn Fn(&CommonCall, &[usize]) -> Option<Vec<Vec<f64>>> + 'a;

/// A common grid call (shift, zoom): the settings recognised, the samples
/// (not empty, at least one axis) resampled on the per-axis coordinate
/// vectors `axes_of` gives for the call and the samples' shape (`None`:
/// not a common call).
fn grid_call<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    settings: &Bound<'py, PyAny>,
    axes_of: &AxesOf<'_>,
) -> Option<Bound<'py, PyAny>> {
    let call = CommonCall::recognise(settings)?;
    crate::common_samples!(input, <E, O> a => {
        if a.is_empty() || a.ndim() == 0 {
            return None;
        }
        let axes = axes_of(&call, a.shape())?;
        grid_common::<E, O>(&call, py, a, &axes)
    })
}

/// The common call's values on the grid of per-axis coordinate vectors
/// `axes` (the engine's separable resampling), `None` where the engine
/// refuses it (the Python layer's to answer).
fn grid_common<'py, E, O>(
    call: &CommonCall,
    py: Python<'py>,
    data: ArrayViewD<'_, E>,
    axes: &[Vec<f64>],
) -> Option<Bound<'py, PyAny>>
where
    E: Sample<f64>,
    O: Stored<f64> + Element,
{
    let axes: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
    let deriv = vec![0; data.ndim()];
    let (opts, how, outside) = (call.options(), call.how(), call.cval_outside());
    resample_generic::<f64, E, O>(py, data, &axes, opts, how, &deriv, call.threads, outside).ok()
}

/// `splinelab.zoom`'s common call in one step (issue 50): the settings of
/// [`CommonCall`], `grid_mode=False` (the caller's check), a float64 or
/// float32 array (exactly `numpy.ndarray`, not empty), `zoom` one real or
/// one per axis ([`per_axis`]) that changes the array; the zoomed array in
/// a new array of the input's dtype, as the full call gives it: scipy's
/// output shape `int(round(n * z))` (ties to even, as Python's `round`),
/// its factors `(n - 1) / (m - 1)` (1 where `m = 1`) and `NI_ZoomShift`'s
/// coordinates `k * factor`, then the separable resampling. `None` for any
/// other call (an empty output, a zoom by 1 with the prefilter: scipy's
/// copy) and where the engine refuses it: the Python layer's.
#[pyfunction]
pub fn zoom_common<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    zoom: &Bound<'py, PyAny>,
    settings: &Bound<'py, PyAny>,
) -> Option<Bound<'py, PyAny>> {
    grid_call(py, input, settings, &|call, shape| {
        let zooms = per_axis(zoom, shape.len())?;
        if call.prefilter && zooms.iter().all(|&z| z == 1.0) {
            return None;
        }
        let mut axes = Vec::with_capacity(shape.len());
        for (&n, &z) in shape.iter().zip(&zooms) {
            let m = (n as f64 * z).round_ties_even();
            // Up to 2^31 samples an axis (no NaN, no negative, no empty
            // axis); the rest is the Python layer's to refuse or allocate.
            if !(1.0..=2_147_483_648.0).contains(&m) {
                return None;
            }
            let m = m as usize;
            let factor = match m {
                1 => 1.0,
                _ => (n - 1) as f64 / (m - 1) as f64,
            };
            axes.push((0..m).map(|k| k as f64 * factor).collect::<Vec<f64>>());
        }
        Some(axes)
    })
}

/// `splinelab.affine_transform`'s common call in one step (issue 50): the
/// settings of [`CommonCall`], a float64 or float32 array (exactly
/// `numpy.ndarray`, not empty), a finite square float64 `matrix`
/// (`(ndim, ndim)`, exactly `numpy.ndarray`), a finite `offset` (one real
/// or one per axis, [`per_axis`]) and an output of `out_shape` (None: the
/// input's; no empty axis); the values at `matrix · o + offset` in a new
/// array of the input's dtype, as the full call gives them (the engine's
/// affine resampling). `None` for any other call, and where the local
/// route may read less (the Python layer's). `rotate` calls it plane by
/// plane.
#[pyfunction]
#[pyo3(signature = (input, matrix, offset, settings, out_shape=None))]
pub fn affine_common<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    matrix: &Bound<'py, PyAny>,
    offset: &Bound<'py, PyAny>,
    settings: &Bound<'py, PyAny>,
    out_shape: Option<Vec<usize>>,
) -> Option<Bound<'py, PyAny>> {
    let call = CommonCall::recognise(settings)?;
    exact::<PyUntypedArray>(matrix)?;
    let m = matrix.cast::<PyArray2<f64>>().ok()?.try_readonly().ok()?;
    crate::common_samples!(input, <E, O> a => {
        let ndim = a.ndim();
        let m = m.as_array();
        if a.is_empty() || ndim == 0 || m.dim() != (ndim, ndim) {
            return None;
        }
        let m = m.as_standard_layout();
        let matrix = m.as_slice()?;
        let offset = per_axis(offset, ndim)?;
        if !matrix.iter().chain(&offset).all(|v| v.is_finite()) {
            return None;
        }
        let out_shape = out_shape.clone().unwrap_or_else(|| a.shape().to_vec());
        let count = out_shape.iter().product();
        let filtered = call.prefilter && call.degree >= 2;
        if count == 0 || out_shape.len() != ndim || may_be_local(a.shape(), count, call.degree, filtered) {
            return None;
        }
        let rule = match call.cval_outside() {
            true => PointRule::CvalOutside,
            false => PointRule::Fold,
        };
        let map = AffineMap { matrix, offset: &offset, out_shape, shift: 0.0, rule };
        affine_generic::<f64, E, O>(py, a, &map, call.options(), call.how(), call.threads).ok()
    })
}
