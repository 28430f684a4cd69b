//! The truncation-width chooser: the smallest half-width `n ≥ 1` whose
//! truncation error meets a tolerance, under one of three criteria.

use super::euler_frobenius::PoleExpansion;
use super::{SplineFamily, SsplineError, TruncationAnalysis};
use crate::scalar::{Mp, Real};
use rug::float::Round;

/// Precision in which widths are chosen: every measure is computed in MPFR
/// at 320 bits from the tail directly. 128 bits would give every measure far
/// more digits than any tolerance needs, but evaluating the Euler–Frobenius
/// polynomial near its dominant root −ρ ≈ −1 cancels about 0.65 bits per
/// order (|V(−1)| ≈ (2/π)^m), so orders above 120 failed to find their poles;
/// 320 bits cover the supported orders up to 200.
type Work = Mp<320>;

/// Which truncation error must fall below the tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, strum::VariantArray, strum::IntoStaticStr)]
#[strum(serialize_all = "kebab-case")]
pub enum Criterion {
    /// `|c_n| < ε` — the paper's rule (absolute).
    Coeff,
    /// `max_j |S_n(j) − δ_{0j}| < ε` — interpolation error at the knots.
    Knot,
    /// `sup_x Σ_k |S(x−k) − S_n(x−k)| < ε` — worst curve error for `|P| ≤ 1`.
    Uniform,
}

crate::named_enum!(Criterion, "criterion");

/// The chosen width and what it achieves.
#[derive(Debug, Clone, PartialEq)]
pub struct WidthChoice {
    /// The smallest half-width `n ≥ 1` meeting the criterion.
    pub n: usize,
    /// The criterion.
    pub criterion: Criterion,
    /// The tolerance ε.
    pub tol: f64,
    /// The criterion's error at `n` (rounded to nearest f64).
    pub achieved: f64,
    /// The analytic tail bound at `n`, rounded up: a guaranteed upper bound
    /// of the uniform (worst-curve) error for data `|P| ≤ 1`, whatever the
    /// criterion.
    pub bound: f64,
}

/// The smallest `n ≥ 1` meeting `criterion` for tolerance `tol ∈ (0, 1)`
/// (see [`WidthChooser::choose`]; this builds a chooser for one query).
///
/// ```
/// use splinelab::sspline::{Criterion, SplineFamily, truncation_width};
/// let w = truncation_width(&SplineFamily::Order(4), 1e-3, Criterion::Coeff).unwrap();
/// // |c_n| = √3 (2 − √3)^n: 2.39e-3 at n = 5, 6.4e-4 at n = 6.
/// assert_eq!(w.n, 6);
/// ```
pub fn truncation_width(
    family: &SplineFamily,
    tol: f64,
    criterion: Criterion,
) -> Result<WidthChoice, SsplineError> {
    WidthChooser::new(family, tol)?.choose(tol, criterion)
}

/// Refuses a tolerance outside the open interval (0, 1) (NaN included):
/// what every width search accepts, checked by callers that estimate the
/// search's cost before starting it.
pub fn check_tol(tol: f64) -> Result<(), SsplineError> {
    if tol > 0.0 && tol < 1.0 {
        Ok(())
    } else {
        Err(SsplineError::InvalidTolerance(tol))
    }
}

/// Chooses widths for one family and any tolerance `≥ min_tol`, sharing one
/// [`TruncationAnalysis`] (for tables over many tolerances and criteria).
#[derive(Debug, Clone)]
pub struct WidthChooser {
    analysis: TruncationAnalysis<Work>,
}

impl WidthChooser {
    /// Prepares the analysis up to the width limit of `min_tol`.
    pub fn new(family: &SplineFamily, min_tol: f64) -> Result<Self, SsplineError> {
        family.validate()?;
        check_tol(min_tol)?;
        let expansion = PoleExpansion::<Work>::new(family)?;
        let n_max = width_limit(&expansion, &Work::from_f64_exact(min_tol))?;
        Ok(WidthChooser {
            analysis: TruncationAnalysis::new(family, n_max)?,
        })
    }

