//! `check(kind, ...)`: the `splinelab check` KINDs on arrays, returning the
//! same JSON object as the command line's `--json` (built by
//! [`Outcome::to_json`], shared with the CLI), its text summary, and with
//! `out` its page, charts and `summary.json` (the command line's `--out`
//! writer).

use crate::error::value_error;
use crate::pool::parallel;
use crate::width::family;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use serde_json::Map;
use splinelab_reports::cli::check::table;
use splinelab_reports::cli::check_out::write_check_dir;
use splinelab_reports::error::CliError;
use splinelab_verify::check::bezier_eval::check_bezier_eval as bezier;
use splinelab_verify::check::bspline_eval::{BSplineEvalInput, check_bspline_eval as bspline};
use splinelab_verify::check::coeffs::check_coeffs as coeffs;
use splinelab_verify::check::cond::{CondInput, Norm, check_cond as cond};
use splinelab_verify::check::grid_spline::{GridSplineInput, check_grid_spline as grid_spline};
use splinelab_verify::check::interp::{InterpInput, ScipyMode, check_interp_with_cval as interp};
use splinelab_verify::check::knot_insertion::check_knot_insertion as insertion;
use splinelab_verify::check::outcome::prefilter_extra;
use splinelab_verify::check::prefilter::{PrefilterInput, check_prefilter as prefilter};
use splinelab_verify::check::rational_bspline::RationalBSpline;
use splinelab_verify::check::{CheckError, Outcome, UserFormat};
use splinelab_verify::conditioning::Basis;
use std::path::PathBuf;

fn format(name: &str) -> PyResult<UserFormat> {
    name.parse().map_err(value_error)
}

fn max_ulps(k: Option<f64>) -> PyResult<Option<f64>> {
    match k {
        Some(k) if !(k.is_finite() && k >= 0.0) => Err(value_error(format!(
            "max_ulps: {k} is not a finite number ≥ 0"
        ))),
        k => Ok(k),
    }
}

/// What every check returns: the JSON contract and the command line's text
/// summary.
type Report = (String, String);

/// The JSON and text of `o`, after writing its folder into `out` when
/// given (an unwritable folder is an `OSError`).
fn report(
    py: Python<'_>,
    o: Outcome,
    extra: &Map<String, serde_json::Value>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let json = o.to_json(extra);
    if let Some(dir) = out {
        py.detach(|| parallel(|| write_check_dir(&dir, &o, &json)))
            .map_err(|e| match e {
                CliError::Output { .. } => PyOSError::new_err(e.to_string()),
                e => value_error(e),
            })?;
    }
    Ok((json.to_string(), table(&o)))
}

fn elements(
    py: Python<'_>,
    run: impl FnOnce() -> Result<splinelab_verify::check::CheckSummary, CheckError> + Send,
    extra: Map<String, serde_json::Value>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let s = py.detach(|| parallel(run)).map_err(value_error)?;
    report(py, Outcome::Elements(Box::new(s)), &extra, out)
}

/// What the grid kinds (`prefilter`, `interp`) share: the mode, the user's
/// format and threshold, and the JSON fields naming degree and mode.
struct GridArgs {
    mode: ScipyMode,
    format: UserFormat,
    max_ulps: Option<f64>,
    extra: Map<String, serde_json::Value>,
}

impl GridArgs {
    fn new(mode: &str, fmt: &str, degree: usize, k: Option<f64>) -> PyResult<GridArgs> {
        let mode = mode.parse::<ScipyMode>().map_err(value_error)?;
        Ok(GridArgs {
            mode,
            format: format(fmt)?,
            max_ulps: max_ulps(k)?,
            extra: prefilter_extra(mode.name(), degree),
        })
    }
}

/// `check prefilter`: samples, the user's coefficients, degree, mode.
#[pyfunction]
#[pyo3(signature = (samples, user, fmt, degree, mode, max_ulps_, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn check_prefilter(
    py: Python<'_>,
    samples: Vec<f64>,
    user: Vec<f64>,
    fmt: &str,
    degree: usize,
    mode: &str,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let g = GridArgs::new(mode, fmt, degree, max_ulps_)?;
    let family =
        splinelab_verify::check::prefilter::family_of_degree(degree).map_err(value_error)?;
    let input = PrefilterInput {
        samples,
        user,
        format: g.format,
        family,
        mode: g.mode.spline_mode(),
        max_ulps: g.max_ulps,
    };
    elements(py, || prefilter(&input), g.extra, out)
}

/// `check coeffs`: the user's c_0..c_{K−1} of an order (or Beta2 tension).
#[pyfunction]
#[pyo3(signature = (user, fmt, order, tension, max_ulps_, out = None))]
pub fn check_coeffs(
    py: Python<'_>,
    user: Vec<f64>,
    fmt: &str,
    order: u32,
    tension: Option<&str>,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let family = family(order, tension)?;
    let (f, k) = (format(fmt)?, max_ulps(max_ulps_)?);
    elements(py, || coeffs(&family, &user, f, k), Map::new(), out)
}

