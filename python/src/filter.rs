//! `spline_filter1d` / `spline_filter`: the prefilter along the given axes
//! of a float64 or float32 array (scipy.ndimage's functions; `order` there
//! is our degree), computed in float64 (float64 or float32 samples read as
//! they lie, float64 or float32 coefficients, the latter rounded after
//! every axis as scipy rounds a float32 `output`) or in float32 (`f32`,
//! the `compute="float32"` opt-in), written into a
//! C-ordered array the caller allocated
//! (numpy: its allocator asks for transparent huge pages, which a fresh
//! Rust `Vec` of the same size does not get — at 10⁷ samples the 4 KiB page
//! faults of an 80 MB `Vec` cost more than the filter itself).
//!
//! The input, whatever its strides, is read once into the output, which is
//! then filtered in place. A single line (1-D) is copied and filtered with
//! [`LineFilter::apply`]; the exact route is checked afterwards by its
//! first coefficient (the recursions spread any NaN/inf there), the
//! convolution while copying, in L1-sized blocks; a long line under `tol`
//! runs in certified blocks on the pool (`BlockPrefilter`), reading the
//! input and writing the output directly. Other shapes go to the engine
//! (`spline_filter_from`): a C-ordered input is read by the first axis's
//! pass, which writes the output and checks the samples as it reads them
//! (no separate copy); other layouts are copied and checked in one pass on
//! the pool first.

use crate::common;
use crate::error::{engine_error, value_error};
use crate::scipy_mode::filter_rule;
use ndarray::{ArrayView1, ArrayViewD, ArrayViewMut1, ArrayViewMutD};
use numpy::{Element, PyArrayDescr, PyArrayDescrMethods, PyReadwriteArrayDyn};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyInt};
use splinelab::ndimage::NdimageError;
use splinelab::ndimage::filter_cache;
use splinelab::ndimage::local::route::global_ns;
use splinelab::ndimage::nd_prefilter::{filter_missing, spline_filter_from_as};
use splinelab::ndimage::samples::{Sample, Stored};
use splinelab::prelude::*;
use std::sync::Arc;

/// How to filter: degree, mode, `cval`, route (`tol` → truncated, or
/// with `convolution` the local truncated convolution chunked filtering
/// needs) and what non-finite samples do.
struct Spec {
    degree: u32,
    mode: Mode,
    cval: f64,
    route: Route,
    nan_policy: NanPolicy,
}

impl Spec {
    fn new(
        degree: u32,
        mode: &str,
        cval: f64,
        tol: Option<f64>,
        convolution: bool,
        nan_policy: &str,
    ) -> PyResult<Spec> {
        let mode: Mode = mode.parse().map_err(value_error)?;
        let nan_policy = crate::error::nan_policy(nan_policy)?;
        let route = match (tol, convolution) {
            (Some(tol), true) => Route::Convolution { tol },
            (Some(tol), false) => Route::Truncated { tol },
            (None, _) => Route::Exact,
        };
        Ok(Spec {
            degree,
            mode,
            cval,
            route,
            nan_policy,
        })
    }

    /// The line filter (kept between calls); degrees 0 and 1 interpolate
    /// their samples as they are (scipy returns the input), so they have none.
    fn line_filter<T: Real + Send + Sync + 'static>(
        &self,
    ) -> Result<Option<Arc<LineFilter<T>>>, NdimageError> {
        if self.degree < 2 {
            return Ok(None);
        }
        filter_cache::line_filter(
            self.degree,
            self.mode,
            self.cval,
            self.route,
            self.nan_policy,
        )
        .map(Some)
    }
}

/// Values per block of [`copy_checked`]: 32 KiB of f64, an L1 data cache.
const BLOCK: usize = 4096;

/// Copies `src` into `dst` and returns `max|src|` (for the overflow
/// check), `None` where a value is not finite — one pass: each block is
/// checked while it is still in L1.
fn copy_checked<T: Real + Copy>(src: &[T], dst: &mut [T]) -> Result<Option<f64>, NdimageError> {
    if src.is_empty() {
        return Err(NdimageError::Empty);
    }
    let mut finite = true;
    let mut max = 0.0f64;
    for (d, s) in dst.chunks_mut(BLOCK).zip(src.chunks(BLOCK)) {
        d.copy_from_slice(s);
        finite &= d.iter().fold(true, |ok, x| ok & x.is_finite());
        max = d.iter().fold(max, |m, x| m.max(x.to_f64().abs()));
    }
    Ok(finite.then_some(max))
}

