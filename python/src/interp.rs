//! `map_coordinates`: the spline interpolant of an array evaluated at
//! points given as scipy does, one row per axis: `(ndim, k)`. It computes
//! in float64 from float64 or float32 samples (read as they lie, widened
//! by the engine as it reads them) and stores float64 or float32 results
//! (each rounded once), or with `f32` float32 samples in float32 (the
//! `compute="float32"` opt-in).
//! With `prefilter` the array holds samples (the engine solves for the
//! coefficients); without, it already holds coefficients (scipy's
//! `prefilter=False`), which are extended by the mode and evaluated as given.
//! With `filter_rule`, the samples are prefiltered under that rule and the
//! coefficients evaluated as given (scipy's route for `nearest` and
//! `grid-constant`), in one coefficient array.
//! With `deriv`, a partial derivative of the interpolant instead of its values;
//! with `cval_outside`, `cval` at points outside the grid (scipy's 'constant').

use crate::coefficients::Coefficients;
use crate::common::{CommonCall, exact, may_be_local};
use crate::error::{engine_error, value_error};
use ndarray::{ArrayView2, ArrayViewD};
use numpy::{Element, PyArrayDyn, PyArrayMethods, PyReadonlyArray2, PyUntypedArray};
use pyo3::prelude::*;
use splinelab::ndimage::interpolant::{
    InPlaceOptions, PointRule, SampleOrder, map_samples_in_place,
};
use splinelab::ndimage::local::route::{self, global_ns};
use splinelab::ndimage::samples::{Sample, Stored};
use splinelab::prelude::*;

pub(crate) fn options(
    degree: u32,
    mode: &str,
    cval: f64,
    tol: Option<f64>,
    nan_policy: &str,
) -> PyResult<Options> {
    let mut opts = Options::new(degree, mode.parse().map_err(value_error)?);
    opts.cval = cval;
    opts.nan_policy = crate::error::nan_policy(nan_policy)?;
    if let Some(tol) = tol {
        opts.route = Route::Truncated { tol };
    }
    Ok(opts)
}

/// Estimated nanoseconds on one thread of a call that builds the
/// interpolant of `shape` under `opts` and `how` and makes `taps`
/// multiply-adds evaluating it ([`crate::pool::run_with`] decides by it):
/// the prefilter, or the copy of given coefficients, as the local route
/// prices the global route ([`global_ns`]), and a nanosecond a tap.
pub(crate) fn work_ns(shape: &[usize], opts: &Options, how: Coefficients, taps: f64) -> f64 {
    let filtered = !matches!(how, Coefficients::Given) && opts.degree >= 2;
    global_ns(shape.iter().product(), shape.len(), filtered) + taps
}

/// The interpolant of `data` (samples of any type read into `T`).
pub(crate) fn interpolant<T, E>(
    data: &ArrayViewD<'_, E>,
    opts: Options,
    how: Coefficients,
) -> Result<Interpolant<T>, NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
{
    match how {
        Coefficients::Prefilter => Interpolant::from_samples(data, opts),
        Coefficients::FilteredAs(rule) => Interpolant::from_samples_filtered_as(data, opts, rule),
        Coefficients::Given => Interpolant::from_coefficients_of(data, opts),
    }
}

/// How degrees 0 and 1 are evaluated where the samples lie (their
/// coefficients are the samples, whatever `prefilter` or the filter rule
/// say): values only, from a C-ordered array, where it pays
/// ([`route::in_place_pays`]), and not
/// under `nan_policy="local"` with a non-finite `cval` (the padded route's
/// alone, see [`InPlaceOptions`]).
/// `None`: the interpolant's padded route.
fn in_place<E>(
    data: &ArrayViewD<'_, E>,
    opts: &Options,
    deriv: bool,
    points: usize,
) -> Option<InPlaceOptions> {
    let order = SampleOrder::of_degree(opts.degree)?;
    // A strided view (a zero-stride broadcast among them) would be copied
    // whole first: the local route reads its windows instead.
    if !data.is_standard_layout() {
        return None;
    }
    let shape = data.shape();
    let local_cval = opts.nan_policy == NanPolicy::Local && !opts.cval.is_finite();
    let pays = pays_in_place(shape, points, opts.degree);
    (!deriv && !local_cval && pays).then_some(InPlaceOptions {
        order,
        mode: opts.mode,
        cval: opts.cval,
        nan_policy: opts.nan_policy,
    })
}

/// The values (or the partial derivative `deriv`) at the columns of
/// `at`, in a new array of `O` and of `out_shape` (numpy's allocation;
/// as many elements as columns).
#[allow(clippy::too_many_arguments)]
fn map_generic<'py, T, E, O>(
    py: Python<'py>,
    data: ArrayViewD<'_, E>,
    at: ArrayView2<'_, f64>,
    out_shape: &[usize],
    opts: Options,
    how: Coefficients,
    threads: Option<usize>,
    deriv: Option<Vec<u32>>,
    cval_outside: bool,
) -> PyResult<Bound<'py, PyAny>>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T> + Element,
{
    // scipy's 'constant': cval outside the grid, decided per point in the
    // parallel evaluation (not by passes over the points in numpy after it).
    let rule = if cval_outside {
        PointRule::CvalOutside
    } else {
        PointRule::Fold
    };
    // numpy's allocation: a result it cannot allocate is `MemoryError`.
    let mut result = crate::alloc::zeros::<O>(py, out_shape)?;
    let out = result.slice_mut();
    let deriv = deriv.filter(|d| d.iter().any(|&k| k > 0));
    let in_place = in_place(&data, &opts, deriv.is_some(), at.ncols());
    let run = || {
        if let Some(o) = &in_place {
            return map_samples_in_place::<T, E, O>(&data, at.t(), o, rule, out);
        }
        let f = interpolant::<T, E>(&data, opts, how)?;
        match &deriv {
            Some(d) => f.eval_derivatives(at.t(), d, out),
            None => f.eval_many_with_as(at.t(), rule, out),
        }
    };
    let m = f64::from(opts.degree) + 1.0;
    let taps = at.ncols() as f64 * m.powi(at.nrows() as i32);
    // In place, nothing is proportional to the input (issue 50).
    let work = match in_place {
        Some(_) => taps,
        None => work_ns(data.shape(), &opts, how, taps),
    };
    crate::pool::run_detached(py, threads, work, run)?.map_err(engine_error)?;
    Ok(result.into_any())
}

