//! Error metrics: one set of comparison helpers for every study and test.
//!
//! References are MPFR floats (`rug::Float`) of at least twice the bits the
//! claim needs; the value under test is converted to the reference's
//! precision exactly (an f64 always fits in 53 bits).

use nalgebra::SVector;
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

/// `max_k |a_k − b_k| / (ε · max_k |b_k|)`: the worst difference of two
/// f64 arrays in units of the machine epsilon of the reference's largest
/// magnitude (how scipy agreement is judged: normwise, so small values are
/// not held to their own ulps). Panics if the lengths differ (a test bug).
///
/// ```
/// use splinelab_verify::metrics::ulps_of_max;
/// let b = [1.0, -4.0, 0.5];
/// let a = [1.0, -4.0 + 8.0 * f64::EPSILON, 0.5];
/// assert_eq!(ulps_of_max(&a, &b), 2.0);
/// ```
pub fn ulps_of_max<'a>(
    a: impl IntoIterator<Item = &'a f64>,
    b: impl IntoIterator<Item = &'a f64, IntoIter: Clone>,
) -> f64 {
    let b = b.into_iter();
    let scale = b.clone().fold(0.0f64, |m, x| m.max(x.abs())) * f64::EPSILON;
    let (mut worst, mut count) = (0.0f64, (0usize, 0usize));
    let mut a = a.into_iter();
    for y in b {
        count.1 += 1;
        if let Some(x) = a.next() {
            count.0 += 1;
            worst = worst.max((x - y).abs());
        }
    }
    assert!(
        a.next().is_none() && count.0 == count.1,
        "arrays of different lengths"
    );
    worst / scale
}

/// `max_k |a_k − r_k| / (ε · max_k |r_k|)` with `ε = 2^{1−BITS}` the machine
/// epsilon of `T`: [`ulps_of_max`] of a result in any format against a
/// higher-precision reference, each difference formed from the exact values
/// in MPFR (the reference is never rounded to `T` first, which would add up
/// to half a unit per element). Panics if the lengths differ (a test bug).
///
/// ```
/// use splinelab::scalar::Mp;
/// use splinelab_verify::metrics::eps_of_max;
/// let r = [Mp::<128>::new(1.0), Mp::new(-4.0)];
/// let a = [1.0f32, -4.0 + 8.0 * f32::EPSILON];
/// assert_eq!(eps_of_max(&a, &r), 2.0);
/// ```
pub fn eps_of_max<T: Real, R: Real>(a: &[T], reference: &[R]) -> f64 {
    assert_eq!(a.len(), reference.len(), "arrays of different lengths");
    let scale = reference
        .iter()
        .fold(0.0f64, |m, r| m.max(r.to_f64().abs()))
        * (1.0 - T::BITS as f64).exp2();
    let worst = a.iter().zip(reference).fold(0.0f64, |m, (x, r)| {
        let r = r.to_float();
        let prec = r.prec().max(T::BITS) + 2;
        m.max(Float::with_val(prec, x.to_float() - &r).abs().to_f64())
    });
    worst / scale
}

// ---- errors of geometric results, in units of `u` ------------------------
//
// Computed in MPFR at `2·BITS + 64` bits from the exact values of the
// computed result, so the measurement adds no rounding of its own.

/// Precision of the references for `T`: `2·BITS + 64`.
pub fn ref_prec<T: Real>() -> u32 {
    2 * T::BITS + 64
}

/// `x` as an MPFR float of the reference precision (exact).
pub fn fl<T: Real>(x: &T) -> Float {
    Float::with_val(ref_prec::<T>(), x.to_float())
}

/// `‖a − b‖₂` in the reference precision from the exact values of `a`, `b`.
pub fn dist_ref<T: Real, const D: usize>(a: &SVector<T, D>, b: &SVector<T, D>) -> Float {
    let p = ref_prec::<T>();
    let mut s = Float::with_val(p, 0);
    for (x, y) in a.iter().zip(b.iter()) {
        let d = Float::with_val(p, fl(x) - fl(y));
        s += d.square();
    }
    s.sqrt()
}

/// `‖a‖_∞` over a set of points (the data scale), as f64, at least 1e-300.
pub fn scale<T: Real, const D: usize>(points: &[SVector<T, D>]) -> f64 {
    points
        .iter()
        .flat_map(|p| p.iter())
        .map(|x| x.to_f64().abs())
        .fold(1e-300, f64::max)
}

/// An error in units of `u` of `T` relative to `scale`.
pub fn in_u<T: Real>(err: &Float, scale: f64) -> f64 {
    (err.clone() / scale / T::unit_roundoff().to_float()).to_f64()
}

/// `|‖p − c‖ − r| / r` in units of `u` (computed in the reference precision).
pub fn radial_error_u<T: Real, const D: usize>(p: &SVector<T, D>, c: &SVector<T, D>, r: &T) -> f64 {
    let d = dist_ref(p, c) - fl(r);
    in_u::<T>(&d.abs(), r.to_f64())
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
