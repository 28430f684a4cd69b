//! The local route from Python ([`splinelab::ndimage::local`]):
//! `map_coordinates` at a few points of a large array reading only their
//! windows (`local_map_f64/f32`, which decline, returning `None`, where the
//! global route is cheaper), the route's cost estimate, and the
//! `splinelab.Interpolant` engine (`LocalSplineF64/F32`): a reusable spline
//! with a bounded tile cache and in-place updates, reading an in-memory
//! array (or a memory map) directly from its buffer, or blocks the Python
//! layer fetched from an array-like ([`Blocks`]). float32 samples are
//! computed in float64 as scipy computes them (widened as they are read,
//! each result rounded once to float32; issue 42).

use crate::error::{engine_error, value_error};
use crate::pool::{parallel, run_with};
use crate::scipy_mode::point_rule;
use numpy::{
    Element, IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArrayDyn,
};
use pyo3::prelude::*;
use splinelab::ndimage::local::route::{C_POINT, locate_ns};
use splinelab::ndimage::local::{LocalInterpolant, LocalOptions, LocalPlan, LocalSpec};
use splinelab::ndimage::samples::{Blocks, Sample, SampleSource, Stored};
use splinelab::prelude::*;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// The local route's options from the Python layer's arguments.
#[allow(clippy::too_many_arguments)]
fn local_options(
    degree: u32,
    mode: &str,
    cval: f64,
    tol: Option<f64>,
    nan_policy: &str,
    prefilter: bool,
    scipy_pad: usize,
) -> PyResult<LocalOptions> {
    let mut opts = LocalOptions {
        prefilter,
        scipy_pad,
        ..LocalOptions::new(degree, mode.parse().map_err(value_error)?)
    };
    opts.options.cval = cval;
    opts.options.nan_policy = crate::error::nan_policy(nan_policy)?;
    // The local route runs the truncated convolution of `tol` (`None`:
    // its default tolerance).
    if let Some(tol) = tol {
        opts.options.route = Route::Convolution { tol };
    }
    Ok(opts)
}

/// Derivative orders, `None` where all are 0.
fn nonzero(deriv: Option<Vec<u32>>) -> Option<Vec<u32>> {
    deriv.filter(|d| d.iter().any(|&k| k > 0))
}

#[allow(clippy::too_many_arguments)]
fn map_local<'py, E>(
    py: Python<'py>,
    input: PyReadonlyArrayDyn<'py, E>,
    coordinates: PyReadonlyArray2<'py, f64>,
    opts: LocalOptions,
    rule: &str,
    deriv: Option<Vec<u32>>,
    threads: Option<usize>,
    force: bool,
) -> PyResult<Option<Bound<'py, PyArray1<E>>>>
where
    E: Sample<f64> + Stored<f64> + Element,
{
    let data = input.as_array();
    let at = coordinates.as_array();
    let rule = point_rule(rule)?;
    let deriv = nonzero(deriv);
    // The route decided where the points' count says (locating them is
    // the decision's cost), then the tiles evaluated where their price says.
    let plan = || -> Result<Option<(LocalSpec<f64>, LocalPlan)>, NdimageError> {
        let spec = LocalSpec::<f64>::new(data.shape(), opts)?;
        let plan = if force {
            Some(LocalPlan::new(&spec, at.t(), rule, None)?)
        } else {
            LocalPlan::new_if_local(&spec, at.t(), rule)?
        };
        Ok(plan.map(|p| (spec, p)))
    };
    let run = |(spec, plan): (LocalSpec<f64>, LocalPlan)| -> Result<Vec<f64>, NdimageError> {
        let mut out = vec![0.0; at.ncols()];
        plan.evaluate(&spec, &data, deriv.as_deref(), &mut out)?;
        Ok(out)
    };
    let out = py.detach(|| -> PyResult<Option<Vec<f64>>> {
        let decided = run_with(threads, locate_ns(at.ncols()), plan)?.map_err(engine_error)?;
        let Some((spec, plan)) = decided else {
            return Ok(None);
        };
        let work = plan.cost().local_ns;
        Ok(Some(
            run_with(threads, work, || run((spec, plan)))?.map_err(engine_error)?,
        ))
    })?;
    Ok(out.map(|v| E::store_vec(v).into_pyarray(py)))
}

