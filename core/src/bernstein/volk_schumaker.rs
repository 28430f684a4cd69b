//! The VS (Volk–Schumaker) Horner-like `O(n)` evaluation of the Bernstein form.
//!
//! **Method** (Schumaker & Volk, *Efficient evaluation of multivariate
//! polynomials*, CAGD 3 (1986)): for `t ≤ ½` factor out `(1 − t)ⁿ`,
//! `p(t) = (1 − t)ⁿ Σ C(n, i) b_i sⁱ` with `s = t/(1 − t)`, and evaluate the
//! sum by Horner's rule with the binomial ratios folded in,
//! `q_n = b_n`, `q_i = b_i + s · ((n − i)/(i + 1)) · q_{i+1}`, `p = (1 − t)ⁿ q_0`.
//! For `t > ½` the roles of `t` and `1 − t` swap (`s = (1 − t)/t`, the
//! coefficients reversed, factor `tⁿ`), so that `|s| ≤ 1` on `[0, 1]`.
//!
//! **Limits at high degree** (guarded): `q_0` can reach `2ⁿ max|b_i|` and the
//! factor can be as small as `2⁻ⁿ`; in f64 this overflows/underflows once
//! `n + log₂ max|b_i| > 1023` or `n > 1021`. [`volk_schumaker`] checks both
//! against the exponent range of `T` and returns
//! [`BezierError::DegreeOutOfRange`] instead of a wrong result (for `Mp` the
//! range is about `±2^{30}` in the exponent: no practical limit).

use super::bezier::{BernsteinPoly, BezierError, Evaluation, check_parameter, finite};
use crate::scalar::Real;
use crate::scalar::running_error::{RoundingModel, Running, abs, underflow_unit};

const METHOD: &str = "vs";

/// Checks that `2ⁿ max|b_i|` is finite and `2⁻ⁿ` is a normal number of `T`.
fn check_range<T: Real>(poly: &BernsteinPoly<T>) -> Result<(), BezierError> {
    let n = poly.degree();
    let fail = |reason| {
        Err(BezierError::DegreeOutOfRange {
            method: METHOD,
            degree: n,
            reason,
        })
    };
    let Ok(k) = i32::try_from(n) else {
        return fail("the degree exceeds the exponent range");
    };
    let max = poly
        .coeffs()
        .iter()
        .map(abs)
        .fold(T::zero(), |m, x| m.max(x));
    if !max.scale_by_pow2(k).is_finite() {
        return fail("the Horner sum 2ⁿ·max|b_i| overflows");
    }
    let eta = underflow_unit::<T>();
    if T::one().scale_by_pow2(-k) < eta {
        return fail("the factor (1 − t)ⁿ ≥ 2⁻ⁿ underflows");
    }
    Ok(())
}

/// `xⁿ` by binary powering, the same multiplications as
/// [`RoundingModel::powi`] (so the bounded and plain routines agree bit for bit).
fn powi<T: Real>(x: &T, mut n: usize) -> T {
    let mut acc = T::one();
    let mut base = x.clone();
    while n > 0 {
        if n & 1 == 1 {
            acc *= base.clone();
        }
        n >>= 1;
        if n > 0 {
            base = base.clone() * base;
        }
    }
    acc
}

/// `(s, base, reversed)`: the Horner variable, the base of the factor and
/// whether the coefficients are taken in reverse order (`t > ½`).
fn reduce<T: Real>(t: &T) -> (T, T, bool) {
    let half = T::one().scale_by_pow2(-1);
    let r = T::one() - t.clone();
    if *t <= half {
        (t.clone() / &r, r, false)
    } else {
        (r / t.clone(), t.clone(), true)
    }
}

/// `p(t)` by the VS scheme (see the module docs).
///
/// **Cost**: `3n` multiplications, `2n + 1` divisions, `n` additions and a
/// binary power — `O(n)` like Horner, with no conversion. **Accuracy**: for
/// `t ∈ [0, 1]` `|p̂ − p| ≤ γ_{c n} Σ |b_i| B_i^n(t)` with a small constant `c`
/// (every term of the expanded sum is a product of `O(n)` rounded factors and
/// no cancellation happens beyond that of the data; Delgado & Peña,
/// *Running relative error for the evaluation of polynomials*, SIAM J. Sci.
/// Comput. 31 (2009)) — stable like de Casteljau at linear cost.
///
/// ```
/// use splinelab::bernstein::{bezier::BernsteinPoly, volk_schumaker::volk_schumaker};
/// let p = BernsteinPoly::new(vec![0.25f64, -0.25, 0.25]).unwrap();
/// assert_eq!(volk_schumaker(&p, &0.75), Ok(0.0625));
/// ```
pub fn volk_schumaker<T: Real>(poly: &BernsteinPoly<T>, t: &T) -> Result<T, BezierError> {
    check_parameter(t)?;
    check_range(poly)?;
    let n = poly.degree();
    let (s, base, reversed) = reduce(t);
    let b = poly.coeffs();
    let coeff = |i: usize| {
        if reversed {
            b[n - i].clone()
        } else {
            b[i].clone()
        }
    };
    let mut q = coeff(n);
    for i in (0..n).rev() {
        let ratio = T::from_f64_exact((n - i) as f64) / T::from_f64_exact((i + 1) as f64);
        q = coeff(i) + s.clone() * ratio * q;
    }
    finite(powi(&base, n) * q, METHOD, n)
}

/// [`volk_schumaker`] with a rigorous running error bound (the same
/// operations in [`Running`] arithmetic; the power by binary powering).
/// Valid for every finite `t` (extrapolation is flagged). **Cost**: about 6×
/// [`volk_schumaker`].
pub fn volk_schumaker_bounded<T: Real>(
    poly: &BernsteinPoly<T>,
    t: &T,
) -> Result<Evaluation<T>, BezierError> {
    let extrapolated = check_parameter(t)?;
    check_range(poly)?;
    let m = RoundingModel::<T>::new();
    let n = poly.degree();
    let half = T::one().scale_by_pow2(-1);
    let tr = Running::exact(t.clone());
    let r = m.sub(&Running::exact(T::one()), &tr);
    let reversed = *t > half;
    let (s, base) = if reversed {
        (m.div(&r, &tr), tr)
    } else {
        (m.div(&tr, &r), r)
    };
    let b = poly.coeffs();
    let coeff = |i: usize| {
        Running::exact(if reversed {
            b[n - i].clone()
        } else {
            b[i].clone()
        })
    };
    let mut q = coeff(n);
    for i in (0..n).rev() {
        let num = Running::exact(T::from_f64_exact((n - i) as f64));
        let ratio = m.div(&num, &Running::exact(T::from_f64_exact((i + 1) as f64)));
        q = m.add(&coeff(i), &m.mul(&m.mul(&s, &ratio), &q));
    }
    let value = m.mul(&m.powi(&base, n), &q);
    Evaluation::finish(value, extrapolated, METHOD, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degree_guard_in_f64() {
        let p = BernsteinPoly::new(vec![1.0f64; 1100]).unwrap();
        assert!(matches!(
            volk_schumaker(&p, &0.25),
            Err(BezierError::DegreeOutOfRange { degree: 1099, .. })
        ));
        let big = BernsteinPoly::new(vec![1e300f64; 40]).unwrap();
        assert!(matches!(
            volk_schumaker(&big, &0.25),
            Err(BezierError::DegreeOutOfRange { .. })
        ));
    }
}
