//! `prefilter`: a user's interpolation coefficients `D` against the solution
//! of the interpolation conditions solved directly in MPFR
//! ([`interpolation_coefficients`], whose module documents the reference),
//! with the componentwise bound of a backward-stable banded solve
//! ([`solve_bound`]). Cost `O(N q²)` per precision.

use super::agreement::{Reference, certify};
use super::format::UserFormat;
pub use super::interpolation_conditions::{
    DEGREES, EXACT_MODES, Mode, ParseMode, extend, family_of_degree, interpolation_coefficients,
    scipy_filter_rule,
};
use super::stable_bound::{solve_bound, solve_constant};
use super::summary::{BoundBasis, CheckSummary, Context, summarize_bounded};
use super::{CheckError, require_finite, require_len};
use splinelab::scalar::Real;
use splinelab::sspline::SplineFamily;
use splinelab::sspline::euler_frobenius::poles;

/// Largest number of samples (times the half-bandwidth) a check accepts.
pub const MAX_WORK: usize = 20_000_000;

/// The boundary horizon at the user's precision: `h = ⌈bits · ln 2 / −ln ρ⌉`,
/// `ρ` the dominant pole magnitude — the distance over which an end
/// condition still moves a coefficient by one unit roundoff (0 without poles).
pub fn horizon(family: &SplineFamily, format: UserFormat) -> Result<usize, CheckError> {
    let xi: Vec<f64> = poles(family)?;
    let rho = xi.iter().map(|x| x.abs()).fold(0.0, f64::max);
    Ok(if rho == 0.0 {
        0
    } else {
        (format.bits() as f64 * std::f64::consts::LN_2 / -rho.ln()).ceil() as usize
    })
}

/// The account of the prefilter's stable bound (half-bandwidth `q`).
pub fn solve_bound_text(q: usize, format: UserFormat) -> String {
    format!(
        "componentwise (Skeel) bound of a backward-stable banded solve in {}: \
         γ_{}/(1 − γ_{})·(|B⁻¹||B||c|)_k + u|c_k| = {:.3e}·(|B⁻¹||B||c|)_k + u|c_k| \
         (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., §7.2 and Thm 9.4 \
         with bandwidth w = q + 1 = {}, one more u for the rounded matrix entries)",
        format.name(),
        3 * (q + 1) + 1,
        q + 1,
        solve_constant(q, format),
        q + 1
    )
}

/// What `check prefilter` is given.
#[derive(Debug, Clone)]
pub struct PrefilterInput {
    /// The samples `s_j`, exactly as the user has them.
    pub samples: Vec<f64>,
    /// The user's coefficients `D_j`.
    pub user: Vec<f64>,
    /// The user's format (f32 data is judged in f32 ulps).
    pub format: UserFormat,
    /// The basis (degree `d` is order `d + 1`).
    pub family: SplineFamily,
    /// The end mode.
    pub mode: Mode,
    /// `--max-ulps`.
    pub max_ulps: Option<f64>,
}

struct PrefilterReference<'a> {
    samples: &'a [f64],
    family: &'a SplineFamily,
    mode: Mode,
}

impl Reference for PrefilterReference<'_> {
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        let s: Vec<T> = self.samples.iter().map(|x| T::from_f64_exact(*x)).collect();
        interpolation_coefficients(&s, self.family, self.mode)
    }
}

/// Checks the user's prefilter output. Inputs are validated first (equal
/// lengths, finite samples, non-empty, within [`MAX_WORK`]); non-finite user
/// coefficients are failed elements.
pub fn check_prefilter(input: &PrefilterInput) -> Result<CheckSummary, CheckError> {
    let n = input.samples.len();
    if n == 0 {
        return Err(CheckError::Empty("samples".into()));
    }
    require_len("coefficients", n, input.user.len())?;
    require_finite("samples", &input.samples)?;
    let q = input.family.pole_count().max(1);
    if n.saturating_mul(q) > MAX_WORK {
        return Err(CheckError::TooLarge(format!(
            "{n} samples × half-bandwidth {q} exceeds {MAX_WORK}"
        )));
    }
    let r = PrefilterReference {
        samples: &input.samples,
        family: &input.family,
        mode: input.mode,
    };
    let cert = certify(&r, input.format, 0)?;
    let ctx = Context {
        kind: "prefilter",
        format: input.format,
        reference_bits: Some(cert.bits),
        reference: format!(
            "banded solve of the interpolation conditions ({} mode), MPFR {} bits agreeing with {} bits",
            input.mode.name(),
            cert.bits,
            cert.low_bits
        ),
        horizon: Some(horizon(&input.family, input.format)?),
        max_ulps: input.max_ulps,
        bound: BoundBasis::PerElement(solve_bound_text(input.family.pole_count(), input.format)),
    };
    let (_, bounds) = solve_bound(
        &input.samples,
        &[n],
        &input.family,
        input.mode,
        input.format,
    )?;
    Ok(summarize_bounded(&ctx, &input.user, &cert.values, &bounds))
}