/// The float64 and float32 entry points, one generic body.
macro_rules! local_map_fn {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        #[pyfunction]
        #[pyo3(signature = (input, coordinates, degree, mode, cval, tol, prefilter, threads, deriv, rule, nan_policy, scipy_pad, force))]
        #[allow(clippy::too_many_arguments)]
        pub fn $name<'py>(
            py: Python<'py>,
            input: PyReadonlyArrayDyn<'py, $t>,
            coordinates: PyReadonlyArray2<'py, f64>,
            degree: u32,
            mode: &str,
            cval: f64,
            tol: Option<f64>,
            prefilter: bool,
            threads: Option<usize>,
            deriv: Option<Vec<u32>>,
            rule: &str,
            nan_policy: &str,
            scipy_pad: usize,
            force: bool,
        ) -> PyResult<Option<Bound<'py, PyArray1<$t>>>> {
            let opts = local_options(degree, mode, cval, tol, nan_policy, prefilter, scipy_pad)?;
            map_local(py, input, coordinates, opts, rule, deriv, threads, force)
        }
    };
}

local_map_fn!(
    local_map_f64,
    f64,
    "map_coordinates of a float64 array on the local route (`None`: the global route is cheaper; `force`: local anyway)."
);
local_map_fn!(
    local_map_f32,
    f32,
    "map_coordinates of a float32 array on the local route (computed in float64, rounded once to float32)."
);

/// The local route's cost estimate for points `coordinates` (`(ndim, k)`)
/// on an array of `shape`: `(local_ns, global_ns, tile, tiles)`.
#[pyfunction]
#[pyo3(signature = (shape, coordinates, degree, mode, tol, prefilter, rule, scipy_pad))]
#[allow(clippy::too_many_arguments)]
pub fn local_route_cost(
    py: Python<'_>,
    shape: Vec<usize>,
    coordinates: PyReadonlyArray2<'_, f64>,
    degree: u32,
    mode: &str,
    tol: Option<f64>,
    prefilter: bool,
    rule: &str,
    scipy_pad: usize,
) -> PyResult<(f64, f64, usize, usize)> {
    let opts = local_options(degree, mode, 0.0, tol, "propagate", prefilter, scipy_pad)?;
    let rule = point_rule(rule)?;
    let at = coordinates.as_array();
    let run = || -> Result<_, NdimageError> {
        let spec = LocalSpec::<f64>::new(&shape, opts)?;
        let c = LocalPlan::new(&spec, at.t(), rule, None)?.cost();
        Ok((c.local_ns, c.global_ns, c.tile, c.tiles))
    };
    py.detach(|| run_with(None, locate_ns(at.ncols()), run))?
        .map_err(engine_error)
}

/// The local route's certified half-width for `degree` (2 or more) and
/// `tol` (`None`: its default, `default_tol`), in float64: what
/// `splinelab._local.may_be_local` prices a tile with (kept there per
/// setting; the filter behind it is kept by the engine).
#[pyfunction]
#[pyo3(signature = (degree, tol))]
pub fn local_half_width(degree: u32, tol: Option<f64>) -> PyResult<usize> {
    let opts = local_options(degree, "mirror", 0.0, tol, "propagate", true, 0)?;
    let spec = LocalSpec::<f64>::new(&[1], opts).map_err(engine_error)?;
    Ok(spec.half_width())
}

/// [`local_half_width`] of `degree` at the default `tol`, kept per degree
/// (a `LocalSpec` per call would cost a small call a microsecond); `None`
/// where the engine refuses the degree.
pub(crate) fn default_half_width(degree: u32) -> Option<usize> {
    static KEPT: OnceLock<Mutex<HashMap<u32, usize>>> = OnceLock::new();
    let kept = KEPT.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(&n) = kept.lock().ok()?.get(&degree) {
        return Some(n);
    }
    let n = local_half_width(degree, None).ok()?;
    kept.lock().ok()?.insert(degree, n);
    Some(n)
}

/// `(k, ndim)` non-negative indices (numpy's `intp`) as a flat `usize` list.
fn flat_indices(indices: &PyReadonlyArray2<'_, i64>) -> PyResult<Vec<usize>> {
    indices
        .as_array()
        .iter()
        .map(|&i| usize::try_from(i).map_err(|_| value_error(format!("index {i} is negative"))))
        .collect()
}

