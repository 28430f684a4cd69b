//! The common call of the interpolation functions in one step (issue 50):
//! the settings recognised from the arguments exactly as Python passed
//! them ([`CommonCall`]), the samples dispatched by dtype
//! ([`common_samples!`]) and the route decided from the shape and the
//! count ([`may_be_local`]). Where anything is not common, the functions
//! return `None` and the Python layer checks, routes and answers the call
//! as scipy does; nothing here refuses anything.

use crate::coefficients::Coefficients;
use crate::scipy_mode::{EngineArgs, engine_args};
use numpy::{PyArrayMethods, PyUntypedArray};
use pyo3::prelude::*;
use pyo3::type_object::{PyTypeCheck, PyTypeInfo};
use pyo3::types::{PyBool, PyFloat, PyInt, PyList, PyString, PyTuple};
use splinelab::ndimage::interpolant::PointRule;
use splinelab::ndimage::local::route;
use splinelab::ndimage::spline_order;
use splinelab::prelude::*;
use splinelab_reports::threads::MAX_THREADS;

/// The common settings of an interpolation call, recognised from its
/// arguments as Python passed them: an int `order` the engine takes, one
/// of scipy's mode names that needs no padding or moving of the points
/// (not 'wrap'; not scipy's padded route for 'nearest' / 'grid-constant'),
/// a float or int `cval`, a bool `prefilter`, `threads` None or an int in
/// range, `nan_policy="propagate"`, `compute="float64"`. Exact types only:
/// anything else is the Python layer's to check (its checks raise what
/// scipy raises; here nothing is refused).
pub(crate) struct CommonCall {
    pub degree: u32,
    pub args: EngineArgs,
    pub cval: f64,
    pub prefilter: bool,
    pub threads: Option<usize>,
}