/// One line `s` holding a non-finite sample, filtered into `d` by the
/// filter's NaN policy (the engine's slow path: refused, or filled and marked).
fn missing_line<T: Real + Send + Sync>(
    s: &[T],
    d: &mut [T],
    f: &LineFilter<T>,
) -> Result<(), NdimageError> {
    filter_missing(&ArrayView1::from(s), &mut ArrayViewMut1::from(d), &[0], f)
}

/// Whether filtering `axes` of an array of `shape` (`len` elements) is one
/// line: a single axis holding every element (an out-of-range axis is not;
/// the engine reports it).
fn one_line(shape: &[usize], len: usize, axes: &[usize]) -> bool {
    matches!(axes, [a] if shape.get(*a) == Some(&len))
}

/// Filters `out` (C order) along `axes`, after copying `src` into it when
/// given (else `out` already holds the samples). One line of samples and
/// coefficients of the compute type takes the line routes below; anything
/// else the engine's N-D filter.
fn filter_into<T, E, O>(
    src: Option<ArrayViewD<'_, E>>,
    out: &mut ArrayViewMutD<'_, O>,
    axes: &[usize],
    spec: &Spec,
) -> Result<(), NdimageError>
where
    T: Real + Copy + Send + Sync + 'static,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
    let filter = spec.line_filter::<T>()?;
    let line = match (&src, &filter) {
        (Some(s), Some(_)) if one_line(out.shape(), out.len(), axes) => {
            s.as_slice().and_then(E::as_compute)
        }
        _ => None,
    };
    let (Some(s), Some(f), Some(d)) = (
        line,
        &filter,
        out.as_slice_mut().and_then(O::as_compute_mut),
    ) else {
        return filter_nd(src, out, axes, filter.as_deref());
    };
    // One long line under `tol`: certified blocks on the pool, read from
    // the input and written into the output (no separate copy).
    if let Some(b) = BlockPrefilter::from_line_filter(f).filter(|b| b.pays_off(s.len())) {
        return b.apply_line_into(s, d);
    }
    // One line: the same call the engine makes for a single lane.
    if f.is_convolution() {
        let Some(max) = copy_checked(s, d)? else {
            return missing_line(s, d, f);
        };
        f.check_magnitude(max, 1)?;
        f.apply(d, &mut Vec::new());
        return Ok(());
    }
    if s.is_empty() {
        return Err(NdimageError::Empty);
    }
    // The exact recursions carry a NaN or infinity (input or overflow) from
    // wherever it appears to the end and back to `d[0]` (every pole's
    // anti-causal pass ends there): checking `d[0]` afterwards replaces a
    // pass over the input. On failure `d` holds garbage and the error says why.
    d.copy_from_slice(s);
    f.apply(d, &mut Vec::new());
    if d.first().is_some_and(|x| x.is_finite()) {
        return Ok(());
    }
    if s.iter().any(|x| !x.is_finite()) {
        return missing_line(s, d, f);
    }
    let max = s.iter().fold(0.0f64, |m, x| m.max(x.to_f64().abs()));
    f.check_magnitude(max, 1)?;
    // Finite data within the growth bound cannot overflow (LineFilter::growth).
    Err(NdimageError::Overflow {
        max,
        growth: f.growth(),
        limit: max,
    })
}

/// The general case: the engine's N-D filter, reading `src` when given
/// (the copy fused into the first pass; `spline_filter_from`), else
/// filtering `out` in place.
fn filter_nd<T, E, O>(
    src: Option<ArrayViewD<'_, E>>,
    out: &mut ArrayViewMutD<'_, O>,
    axes: &[usize],
    filter: Option<&LineFilter<T>>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
    if let Some(s) = src {
        return spline_filter_from_as(&s, out, axes, filter);
    }
    let Some(f) = filter else {
        return Ok(());
    };
    if axes.iter().copied().eq(0..out.ndim()) {
        // Every axis: one finite check, not one per axis.
        return spline_filter(out, f);
    }
    axes.iter()
        .try_for_each(|&axis| spline_filter1d(out, axis, f))
}