/// `check bspline-eval`: knots, coefficients, degree, x, the user's values.
#[pyfunction]
#[pyo3(signature = (t, c, k, x, user, fmt, extrapolate, max_ulps_, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn check_bspline_eval(
    py: Python<'_>,
    t: Vec<f64>,
    c: Vec<f64>,
    k: usize,
    x: Vec<f64>,
    user: Vec<f64>,
    fmt: &str,
    extrapolate: bool,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let input = BSplineEvalInput {
        t,
        c,
        k,
        extrapolate,
        x,
        user,
        format: format(fmt)?,
        max_ulps: max_ulps(max_ulps_)?,
    };
    elements(py, || bspline(&input), Map::new(), out)
}

/// `check grid-spline`: the grid's nodes (ascending per axis), the samples
/// (C order), the odd degree, the points (point-major) and the user's values.
#[pyfunction]
#[pyo3(signature = (grid, samples, degree, points, user, fmt, max_ulps_, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn check_grid_spline(
    py: Python<'_>,
    grid: Vec<Vec<f64>>,
    samples: Vec<f64>,
    degree: usize,
    points: Vec<f64>,
    user: Vec<f64>,
    fmt: &str,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let input = GridSplineInput {
        grid,
        samples,
        degree,
        points,
        user,
        format: format(fmt)?,
        max_ulps: max_ulps(max_ulps_)?,
    };
    let mut extra = Map::new();
    extra.insert("degree".into(), degree.into());
    elements(py, || grid_spline(&input), extra, out)
}

/// `check bezier-eval`: Bernstein coefficients, t, the user's values.
#[pyfunction]
#[pyo3(signature = (b, t, user, fmt, max_ulps_, out = None))]
pub fn check_bezier_eval(
    py: Python<'_>,
    b: Vec<f64>,
    t: Vec<f64>,
    user: Vec<f64>,
    fmt: &str,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let (f, k) = (format(fmt)?, max_ulps(max_ulps_)?);
    elements(py, || bezier(&b, &t, &user, f, k), Map::new(), out)
}

/// `check knot-insertion`: a B-spline `(t, c, k)` before and after.
#[pyfunction]
#[pyo3(signature = (before, after, fmt, max_ulps_, out = None))]
pub fn check_knot_insertion(
    py: Python<'_>,
    before: (Vec<f64>, Vec<f64>, usize),
    after: (Vec<f64>, Vec<f64>, usize),
    fmt: &str,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let spline = |(t, c, k): &(Vec<f64>, Vec<f64>, usize), what: &str| {
        RationalBSpline::from_f64(t, c, *k).map_err(|e| value_error(format!("{what}: {e}")))
    };
    let (b, a) = (spline(&before, "before")?, spline(&after, "after")?);
    let (f, k) = (format(fmt)?, max_ulps(max_ulps_)?);
    let s = py
        .detach(|| parallel(|| insertion(&b, &a, f, k)))
        .map_err(value_error)?;
    report(py, Outcome::Insertion(s), &Map::new(), out)
}

/// `check interp`: 1-D or 2-D samples (C order, `shape`), points point-major
/// (`points[k·D + a]`), the user's values, degree, mode, `cval` (scipy's
/// constant for `grid-constant`).
#[pyfunction]
#[pyo3(signature = (samples, shape, points, user, fmt, degree, mode, cval, max_ulps_, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn check_interp(
    py: Python<'_>,
    samples: Vec<f64>,
    shape: Vec<usize>,
    points: Vec<f64>,
    user: Vec<f64>,
    fmt: &str,
    degree: usize,
    mode: &str,
    cval: f64,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let g = GridArgs::new(mode, fmt, degree, max_ulps_)?;
    let input = InterpInput {
        samples,
        shape,
        points,
        user,
        format: g.format,
        degree,
        mode: g.mode,
        max_ulps: g.max_ulps,
    };
    elements(py, || interp(&input, cval), g.extra, out)
}

/// `check cond`: node sets, basis (`bernstein`, `monomial`), norm (`2`,
/// `inf`), the user's condition numbers (one per set).
#[pyfunction]
#[pyo3(signature = (node_sets, basis, norm, user, fmt, max_ulps_, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn check_cond(
    py: Python<'_>,
    node_sets: Vec<Vec<f64>>,
    basis: &str,
    norm: &str,
    user: Vec<f64>,
    fmt: &str,
    max_ulps_: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Report> {
    let input = CondInput {
        node_sets,
        basis: basis.parse::<Basis>().map_err(value_error)?,
        norm: norm.parse::<Norm>().map_err(value_error)?,
        user,
        format: format(fmt)?,
        max_ulps: max_ulps(max_ulps_)?,
    };
    elements(py, || cond(&input), Map::new(), out)
}