impl CommonCall {
    /// The settings `(order, mode, cval, prefilter, threads, nan_policy,
    /// compute)` (a tuple, as the Python layer passes them), recognised.
    pub(crate) fn recognise(settings: &Bound<'_, PyAny>) -> Option<Self> {
        let settings = exact::<PyTuple>(settings)?;
        let [order, mode, cval, prefilter, threads, nan_policy, compute] =
            <[Bound<'_, PyAny>; 7]>::try_from(settings.iter().collect::<Vec<_>>()).ok()?;
        let (order, mode, cval, prefilter) = (&order, &mode, &cval, &prefilter);
        let (threads, nan_policy, compute) = (&threads, &nan_policy, &compute);
        let degree = degree(order)?;
        let prefilter = exact::<PyBool>(prefilter)?.is_true();
        let args = engine_args(name(mode)?, degree, prefilter, false)?;
        if args.pad != 0 || args.rule == PointRule::WrapPeriodNMinus1 {
            return None;
        }
        let cval = real(cval)?;
        let threads = common_threads(threads)?;
        if !default_engine(nan_policy, compute) {
            return None;
        }
        Some(CommonCall {
            degree,
            args,
            cval,
            prefilter,
            threads,
        })
    }

    /// The engine's options of the call (the exact filter: `tol`'s default).
    pub(crate) fn options(&self) -> Options {
        let mut opts = Options::new(self.degree, self.args.mode);
        opts.cval = self.cval;
        opts
    }

    /// How the coefficients are made (`prefilter`; no filter rule: scipy's
    /// padded route is not a common call).
    pub(crate) fn how(&self) -> Coefficients {
        match self.prefilter {
            true => Coefficients::Prefilter,
            false => Coefficients::Given,
        }
    }

    /// Whether `cval` is taken outside the grid (scipy's 'constant').
    pub(crate) fn cval_outside(&self) -> bool {
        self.args.rule == PointRule::CvalOutside
    }
}

/// `value` where its type is exactly `T` (not a subclass: numpy's scalars,
/// bools for ints, str subclasses are the Python layer's to check).
pub(crate) fn exact<'a, 'py, T: PyTypeCheck + PyTypeInfo>(
    value: &'a Bound<'py, PyAny>,
) -> Option<&'a Bound<'py, T>> {
    value
        .is_exact_instance_of::<T>()
        .then(|| value.cast::<T>().ok())
        .flatten()
}

/// Whether the local route may read less than the global one for `k`
/// points on an array of `shape` at the default `tol`
/// ([`route::may_be_local`], as `splinelab._local.may_be_local` decides in
/// Python); true where the half-width is unknown (the Python layer then
/// decides).
pub(crate) fn may_be_local(shape: &[usize], k: usize, degree: u32, filtered: bool) -> bool {
    let half_width = || crate::local::default_half_width(degree);
    route::may_be_local(
        shape.iter().product(),
        shape.len(),
        degree,
        k,
        filtered,
        half_width,
    )
}

/// A degree given as an exact Python int the engine takes.
pub(crate) fn degree(order: &Bound<'_, PyAny>) -> Option<u32> {
    let degree = exact::<PyInt>(order)?.extract::<u32>().ok()?;
    spline_order(degree).ok().map(|_| degree)
}

/// An exact Python str.
pub(crate) fn name<'a>(value: &'a Bound<'_, PyAny>) -> Option<&'a str> {
    exact::<PyString>(value)?.to_str().ok()
}

/// `threads` of a common call: `Some(None)` for None, `Some(Some(n))` for
/// an exact int in `1..=MAX_THREADS`; `None` for anything else (the
/// Python layer's to refuse).
pub(crate) fn common_threads(threads: &Bound<'_, PyAny>) -> Option<Option<usize>> {
    if threads.is_none() {
        return Some(None);
    }
    let n = exact::<PyInt>(threads)?.extract::<usize>().ok()?;
    (1..=MAX_THREADS).contains(&n).then_some(Some(n))
}

/// Whether `nan_policy` and `compute` are their defaults, 'propagate' and
/// 'float64' (exact strs).
pub(crate) fn default_engine(nan_policy: &Bound<'_, PyAny>, compute: &Bound<'_, PyAny>) -> bool {
    name(nan_policy) == Some("propagate") && name(compute) == Some("float64")
}

/// A real number given as an exact Python float or int (an int as
/// Python's `float()` rounds it, to nearest even: `i64 as f64`).
pub(crate) fn real(value: &Bound<'_, PyAny>) -> Option<f64> {
    match exact::<PyFloat>(value) {
        Some(v) => Some(v.value()),
        None => Some(exact::<PyInt>(value)?.extract::<i64>().ok()? as f64),
    }
}

/// scipy's `_normalize_sequence` of a common call: one [`real`] for every
/// axis, or a tuple, list or float64 vector of `ndim` of them.
pub(crate) fn per_axis(value: &Bound<'_, PyAny>, ndim: usize) -> Option<Vec<f64>> {
    if let Some(v) = real(value) {
        return Some(vec![v; ndim]);
    }
    let values: Vec<f64> = if let Some(t) = exact::<PyTuple>(value) {
        t.iter().map(|v| real(&v)).collect::<Option<_>>()?
    } else if let Some(l) = exact::<PyList>(value) {
        l.iter().map(|v| real(&v)).collect::<Option<_>>()?
    } else {
        exact::<PyUntypedArray>(value)?;
        let v = value
            .cast::<numpy::PyArray1<f64>>()
            .ok()?
            .try_readonly()
            .ok()?;
        v.as_array().to_vec()
    };
    (values.len() == ndim).then_some(values)
}

/// `$body` with `$a` the view of `$input` (exactly a `numpy.ndarray` of
/// float64 or float32, read-only borrowed), `$E` its element type and `$O`
/// the result's (the same: the common call's output is the input's
/// dtype); `None` for any other input.
#[macro_export]
macro_rules! common_samples {
    ($input:expr, <$E:ident, $O:ident> $a:ident => $body:expr) => {{
        #[allow(unused_imports)]
        use numpy::PyArrayMethods;
        let input: &pyo3::Bound<'_, pyo3::PyAny> = $input;
        $crate::common::exact::<numpy::PyUntypedArray>(input)?;
        if let Ok(a) = input.cast::<numpy::PyArrayDyn<f64>>() {
            type $E = f64;
            type $O = f64;
            let r = a.try_readonly().ok()?;
            let $a = r.as_array();
            $body
        } else {
            type $E = f32;
            type $O = f32;
            let r = input
                .cast::<numpy::PyArrayDyn<f32>>()
                .ok()?
                .try_readonly()
                .ok()?;
            let $a = r.as_array();
            $body
        }
    }};
}