fn filter_generic<'py, T, E, O>(
    py: Python<'py>,
    src: Option<ArrayViewD<'_, E>>,
    mut out: ArrayViewMutD<'_, O>,
    axes: Vec<usize>,
    spec: Spec,
    threads: Option<usize>,
) -> PyResult<()>
where
    T: Real + Copy + Send + Sync + 'static,
    E: Sample<T>,
    O: Sample<T> + Stored<T> + Element,
{
    // The engine's strided-axis kernels assume C order (a Fortran-ordered
    // array would take the per-lane path, whose rounding differs by ulps).
    if !out.is_standard_layout() {
        return Err(value_error("output must be a C-contiguous array"));
    }
    if src.as_ref().is_some_and(|s| s.shape() != out.shape()) {
        return Err(value_error("input and output shapes differ"));
    }
    // One line is filtered by one thread whatever `threads` says, except
    // in certified blocks (`tol`, a line long enough for them to pay off):
    // run it on the calling thread rather than hand it to a pool thread
    // and wait (measured at 10⁴ samples: 0.04 against 0.03 ms).
    let blocks = || {
        let f = spec.line_filter::<T>().ok().flatten()?;
        BlockPrefilter::from_line_filter(&f).filter(|b| b.pays_off(out.len()))
    };
    let work = global_ns(out.len(), axes.len(), true);
    let single = one_line(out.shape(), out.len(), &axes) && blocks().is_none();
    let threads = match threads {
        Some(0) => Some(0), // refused by the pool, as before
        // One thread's work whatever the pool.
        _ if single => Some(1),
        t => t,
    };
    crate::pool::run_detached(py, threads, work, || {
        filter_into::<T, E, O>(src, &mut out, &axes, &spec)
    })?
    .map_err(engine_error)
}

/// Whether `output` is a float32 array (else a float64 one; another
/// dtype is `unsupported`), tried by the extraction the filter then makes.
fn writes_f32(output: &Bound<'_, PyAny>) -> PyResult<bool> {
    if output.extract::<PyReadwriteArrayDyn<'_, f64>>().is_ok() {
        Ok(false)
    } else if output.extract::<PyReadwriteArrayDyn<'_, f32>>().is_ok() {
        Ok(true)
    } else {
        Err(crate::samples::unsupported(output))
    }
}

/// Coefficients along `axes` (in that order) of `input` (any strides;
/// None: `output` filtered in place), written into `output` (C order):
/// computed in float64 from a float64 or float32 array into float64 or
/// float32 (float32 rounded after every axis, as scipy), or with `f32` in
/// float32 from float32 into float32 (the `compute="float32"` opt-in).
#[pyfunction]
#[pyo3(signature = (input, output, axes, degree, mode, cval, tol, threads, convolution=false, nan_policy="propagate", f32=false))]
#[allow(clippy::too_many_arguments)]
pub fn filter<'py>(
    py: Python<'py>,
    input: Option<Bound<'py, PyAny>>,
    output: Bound<'py, PyAny>,
    axes: Vec<usize>,
    degree: u32,
    mode: &str,
    cval: f64,
    tol: Option<f64>,
    threads: Option<usize>,
    convolution: bool,
    nan_policy: &str,
    f32: bool,
) -> PyResult<()> {
    let spec = Spec::new(degree, mode, cval, tol, convolution, nan_policy)?;
    // The results' type is the output's; with `f32` float32 (which its
    // extraction checks).
    let out32 = f32 || writes_f32(&output)?;
    crate::dispatch_compute!(optional input.as_ref(), f32, out32, <T, O> src => {
        let mut out = output.extract::<PyReadwriteArrayDyn<'py, O>>()?;
        filter_generic::<T, _, O>(py, src, out.as_array_mut(), axes, spec, threads)
    })
}

/// `(half_width, bound, amplification)` of the filter for `degree`, `tol`:
/// the certified truncation half-width and its tail bound `Σ_{|j|>n}|c_j|`
/// (`None`, 0 for the exact route), and `1/|V(−1)|` (max|D| ≤ it · max|s|).
#[pyfunction]
#[pyo3(signature = (degree, tol))]
pub fn filter_bound(degree: u32, tol: Option<f64>) -> PyResult<(Option<usize>, f64, f64)> {
    let spec = Spec::new(degree, "mirror", 0.0, tol, false, "propagate")?;
    match spec.line_filter::<f64>().map_err(value_error)? {
        Some(f) => Ok((f.half_width(), f.bound(), f.recursive().amplification())),
        None => Ok((tol.map(|_| 0), 0.0, 1.0)),
    }
}

/// How many samples a missing one reaches under `nan_policy="local"`
/// (the engine's `nan_reach`: the certified half-width for `tol` plus the
/// spline's window `degree // 2 + 1`).
#[pyfunction]
#[pyo3(signature = (degree, tol))]
pub fn nan_reach(degree: u32, tol: f64) -> PyResult<usize> {
    splinelab::prelude::nan_reach(degree, tol).map_err(value_error)
}

