//! `bspline-eval`: a user's values of `BSpline(t, c, k, extrapolate)(x)`
//! (scipy's convention) against exact rational de Boor evaluation of the
//! f64 inputs ([`RationalBSpline`]).

use super::format::UserFormat;
use super::rational_bspline::RationalBSpline;
use super::stable_bound::{gamma, unit_roundoff};
use super::summary::{
    BoundBasis, CheckSummary, Context, ElementError, element_error, from_elements,
};
use super::{CheckError, require_finite, require_len};
use rayon::prelude::*;
use rug::{Float, Rational};

/// Bits an exact reference is rounded to for the error arithmetic (its own
/// rounding, `2^−256` relative, is invisible in any reported figure).
pub const EXACT_FLOAT_BITS: u32 = 256;

/// Largest `len(x) · (k + 1)²` accepted.
pub const MAX_WORK: usize = 50_000_000;

/// What `check bspline-eval` is given.
#[derive(Debug, Clone)]
pub struct BSplineEvalInput {
    /// Knots `t`.
    pub t: Vec<f64>,
    /// Coefficients `c` (`len(t) − k − 1` of them).
    pub c: Vec<f64>,
    /// Degree `k`.
    pub k: usize,
    /// scipy's `extrapolate`: outside `[t[k], t[n]]` the value is NaN when false.
    pub extrapolate: bool,
    /// Evaluation points.
    pub x: Vec<f64>,
    /// The user's values.
    pub user: Vec<f64>,
    /// The user's format.
    pub format: UserFormat,
    /// `--max-ulps`.
    pub max_ulps: Option<f64>,
}

/// The error of a value where the reference is NaN (outside the base
/// interval without extrapolation): right only if the user's is NaN too.
pub fn undefined_reference(index: usize, x: f64) -> ElementError {
    let ok = x.is_nan();
    let e = if ok { 0.0 } else { f64::INFINITY };
    ElementError {
        index,
        value: x,
        reference: f64::NAN,
        ulps: e,
        rel: e,
        abs: e,
        digits: 0.0,
        region: None,
        // Nothing but NaN is right here: any other value is infinitely over.
        bound: Some(0.0),
        excess: Some(e),
    }
}

/// Checks the user's B-spline values (parallel over `x`).
pub fn check_bspline_eval(input: &BSplineEvalInput) -> Result<CheckSummary, CheckError> {
    let s = RationalBSpline::from_f64(&input.t, &input.c, input.k)?;
    require_finite("x", &input.x)?;
    require_len("values (one per x)", input.x.len(), input.user.len())?;
    if input.x.is_empty() {
        return Err(CheckError::Empty("x".into()));
    }
    let work = input.x.len().saturating_mul((input.k + 1).pow(2));
    if work > MAX_WORK {
        return Err(CheckError::TooLarge(format!(
            "len(x)·(k+1)² = {work} exceeds {MAX_WORK}"
        )));
    }
    let gk = gamma(6 * input.k + 2, input.format);
    let u0 = unit_roundoff(input.format);
    let elements: Vec<ElementError> = input
        .x
        .par_iter()
        .zip(input.user.par_iter())
        .enumerate()
        .map(|(i, (x, u))| {
            let x = Rational::from_f64(*x).expect("finite");
            if !input.extrapolate && !s.in_base(&x) {
                return undefined_reference(i, *u);
            }
            let r = Float::with_val(EXACT_FLOAT_BITS, &s.eval(&x));
            let scale = s.abs_eval(&x).to_f64();
            element_error(i, *u, &r, input.format, None)
                .with_bound(gk * scale + u0 * r.to_f64().abs())
        })
        .collect();
    let ctx = Context {
        kind: "bspline-eval",
        format: input.format,
        reference_bits: None,
        reference: "exact rational Cox–de Boor recursion (scipy convention)".into(),
        horizon: None,
        max_ulps: input.max_ulps,
        bound: BoundBasis::PerElement(format!(
            "γ_{}·Σ_j |c_j||B_j(x)| + u|f(x)|: de Boor / Cox–de Boor evaluation, each basis value a product of k levels of non-negative terms with ≤ 5 roundings each and a sum of k + 1 products (Higham, Accuracy and Stability, 2nd ed., §3.1 and Lemma 3.1; Cox 1972 on the stability of the recurrence); outside the base interval the same form is used",
            6 * input.k + 2
        )),
    };
    Ok(from_elements(&ctx, elements))
}