/// Values of the interpolant of `input` at `coordinates` (`(ndim, k)`):
/// computed in float64 from a float64 or float32 array (float32 results
/// with `out32`), or with `f32` in float32 from a float32 array (the
/// `compute="float32"` opt-in).
#[pyfunction]
#[pyo3(signature = (input, coordinates, degree, mode, cval, tol, prefilter, threads, deriv=None, cval_outside=false, nan_policy="propagate", out32=false, filter_rule=None, f32=false))]
#[allow(clippy::too_many_arguments)]
pub fn map_coordinates<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    coordinates: PyReadonlyArray2<'py, f64>,
    degree: u32,
    mode: &str,
    cval: f64,
    tol: Option<f64>,
    prefilter: bool,
    threads: Option<usize>,
    deriv: Option<Vec<u32>>,
    cval_outside: bool,
    nan_policy: &str,
    out32: bool,
    filter_rule: Option<&str>,
    f32: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let opts = options(degree, mode, cval, tol, nan_policy)?;
    let how = Coefficients::new(prefilter, filter_rule)?;
    let at = coordinates.as_array();
    let shape = [at.ncols()];
    crate::dispatch_compute!(input, f32, out32, <T, O> a => {
        map_generic::<T, _, O>(py, a, at.view(), &shape, opts, how, threads, deriv, cval_outside)
    })
}

/// Whether `points` points of `degree` (0 or 1) on an array of `shape` are
/// read in place ([`route::in_place_pays`]): what
/// `splinelab._local.in_place_pays` decides in Python before any call.
#[pyfunction]
pub fn in_place_pays(shape: Vec<usize>, points: usize, degree: u32) -> bool {
    pays_in_place(&shape, points, degree)
}

/// [`route::in_place_pays`] for `points` points of `degree` (0 or 1; false
/// above) on an array of `shape`: `(degree + 1)^ndim` samples a point.
fn pays_in_place(shape: &[usize], points: usize, degree: u32) -> bool {
    let taps = f64::from(degree.saturating_add(1)).powi(shape.len() as i32);
    degree <= 1 && route::in_place_pays(shape.iter().product(), points, taps)
}

/// The values at the points `coordinates` (`(ndim, ...)`, C-ordered) of
/// the non-empty samples `data` (any strides: a strided view is read
/// in place by neither route, [`in_place`]), of `coordinates.shape[1:]`
/// in `O` (the samples' dtype); `None` where the local route may read
/// less ([`may_be_local`], the Python layer's to route) or where the
/// engine refuses the call (the Python layer's to answer as scipy).
fn points_common<'py, E, O>(
    call: &CommonCall,
    py: Python<'py>,
    data: ArrayViewD<'_, E>,
    coordinates: ArrayViewD<'_, f64>,
) -> Option<Bound<'py, PyAny>>
where
    E: Sample<f64>,
    O: Stored<f64> + Element,
{
    let ndim = data.ndim();
    if !coordinates.is_standard_layout()
        || data.is_empty()
        || coordinates.shape().first() != Some(&ndim)
    {
        return None;
    }
    let out_shape = coordinates.shape().get(1..)?.to_vec();
    let k: usize = out_shape.iter().product();
    let at = coordinates.into_shape_with_order((ndim, k)).ok()?;
    let opts = call.options();
    let filtered = call.prefilter && call.degree >= 2;
    if in_place(&data, &opts, false, k).is_none()
        && may_be_local(data.shape(), k, call.degree, filtered)
    {
        return None;
    }
    map_generic::<f64, E, O>(
        py,
        data,
        at,
        &out_shape,
        opts,
        call.how(),
        call.threads,
        None,
        call.cval_outside(),
    )
    .ok()
}

/// `splinelab.map_coordinates`'s common call in one step (issue 50):
/// float64 or float32 arrays (exactly `numpy.ndarray`) of samples (any
/// strides) and of float64 coordinates `(ndim, ...)` (C-ordered), the settings of
/// [`CommonCall`]; the values in a new array of the samples' dtype and of
/// `coordinates.shape[1:]`, as the full call gives them (the same engine
/// call: the interpolant, or degrees 0 and 1 read in place). `None` for
/// any other call, and where the local route may pay or the engine refuses
/// the call: the Python layer then checks, routes and answers it. The
/// caller has checked the arguments this does not take (`output`,
/// `derivative`, `tol`, `exact_edges`, the forced route).
#[pyfunction]
pub fn map_coordinates_common<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    coordinates: &Bound<'py, PyAny>,
    settings: &Bound<'py, PyAny>,
) -> Option<Bound<'py, PyAny>> {
    let call = CommonCall::recognise(settings)?;
    exact::<PyUntypedArray>(coordinates)?;
    let points = coordinates
        .cast::<PyArrayDyn<f64>>()
        .ok()?
        .try_readonly()
        .ok()?;
    let at = points.as_array();
    crate::common_samples!(input, <E, O> a => points_common::<E, O>(&call, py, a, at))
}