/// `splinelab.spline_filter1d`'s (and with `every`, `spline_filter`'s)
/// common call in one step (issue 50): an exact int `order` the engine
/// takes (degrees 0 and 1: scipy's copy, converted as numpy converts), a float64 or float32 array (exactly `numpy.ndarray`,
/// not empty), an exact int `axis` it has (or `every` axis), `output`
/// None (the input's dtype) or float64 / float32 (numpy's type or dtype,
/// or Python's `float`), one of scipy's mode names, a bool
/// `exact_edges`, `threads` None or an int in range and the engine's
/// defaults (the caller checks `tol`); the coefficients in a new array,
/// as the full call gives them (the same engine filter: scipy's rule for
/// the mode, [`filter_rule`]). `None` for any other call: the Python layer's.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn filter_common<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    order: &Bound<'py, PyAny>,
    axis: &Bound<'py, PyAny>,
    every: bool,
    output: &Bound<'py, PyAny>,
    mode: &Bound<'py, PyAny>,
    threads: &Bound<'py, PyAny>,
    nan_policy: &Bound<'py, PyAny>,
    compute: &Bound<'py, PyAny>,
    exact_edges: &Bound<'py, PyAny>,
) -> Option<Bound<'py, PyAny>> {
    let degree = common::degree(order)?;
    let exact_edges = common::exact::<PyBool>(exact_edges)?.is_true();
    let rule = filter_rule(common::name(mode)?, exact_edges)?;
    let threads = common::common_threads(threads)?;
    if !common::default_engine(nan_policy, compute) {
        return None;
    }
    let spec = Spec {
        degree,
        mode: rule,
        cval: 0.0,
        route: Route::Exact,
        nan_policy: NanPolicy::Propagate,
    };
    let out32 = writes_f32_dtype(py, output)?;
    crate::common_samples!(input, <E, I> a => {
        let ndim = a.ndim();
        if a.is_empty() || ndim == 0 {
            return None;
        }
        let axes: Vec<usize> = match every {
            true => (0..ndim).collect(),
            false => {
                let k = common::exact::<PyInt>(axis)?.extract::<isize>().ok()?;
                let n = ndim as isize;
                vec![usize::try_from(if k < 0 { k + n } else { k }).ok().filter(|&k| k < ndim)?]
            }
        };
        // The output's dtype: the input's (None) or the one named.
        match out32.unwrap_or(std::any::TypeId::of::<I>() == std::any::TypeId::of::<f32>()) {
            true => filter_new::<E, f32>(py, a, axes, spec, threads),
            false => filter_new::<E, f64>(py, a, axes, spec, threads),
        }
    })
}

/// Whether `output` names float32 (`Some(true)`) or float64
/// (`Some(false)`): numpy's scalar type, a native dtype or Python's
/// `float`; `Some(None)` for None (the input's dtype); `None` otherwise.
fn writes_f32_dtype(py: Python<'_>, output: &Bound<'_, PyAny>) -> Option<Option<bool>> {
    if output.is_none() {
        return Some(None);
    }
    let (f64_descr, f32_descr) = (numpy::dtype::<f64>(py), numpy::dtype::<f32>(py));
    if let Ok(d) = output.cast::<PyArrayDescr>() {
        return match (d.is_equiv_to(&f64_descr), d.is_equiv_to(&f32_descr)) {
            (true, _) => Some(Some(false)),
            (_, true) => Some(Some(true)),
            _ => None,
        };
    }
    if output.is(f64_descr.typeobj()) || output.is(py.get_type::<PyFloat>()) {
        Some(Some(false))
    } else if output.is(f32_descr.typeobj()) {
        Some(Some(true))
    } else {
        None
    }
}

/// The filter of `a` along `axes` into a new array of `O` (numpy's
/// allocation), `None` where the engine refuses it.
fn filter_new<'py, E, O>(
    py: Python<'py>,
    a: ArrayViewD<'_, E>,
    axes: Vec<usize>,
    spec: Spec,
    threads: Option<usize>,
) -> Option<Bound<'py, PyAny>>
where
    E: Sample<f64>,
    O: Sample<f64> + Stored<f64> + Element,
{
    let mut out = crate::alloc::zeros::<O>(py, a.shape()).ok()?;
    if spec.degree < 2 {
        // scipy's `output[...] = input`: float32 from float64 rounded to
        // nearest (overflow to ±inf), as numpy's unsafe cast.
        out.view_mut()
            .zip_mut_with(&a, |o, s| *o = O::store(&s.widen()));
    } else {
        filter_generic::<f64, E, O>(py, Some(a), out.view_mut(), axes, spec, threads).ok()?;
    }
    Some(out.into_any())
}
