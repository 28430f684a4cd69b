//! `map_coordinates`: the spline interpolant of a float64 or float32 array
//! evaluated at points given as scipy does, one row per axis: `(ndim, k)`.
//! With `prefilter` the array holds samples (the engine solves for the
//! coefficients); without, it already holds coefficients (scipy's
//! `prefilter=False`), which are extended by the mode and evaluated as given.
//! With `deriv`, a partial derivative of the interpolant instead of its values;
//! with `cval_outside`, `cval` at points outside the grid (scipy's 'constant').

use crate::error::{engine_error, value_error};
use crate::pool::run_with;
use numpy::{Element, PyArrayDyn, PyArrayMethods, PyReadonlyArray2, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use rayon::prelude::*;
use splinelab::ndimage::interpolant::PointRule;
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

/// The interpolant of samples (`prefilter`: the engine solves for the
/// coefficients) or of given coefficients (scipy's `prefilter=False`).
pub(crate) fn interpolant<T: Real + Send + Sync>(
    data: &ndarray::ArrayViewD<'_, T>,
    opts: Options,
    prefilter: bool,
) -> Result<Interpolant<T>, NdimageError> {
    if prefilter {
        Interpolant::new(data, opts)
    } else {
        Interpolant::from_coefficients_with(data, opts)
    }
}

/// `∂^deriv f` at each point (columns of `at`) into `out`, in parallel:
/// the engine's [`Interpolant::eval_derivative`] per point.
fn derivatives<T: Real + Send + Sync>(
    f: &Interpolant<T>,
    at: ndarray::ArrayView2<'_, f64>,
    deriv: &[u32],
    out: &mut [T],
) -> Result<(), NdimageError> {
    out.par_iter_mut()
        .with_min_len(256)
        .zip(at.axis_iter(ndarray::Axis(1)))
        .try_for_each(|(o, x)| {
            *o = f.eval_derivative(&x.to_vec(), deriv)?;
            Ok(())
        })
}

#[allow(clippy::too_many_arguments)]
fn map_generic<'py, T>(
    py: Python<'py>,
    input: PyReadonlyArrayDyn<'py, T>,
    coordinates: PyReadonlyArray2<'py, f64>,
    opts: Options,
    prefilter: bool,
    threads: Option<usize>,
    deriv: Option<Vec<u32>>,
    cval_outside: bool,
) -> PyResult<Bound<'py, PyArrayDyn<T>>>
where
    T: Real + Element + Send + Sync,
{
    let data = input.as_array();
    let at = coordinates.as_array();
    // numpy's allocation: a result it cannot allocate is `MemoryError`.
    let result = crate::alloc::zeros::<T>(py, &[at.ncols()])?;
    let mut view = result.readwrite();
    let out = view.as_slice_mut()?;
    // scipy's 'constant': cval outside the grid, decided per point in the
    // parallel evaluation (not by passes over the points in numpy after it).
    let rule = if cval_outside {
        PointRule::CvalOutside
    } else {
        PointRule::Fold
    };
    let run = || {
        let deriv = deriv.filter(|d| d.iter().any(|&k| k > 0));
        let f = interpolant(&data, opts, prefilter)?;
        if let Some(d) = deriv {
            return derivatives(&f, at, &d, out);
        }
        f.eval_many_with(at.t(), rule, out)
    };
    py.detach(|| run_with(threads, run))?
        .map_err(engine_error)?;
    drop(view);
    Ok(result)
}

/// The float64 and float32 entry points, one generic body.
macro_rules! map_fn {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        #[pyfunction]
        #[pyo3(signature = (input, coordinates, degree, mode, cval, tol, prefilter, threads, deriv=None, cval_outside=false, nan_policy="propagate"))]
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
            cval_outside: bool,
            nan_policy: &str,
        ) -> PyResult<Bound<'py, PyArrayDyn<$t>>> {
            let opts = options(degree, mode, cval, tol, nan_policy)?;
            map_generic(
                py,
                input,
                coordinates,
                opts,
                prefilter,
                threads,
                deriv,
                cval_outside,
            )
        }
    };
}

map_fn!(
    map_coordinates_f64,
    f64,
    "Values of the float64 interpolant at `coordinates` (`(ndim, k)`)."
);
map_fn!(
    map_coordinates_f32,
    f32,
    "Values of the float32 interpolant (computed in float32) at `coordinates`."
);
