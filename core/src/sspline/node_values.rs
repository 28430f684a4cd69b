//! Exact node values `V_j` of the centred basis: the values `β(j)` at the
//! interpolation nodes, which are the coefficients of the Euler–Frobenius
//! polynomial (seed 000 eq 11, 19, 37).

use super::{SplineFamily, SsplineError, beta2, bspline_uniform::uniform_bspline_exact};
use crate::scalar::Real;
use rug::Rational;

/// `[V_1, …, V_{d+1}]`, exactly, `d = 2p` the Euler–Frobenius degree:
///
/// - even order `m = 2k`: `V_j = N_{0,m}(j)`, `j = 1..m−1` (eq 11);
/// - odd order `m = 2k+1`: `V_j = N_{0,m}(j − ½)`, `j = 1..m` (eq 19) — the
///   nodes of an odd-order S-spline sit at the centres of the knot intervals;
/// - Beta2: `[2, β2 + 8, 2]/(β2 + 12)` (eq 37).
///
/// `V_{p+1+j} = β(j)`; the list is symmetric, positive and sums to 1.
/// Cost: `O(m²)` big-rational operations (eq 31 per node).
///
/// ```
/// use splinelab::sspline::{SplineFamily, node_values::node_values_exact};
/// use rug::Rational;
/// let v = node_values_exact(&SplineFamily::Order(3)).unwrap();
/// assert_eq!(v, vec![Rational::from((1, 8)), Rational::from((3, 4)), Rational::from((1, 8))]);
/// ```
pub fn node_values_exact(family: &SplineFamily) -> Result<Vec<Rational>, SsplineError> {
    family.validate()?;
    Ok(match family {
        SplineFamily::Order(m) if m % 2 == 0 => (1..*m)
            .map(|j| uniform_bspline_exact(*m, &Rational::from(j)))
            .collect(),
        SplineFamily::Order(m) => (1..=*m)
            .map(|j| uniform_bspline_exact(*m, &Rational::from((2 * j as i64 - 1, 2))))
            .collect(),
        SplineFamily::Beta2(b) => beta2::node_values_exact(b),
    })
}

/// The node values correctly rounded to `T`; refused when one would not be
/// a normal number of `T` (orders above about 170 in `f64`: `V_1 = 1/(m−1)!`
/// underflows), since the poles would then be meaningless.
///
/// ```
/// // In MPFR: the quartic's node values against the exact rationals.
/// use splinelab::scalar::{Mp, Real};
/// use splinelab::sspline::{SplineFamily, node_values::{node_values, node_values_exact}};
/// type M = Mp<200>;
/// let v: Vec<M> = node_values(&SplineFamily::Order(5)).unwrap();
/// let e = node_values_exact(&SplineFamily::Order(5)).unwrap();
/// assert_eq!(v.len(), e.len());
/// for (a, b) in v.iter().zip(&e) {
///     assert!((a.clone() - M::from_rational(b)).to_f64().abs() < 1e-58);
/// }
/// ```
pub fn node_values<T: Real>(family: &SplineFamily) -> Result<Vec<T>, SsplineError> {
    let exact = node_values_exact(family)?;
    let v: Vec<T> = exact.iter().map(T::from_rational).collect();
    if !v.iter().all(is_normal) {
        return Err(SsplineError::PrecisionTooLow {
            family: family.to_string(),
            scalar: T::type_name(),
        });
    }
    Ok(v)
}

/// `x` is finite, non-zero and (for `f64`-sized types) not subnormal; MPFR's
/// exponent range makes every non-zero finite `Mp` normal.
pub(crate) fn is_normal<T: Real>(x: &T) -> bool {
    if x.is_zero() || !x.is_finite() {
        return false;
    }
    T::BITS > 64 || x.to_f64().abs() >= f64::MIN_POSITIVE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symmetric_positive_partition_of_unity() {
        for m in 2..=30 {
            let v = node_values_exact(&SplineFamily::Order(m)).unwrap();
            assert_eq!(v.len() % 2, 1, "m={m}");
            let sum: Rational = v.iter().sum();
            assert_eq!(sum, 1, "m={m}");
            assert!(v.iter().all(|x| *x > 0));
            assert!(v.iter().eq(v.iter().rev()));
        }
    }

    #[test]
    fn f64_refuses_underflowing_orders() {
        assert!(node_values::<f64>(&SplineFamily::Order(180)).is_err());
        assert!(node_values::<f64>(&SplineFamily::Order(40)).is_ok());
    }
}
