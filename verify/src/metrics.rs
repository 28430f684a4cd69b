//! Error metrics: one set of comparison helpers for every study and test.
//!
//! References are MPFR floats (`rug::Float`) of at least twice the bits the
//! claim needs; the value under test is converted to the reference's
//! precision exactly (an f64 always fits in 53 bits).

use rug::Float;
use splinelab::scalar::Real;

/// Decimal digits carried by an f64: `53 · log10 2 ≈ 15.95`.
pub const F64_DIGITS: f64 = 53.0 * std::f64::consts::LOG10_2;

/// `|x − r| / |r|` evaluated in the reference's precision and rounded to
/// f64; `|x − r|` when `r = 0`. Infinite if `x` is not finite.
pub fn relative_error<T: Real>(x: &T, reference: &Float) -> f64 {
    let x = x.to_float();
    if !x.is_finite() {
        return f64::INFINITY;
    }
    let prec = reference.prec().max(x.prec());
    let diff = Float::with_val(prec, &x - reference).abs();
    if reference.is_zero() {
        diff.to_f64()
    } else {
        (diff / reference.clone().abs()).to_f64()
    }
}

/// The number of correct significant decimal digits implied by a relative
/// error: `−log10(rel)`, capped at `cap` (the digits the format carries) and
/// floored at 0. An exact result gets `cap`.
pub fn correct_digits(rel: f64, cap: f64) -> f64 {
    if rel == 0.0 {
        cap
    } else {
        (-rel.log10()).clamp(0.0, cap)
    }
}

/// The distance from `x` to `reference` in units in the last place of the
/// f64 nearest to the reference (`ulp(r) = 2^(e−52)` for `r ∈ [2^e, 2^(e+1))`).
pub fn ulps_f64(x: f64, reference: &Float) -> f64 {
    let r = reference.to_f64();
    if !x.is_finite() || !r.is_finite() {
        return f64::INFINITY;
    }
    let ulp = if r == 0.0 {
        f64::from_bits(1)
    } else {
        let e = r.abs().log2().floor() as i32;
        2f64.powi(e - 52).max(f64::from_bits(1))
    };
    let diff = Float::with_val(reference.prec().max(64), x - reference).abs();
    (diff / ulp).to_f64()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_ulp_off_is_one_ulp() {
        let r = Float::with_val(200, 1.5);
        assert_eq!(ulps_f64(1.5 + f64::EPSILON, &r), 1.0);
        assert_eq!(
            relative_error(&(1.5 + f64::EPSILON), &r),
            f64::EPSILON / 1.5
        );
    }

    #[test]
    fn digits_are_capped_and_floored() {
        assert_eq!(correct_digits(0.0, F64_DIGITS), F64_DIGITS);
        assert_eq!(correct_digits(10.0, F64_DIGITS), 0.0);
        assert!((correct_digits(1e-5, F64_DIGITS) - 5.0).abs() < 1e-12);
    }
}
