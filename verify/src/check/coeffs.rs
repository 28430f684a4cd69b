//! `coeffs`: a user's S-spline coefficients `c_0..c_{K−1}` (seed 000 eq 17)
//! for an order or a Beta2 tension, against core's partial-fraction
//! expansion run in MPFR and certified by `p / p + 64` agreement.

use super::CheckError;
use super::agreement::{Reference, certify};
use super::format::UserFormat;
use super::stable_bound::unit_roundoff;
use super::summary::{BoundBasis, CheckSummary, Context, summarize_bounded};
use splinelab::scalar::Real;
use splinelab::sspline::{CoefficientMethod, SplineFamily, coefficients};

/// Largest `K` accepted.
pub const MAX_COUNT: usize = 1_000_000;

struct CoeffsReference<'a> {
    family: &'a SplineFamily,
    count: usize,
}

impl Reference for CoeffsReference<'_> {
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        Ok(coefficients(
            self.family,
            self.count,
            CoefficientMethod::PartialFractions,
        )?)
    }
}

/// Checks `user[i] ≈ c_i`, `i = 0..K−1`. Cost: `K` MPFR powers per pole at
/// two precisions per rung of the ladder (the orders' cancellation near the
/// dominant pole is what can push the ladder up).
pub fn check_coeffs(
    family: &SplineFamily,
    user: &[f64],
    format: UserFormat,
    max_ulps: Option<f64>,
) -> Result<CheckSummary, CheckError> {
    family.validate()?;
    if user.is_empty() {
        return Err(CheckError::Empty("coefficients".into()));
    }
    if user.len() > MAX_COUNT {
        return Err(CheckError::TooLarge(format!(
            "{} coefficients exceed {MAX_COUNT}",
            user.len()
        )));
    }
    let r = CoeffsReference {
        family,
        count: user.len(),
    };
    let min_bits = (0.7 * family.spline_order() as f64) as u32 + 128;
    let cert = certify(&r, format, min_bits.min(1024))?;
    let ctx = Context {
        kind: "coeffs",
        format,
        reference_bits: Some(cert.bits),
        reference: format!(
            "partial fractions (eq 17) in MPFR {} bits agreeing with {} bits ({family})",
            cert.bits, cert.low_bits
        ),
        horizon: None,
        max_ulps,
        bound: BoundBasis::PerElement(format!(
            "u|c_k|, u = 2^-{}: the coefficients are constants, so a stable computation returns them correctly rounded, or within one rounding (Higham, Accuracy and Stability, 2nd ed., §2.2)",
            format.bits()
        )),
    };
    let u = unit_roundoff(format);
    let bounds: Vec<f64> = cert.values.iter().map(|c| u * c.to_f64().abs()).collect();
    Ok(summarize_bounded(&ctx, user, &cert.values, &bounds))
}