/// Fetched blocks as a sample source of `shape`.
fn blocks<'a, 'py, T: Element>(
    shape: &[usize],
    fetched: &'a [(Vec<usize>, PyReadonlyArrayDyn<'py, T>)],
) -> PyResult<Blocks<'a, T>> {
    let views = fetched
        .iter()
        .map(|(lo, b)| (lo.clone(), b.as_array()))
        .collect();
    Blocks::new(shape, views).map_err(engine_error)
}

/// The shared bodies of the two interpolant classes.
fn eval_source<T, S>(
    f: &LocalInterpolant<T>,
    source: &S,
    coordinates: numpy::ndarray::ArrayView2<'_, f64>,
    rule: &str,
    deriv: Option<Vec<u32>>,
    threads: Option<usize>,
) -> PyResult<Vec<T>>
where
    T: Real + Send + Sync,
    S: SampleSource<T> + ?Sized,
{
    let rule = point_rule(rule)?;
    let deriv = nonzero(deriv);
    let mut out = vec![T::zero(); coordinates.ncols()];
    let run = || f.eval_many(source, coordinates.t(), rule, deriv.as_deref(), &mut out);
    // A point's share of a tile unknown before the plan: a point priced
    // as the local route prices one (`C_POINT`).
    let work = coordinates.ncols() as f64 * C_POINT;
    run_with(threads, work, run)?.map_err(engine_error)?;
    Ok(out)
}

/// Samples as float64 values (exact from float32).
fn widened<E: Sample<f64> + Element>(values: &PyReadonlyArray1<'_, E>) -> Vec<f64> {
    values.as_array().iter().map(Sample::widen).collect()
}

