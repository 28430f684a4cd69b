//! `knot-insertion`: a B-spline before and after the user's knot insertion
//! must be the same curve. Judged exactly on the f64 inputs: on every piece
//! between consecutive distinct knots (of either spline) inside the original
//! base interval, the difference is a polynomial of degree ≤ k, so it is
//! identically zero iff it vanishes at `k + 1` points of the piece; the
//! maximum deviation is taken, exactly, over [`SAMPLES_PER_PIECE`] points of
//! each piece, ends included (a lower bound of the supremum, exact when it
//! is 0). Both curves are evaluated in scipy's convention, so a change that
//! only scipy's evaluation sees — the value at the right end after a knot of
//! multiplicity `k + 2` appears there — is a change.

use super::format::UserFormat;
use super::rational_bspline::RationalBSpline;
use super::{CheckError, summary::verdict};
use rayon::prelude::*;
use rug::{Float, Rational};
use serde::Serialize;

/// Exact evaluation points per piece (equispaced, including both ends).
pub const SAMPLES_PER_PIECE: usize = 65;

/// Largest number of pieces accepted.
pub const MAX_PIECES: usize = 100_000;

/// The result of a knot-insertion check (JSON contract: `max_deviation`
/// and `max_deviation_rel` instead of ulps figures).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InsertionSummary {
    /// `"knot-insertion"`.
    pub kind: String,
    /// Evaluation points compared.
    pub n: usize,
    /// `None`: the reference is exact.
    pub reference_bits: Option<u32>,
    /// How the curves were compared.
    pub reference: String,
    /// `max |after(x) − before(x)|` over the points, exact then rounded.
    pub max_deviation: f64,
    /// `max_deviation / max |c_before|` (the curve's scale).
    pub max_deviation_rel: f64,
    /// The deviation in ulps of the user's format at the curve's scale.
    pub max_deviation_ulps: f64,
    /// Where the largest deviation occurs.
    pub worst_x: f64,
    /// `true` when the curves are identical (proved exactly).
    pub identical: bool,
    /// Threshold used in ulps of the scale (`--max-ulps`, default
    /// [`default_max_ulps`]).
    pub max_ulps: f64,
    /// 1 when the deviation exceeds the threshold, else 0.
    pub failed: usize,
    /// `"pass"` or `"fail"`.
    pub verdict: String,
    /// `"stable-bound"` without `--max-ulps` (the threshold is
    /// [`default_max_ulps`], the bound below), `"max-ulps"` with it.
    pub verdict_basis: String,
    /// The stable bound the default threshold stands for, and its source.
    pub stable_bound: String,
}

/// Default tolerance in ulps of the curve's scale: a correct insertion in
/// floating point forms each new coefficient by one convex combination
/// (≤ 2 roundings), and evaluation mixes `k + 1` of them. As a stable
/// bound ([`super::stable_bound`]): Boehm's new coefficient
/// `(1 − α) c_{i−1} + α c_i`, `α = (x − t_i)/(t_{i+k} − t_i)`, carries at
/// most `γ_7 max(|c_{i−1}|, |c_i|)` (3 roundings in `α`, 1 in `1 − α`, 2
/// products, 1 sum; Higham, *Accuracy and Stability*, 2nd ed., Lemma 3.1),
/// and the B-splines sum to 1, so the curve moves by at most `γ_7 max |c|`,
/// under 8 ulps of the scale; `4(k + 1) ≥ 8` for `k ≥ 1`.
pub fn default_max_ulps(k: usize) -> f64 {
    4.0 * (k as f64 + 1.0)
}

/// Compares `before` and `after` on the base interval of `before`.
pub fn check_knot_insertion(
    before: &RationalBSpline,
    after: &RationalBSpline,
    format: UserFormat,
    max_ulps: Option<f64>,
) -> Result<InsertionSummary, CheckError> {
    let k = before.degree();
    if after.degree() != k {
        return Err(CheckError::Invalid(format!(
            "degree changed from {k} to {}",
            after.degree()
        )));
    }
    let (a, b) = before.base_interval();
    let mut breaks: Vec<Rational> = before
        .knots()
        .iter()
        .chain(after.knots())
        .filter(|u| **u > a && **u < b)
        .cloned()
        .chain([a.clone(), b.clone()])
        .collect();
    breaks.sort();
    breaks.dedup();
    if breaks.len() > MAX_PIECES {
        return Err(CheckError::TooLarge(format!(
            "{} pieces exceed {MAX_PIECES}",
            breaks.len() - 1
        )));
    }
    let m = SAMPLES_PER_PIECE - 1;
    let points: Vec<Rational> = breaks
        .windows(2)
        .flat_map(|w| {
            let h = Rational::from(&w[1] - &w[0]) / m as u32;
            (0..=m).map(move |j| w[0].clone() + h.clone() * j as u32)
        })
        .collect();
    let (dev, x) = points
        .par_iter()
        .map(|x| ((after.eval(x) - before.eval(x)).abs(), x))
        .reduce_with(|p, q| if q.0 > p.0 { q } else { p })
        .expect("at least one piece");
    let scale = before
        .coefficients()
        .iter()
        .map(|c| c.clone().abs())
        .max()
        .unwrap_or_default();
    let devf = Float::with_val(256, &dev);
    let scalef = Float::with_val(256, &scale);
    let rel = if scale == 0 {
        devf.to_f64()
    } else {
        Float::with_val(256, &devf / &scalef).to_f64()
    };
    let ulps = (devf.clone() >> format.ulp_exp(&scalef)).to_f64();
    let limit = max_ulps.unwrap_or_else(|| default_max_ulps(k));
    let failed = usize::from(ulps > limit || ulps.is_nan());
    Ok(InsertionSummary {
        kind: "knot-insertion".into(),
        n: points.len(),
        reference_bits: None,
        reference: format!(
            "exact rational Cox–de Boor (scipy convention) at {SAMPLES_PER_PIECE} points on each of {} pieces",
            breaks.len() - 1
        ),
        max_deviation: devf.to_f64(),
        max_deviation_rel: rel,
        max_deviation_ulps: ulps,
        worst_x: x.to_f64(),
        identical: dev == 0,
        max_ulps: limit,
        failed,
        verdict: verdict(failed),
        verdict_basis: if max_ulps.is_some() {
            "max-ulps"
        } else {
            "stable-bound"
        }
        .into(),
        stable_bound: format!(
            "a stable Boehm insertion moves the curve by at most γ_7·max|c| (convex combinations, partition of unity; Higham, Accuracy and Stability, 2nd ed., Lemma 3.1): default threshold 4(k + 1) = {} ulps of max|c|",
            default_max_ulps(k)
        ),
    })
}