    /// The smallest `n ≥ 1` meeting `criterion` for `tol` (`min_tol ≤ tol < 1`).
    ///
    /// Method: the tail bound gives a limit `n_max` (the smallest `n` with
    /// `bound(n − 1) < tol`, which meets every criterion since
    /// `|c_n| ≤ bound(n−1)/2` and `knot ≤ uniform ≤ bound`); `n = 1, 2, …`
    /// are scanned up to it. For `uniform`, `n` with `knot(n) ≥ tol` are
    /// skipped without computing the sup (`uniform ≥ knot`). All in 128-bit
    /// MPFR, from the tail directly.
    ///
    /// Cost: `O(n_max·K·p)` for knot, plus one or two sup evaluations for
    /// uniform (each `≈ 57·(K − n)·m` products), `K ≈ n_max + 64/log2(1/ρ)`.
    /// **Accuracy**: decisions on 128-bit MPFR values of the measures; the
    /// cubic matches seed 000 eq 18 (`verify/tests/it/sspline_truncation.rs::coeff_width_of_the_cubic_matches_eq18`).
    /// **Source**: seed 000 eqs 10, 28 and the tail bound.
    pub fn choose(&self, tol: f64, criterion: Criterion) -> Result<WidthChoice, SsplineError> {
        check_tol(tol)?;
        let a = &self.analysis;
        let eps = Work::from_f64_exact(tol);
        let n_max = width_limit(a.expansion(), &eps)?;
        if n_max > a.max_n() {
            return Err(SsplineError::WidthNotFound {
                limit: a.max_n(),
                tol,
            });
        }
        for n in 1..=n_max {
            let achieved = match criterion {
                Criterion::Coeff => a.coeff_error(n),
                Criterion::Knot => a.knot_error(n),
                Criterion::Uniform if a.knot_error(n) >= eps => continue,
                Criterion::Uniform => a.uniform_error(n),
            };
            if achieved < eps {
                return Ok(WidthChoice {
                    n,
                    criterion,
                    tol,
                    achieved: achieved.to_f64(),
                    bound: round_up(&a.tail_bound(n)),
                });
            }
        }
        Err(SsplineError::WidthNotFound { limit: n_max, tol })
    }
}

/// Smallest `n ≥ 1` with `bound(n − 1) < eps`, searched up to 100 000.
fn width_limit(e: &PoleExpansion<Work>, eps: &Work) -> Result<usize, SsplineError> {
    const LIMIT: usize = 100_000;
    (1..=LIMIT)
        .find(|n| e.tail_bound(n - 1) < *eps)
        .ok_or(SsplineError::WidthNotFound {
            limit: LIMIT,
            tol: eps.to_f64(),
        })
}

/// Rounds a 128-bit bound up to f64, after inflating it by `2^{−100}` to
/// cover its own rounding errors.
fn round_up(x: &Work) -> f64 {
    let inflated = x.clone() * (Work::from_int(1) + Work::from_int(1).scale_by_pow2(-100));
    inflated.to_float().to_f64_round(Round::Up)
}

/// The smallest half-width `n ≥ 1` whose analytic tail bound
/// `2 Σ_r |κ_r| |ξ_r|^{n+1}/(1 − |ξ_r|) ≥ Σ_{|i|>n} |c_i|` is below `tol`,
/// with that bound rounded up: truncating a prefilter to `c_0..c_n` changes
/// each coefficient by at most `bound · max|s|`, guaranteed (the guarantee
/// the engine's truncated route and its parallel blocks rest on).
/// 320-bit MPFR; cost one pole expansion and `O(n)` bound evaluations.
///
/// ```
/// use splinelab::sspline::{SplineFamily, width::certified_width};
/// let (n, bound) = certified_width(&SplineFamily::Order(4), 1e-10).unwrap();
/// assert!(bound < 1e-10 && n == 18);
/// ```
pub fn certified_width(family: &SplineFamily, tol: f64) -> Result<(usize, f64), SsplineError> {
    family.validate()?;
    check_tol(tol)?;
    let e = PoleExpansion::<Work>::new(family)?;
    let eps = Work::from_f64_exact(tol);
    let n = width_limit(&e, &eps)?.saturating_sub(1).max(1);
    let n = if e.tail_bound(n) < eps { n } else { n + 1 };
    Ok((n, round_up(&e.tail_bound(n))))
}

/// The f64 saturation width: the smallest `n` whose tail bound is at most
/// `2^{−54}` (half an ulp of 1). Widening beyond it cannot change an f64
/// curve value `Σ_k P_k S_n(x−k)` with `|P_k| ≤ 1` by more than half an ulp
/// of 1 — the largest width that still matters in `f64`.
///
/// ```
/// use splinelab::sspline::{SplineFamily, f64_saturation_width};
/// // Cubic: 2√3 ρ^{n+1}/(1−ρ) ≤ 2^{−54} with ρ = 2 − √3 first at n = 29.
/// assert_eq!(f64_saturation_width(&SplineFamily::Order(4)).unwrap(), 29);
/// ```
pub fn f64_saturation_width(family: &SplineFamily) -> Result<usize, SsplineError> {
    family.validate()?;
    let e = PoleExpansion::<Work>::new(family)?;
    let half_ulp = Work::from_int(1).scale_by_pow2(-54);
    Ok(width_limit(&e, &half_ulp)?.saturating_sub(1).max(1))
}
