//! `truncation_width` and `coefficients`: the width chooser and the
//! S-spline coefficient table c_0..c_{K−1}, in float64 or as decimal
//! strings at a requested number of bits (the `width` / `coeffs` commands'
//! computations, without their files).

use crate::error::value_error;
use crate::pool::parallel;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use rug::Float;
use serde_json::json;
use splinelab::scalar::{Mp, Real, decimal_string};
use splinelab::sspline::{
    CoefficientMethod, Criterion, SplineFamily, check_tol, coefficients, f64_saturation_width,
};
use splinelab_verify::cost::{Estimate, width_search};

/// Largest `count` (as `splinelab coeffs --count`).
const MAX_COUNT: usize = 100_000;
/// The precision decimal tables are computed at, then rounded to the bits
/// asked for (the top of the command line's `--prec` ladder).
const MAX_BITS: u32 = 2048;
const MIN_BITS: u32 = 16;

/// The family of B-spline order `m`, or the cubic Beta2 of `tension`.
pub fn family(order: u32, tension: Option<&str>) -> PyResult<SplineFamily> {
    match tension {
        Some(t) => SplineFamily::parse_tension(t),
        None => SplineFamily::order(order),
    }
    .map_err(value_error)
}

fn count_ok(count: usize) -> PyResult<()> {
    if (1..=MAX_COUNT).contains(&count) {
        Ok(())
    } else {
        Err(value_error(format!(
            "count {count} is outside 1..={MAX_COUNT}"
        )))
    }
}

/// Refuses, before any work, a request whose estimated run time passes
/// `budget` seconds (the CLI's `--budget`), with the estimate and the value
/// that would admit it.
fn within_budget(e: &Estimate, budget: f64) -> PyResult<()> {
    if !(budget.is_finite() && budget > 0.0) {
        return Err(value_error(format!(
            "budget={budget} is not a positive number of seconds"
        )));
    }
    e.within(budget, None).map_err(|over| {
        value_error(format!(
            "{over}: reduce it, or pass budget={:.0}",
            over.admit()
        ))
    })
}

/// The width choice: `(n, achieved, bound, criterion, f64 saturation n,
/// half support, B-spline order, tension, family)`; splinelab/__init__.py
/// names the fields as `splinelab width --json` does.
#[pyfunction]
#[pyo3(signature = (order, tension, tol, criterion, budget))]
#[allow(clippy::type_complexity)]
pub fn truncation_width(
    py: Python<'_>,
    order: u32,
    tension: Option<&str>,
    tol: f64,
    criterion: &str,
    budget: f64,
) -> PyResult<(
    usize,
    f64,
    f64,
    String,
    usize,
    f64,
    u32,
    Option<String>,
    String,
)> {
    let family = family(order, tension)?;
    let criterion: Criterion = criterion.parse().map_err(value_error)?;
    check_tol(tol).map_err(value_error)?;
    let saturation = f64_saturation_width(&family).map_err(value_error)?;
    within_budget(&width_search(&family, saturation, tol), budget)?;
    let w = py
        .detach(|| parallel(|| splinelab::sspline::truncation_width(&family, tol, criterion)))
        .map_err(value_error)?;
    Ok((
        w.n,
        w.achieved,
        w.bound,
        w.criterion.name().to_string(),
        saturation,
        family.half_support(),
        family.spline_order(),
        family.tension().map(|t| t.to_string()),
        family.to_string(),
    ))
}

/// c_0..c_{count−1} in float64 (production method: partial fractions with
/// ≥ 128 guard bits, rounded once).
#[pyfunction]
#[pyo3(signature = (order, tension, count))]
pub fn coefficients_f64<'py>(
    py: Python<'py>,
    order: u32,
    tension: Option<&str>,
    count: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let family = family(order, tension)?;
    count_ok(count)?;
    let c: Vec<f64> = py
        .detach(|| parallel(|| coefficients(&family, count, CoefficientMethod::Production)))
        .map_err(value_error)?;
    Ok(c.into_pyarray(py))
}

/// c_0..c_{count−1} as decimal strings carrying `bits` bits (16..=2048):
/// computed in 2048-bit MPFR, rounded once to `bits`, printed with
/// `⌈bits·log10 2⌉ + 1` digits; JSON `{c, prec, working_bits}`.
#[pyfunction]
#[pyo3(signature = (order, tension, count, bits))]
pub fn coefficients_decimal(
    py: Python<'_>,
    order: u32,
    tension: Option<&str>,
    count: usize,
    bits: u32,
) -> PyResult<String> {
    let family = family(order, tension)?;
    count_ok(count)?;
    if !(MIN_BITS..=MAX_BITS).contains(&bits) {
        return Err(value_error(format!(
            "bits {bits} is outside {MIN_BITS}..={MAX_BITS}"
        )));
    }
    let digits = (f64::from(bits) * std::f64::consts::LOG10_2).ceil() as usize + 1;
    let c: Vec<Mp<MAX_BITS>> = py
        .detach(|| parallel(|| coefficients(&family, count, CoefficientMethod::Production)))
        .map_err(value_error)?;
    let c: Vec<String> = c
        .iter()
        .map(|x| decimal_string(&Float::with_val(bits, x.to_float()), digits))
        .collect();
    Ok(json!({"c": c, "prec": bits, "working_bits": MAX_BITS}).to_string())
}