/// The float64 and float32 interpolant classes, one body (computed in
/// float64 either way; `$t` is the samples' and the results' type).
macro_rules! spline_class {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        #[pyclass(module = "splinelab._splinelab")]
        pub struct $name {
            inner: LocalInterpolant<f64>,
        }

        #[pymethods]
        impl $name {
            #[new]
            #[pyo3(signature = (shape, degree, mode, cval, tol, nan_policy, prefilter, scipy_pad, cache_bytes, one_call=false))]
            #[allow(clippy::too_many_arguments)]
            fn new(
                py: Python<'_>,
                shape: Vec<usize>,
                degree: u32,
                mode: &str,
                cval: f64,
                tol: Option<f64>,
                nan_policy: &str,
                prefilter: bool,
                scipy_pad: usize,
                cache_bytes: usize,
                one_call: bool,
            ) -> PyResult<Self> {
                let opts = local_options(degree, mode, cval, tol, nan_policy, prefilter, scipy_pad)?;
                let inner = py
                    .detach(|| parallel(|| LocalInterpolant::new(&shape, opts, cache_bytes)))
                    .map_err(engine_error)?;
                let inner = if one_call { inner.for_one_call() } else { inner };
                Ok($name { inner })
            }

            /// `(half-width, per-axis bound, tolerance)`.
            fn truncation(&self) -> (usize, f64, Option<f64>) {
                let s = self.inner.spec();
                (s.half_width(), s.bound(), s.tol())
            }

            /// `(budget, bytes held, tiles held, bytes of changed samples)`.
            fn cache_info(&self) -> (usize, usize, usize, usize) {
                let (budget, held) = self.inner.cache_bytes();
                (budget, held, self.inner.cached_tiles(), self.inner.changed_bytes())
            }

            #[pyo3(signature = (input, coordinates, rule, deriv, threads))]
            fn eval<'py>(
                &self,
                py: Python<'py>,
                input: PyReadonlyArrayDyn<'py, $t>,
                coordinates: PyReadonlyArray2<'py, f64>,
                rule: &str,
                deriv: Option<Vec<u32>>,
                threads: Option<usize>,
            ) -> PyResult<Bound<'py, PyArray1<$t>>> {
                let (data, at) = (input.as_array(), coordinates.as_array());
                let out = py.detach(|| eval_source(&self.inner, &data, at, rule, deriv, threads))?;
                Ok(<$t as Stored<f64>>::store_vec(out).into_pyarray(py))
            }

            #[pyo3(signature = (shape, fetched, coordinates, rule, deriv, threads))]
            #[allow(clippy::too_many_arguments)]
            fn eval_blocks<'py>(
                &self,
                py: Python<'py>,
                shape: Vec<usize>,
                fetched: Vec<(Vec<usize>, PyReadonlyArrayDyn<'py, $t>)>,
                coordinates: PyReadonlyArray2<'py, f64>,
                rule: &str,
                deriv: Option<Vec<u32>>,
                threads: Option<usize>,
            ) -> PyResult<Bound<'py, PyArray1<$t>>> {
                let source = blocks(&shape, &fetched)?;
                let at = coordinates.as_array();
                let out = py.detach(|| eval_source(&self.inner, &source, at, rule, deriv, threads))?;
                Ok(<$t as Stored<f64>>::store_vec(out).into_pyarray(py))
            }

            /// The source boxes `(lo, hi)` evaluating at `coordinates` reads.
            fn boxes_for_eval(
                &self,
                coordinates: PyReadonlyArray2<'_, f64>,
                rule: &str,
            ) -> PyResult<Vec<(Vec<usize>, Vec<usize>)>> {
                let rule = point_rule(rule)?;
                let at = coordinates.as_array();
                run_with(None, locate_ns(at.ncols()), || self.inner.boxes_for_eval(at.t(), rule))?
                    .map_err(engine_error)
            }

            /// The source boxes updating the samples at `indices` reads.
            fn boxes_for_update(&self, indices: PyReadonlyArray2<'_, i64>) -> PyResult<Vec<(Vec<usize>, Vec<usize>)>> {
                Ok(self.inner.boxes_for_update(&flat_indices(&indices)?))
            }

            /// Sets the samples at `indices` (`(k, ndim)`) to `values`;
            /// `(tiles, coefficients)` recomputed.
            fn update(
                &mut self,
                py: Python<'_>,
                input: PyReadonlyArrayDyn<'_, $t>,
                indices: PyReadonlyArray2<'_, i64>,
                values: PyReadonlyArray1<'_, $t>,
            ) -> PyResult<(usize, usize)> {
                let (idx, v) = (flat_indices(&indices)?, widened(&values));
                let data = input.as_array();
                let inner = &mut self.inner;
                let s = py.detach(|| parallel(|| inner.update(&data, &idx, &v))).map_err(engine_error)?;
                Ok((s.tiles, s.coefficients))
            }

            /// [`Self::update`] reading fetched blocks.
            fn update_blocks(
                &mut self,
                py: Python<'_>,
                shape: Vec<usize>,
                fetched: Vec<(Vec<usize>, PyReadonlyArrayDyn<'_, $t>)>,
                indices: PyReadonlyArray2<'_, i64>,
                values: PyReadonlyArray1<'_, $t>,
            ) -> PyResult<(usize, usize)> {
                let source = blocks(&shape, &fetched)?;
                let (idx, v) = (flat_indices(&indices)?, widened(&values));
                let inner = &mut self.inner;
                let s = py.detach(|| parallel(|| inner.update(&source, &idx, &v))).map_err(engine_error)?;
                Ok((s.tiles, s.coefficients))
            }

            /// The changed samples' blocks `(first index, flat samples)`.
            fn changed_blocks<'py>(&self, py: Python<'py>) -> Vec<(Vec<usize>, Bound<'py, PyArray1<$t>>)> {
                self.inner
                    .changed_blocks()
                    .into_iter()
                    .map(|(first, data)| (first, <$t as Stored<f64>>::store_vec(data).into_pyarray(py)))
                    .collect()
            }

            /// Restores a block saved by `changed_blocks`.
            fn restore_block(&mut self, first: Vec<usize>, data: PyReadonlyArray1<'_, $t>) -> PyResult<()> {
                self.inner
                    .restore_block(&first, widened(&data))
                    .map_err(engine_error)
            }
        }
    };
}

spline_class!(
    LocalSplineF64,
    f64,
    "The engine of `splinelab.Interpolant` for float64 samples."
);
spline_class!(
    LocalSplineF32,
    f32,
    "The engine of `splinelab.Interpolant` for float32 samples (computed in float64, results rounded once to float32)."
);
