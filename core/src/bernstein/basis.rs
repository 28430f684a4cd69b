//! The Bernstein basis `B_i^n(t) = C(n, i) tᶦ (1 − t)ⁿ⁻ⁱ`.
//!
//! Seed 001 eq 1 and seed 002 (Bézier curves) are built on it.

use crate::scalar::Real;
use rug::Integer;

/// The binomial coefficient `C(n, k)` as an exact integer (0 when `k > n`).
///
/// ```
/// use splinelab::bernstein::basis::binomial;
/// assert_eq!(binomial(30, 15).to_string(), "155117520");
/// ```
pub fn binomial(n: u32, k: u32) -> Integer {
    if k > n {
        return Integer::new();
    }
    Integer::from(Integer::binomial_u(n, k))
}

/// The binomial coefficient `C(n, k)` rounded to the scalar type
/// (correctly rounded; exact while `C(n, k) < 2^BITS`).
pub fn binomial_real<T: Real>(n: u32, k: u32) -> T {
    T::from_rational(&binomial(n, k).into())
}

/// All `n + 1` Bernstein basis values `B_0^n(t), …, B_n^n(t)`.
///
/// **Method**: the triangular recurrence
/// `B_i^k(t) = (1 − t) B_i^{k−1}(t) + t B_{i−1}^{k−1}(t)`, `B_0^0 = 1`
/// (de Casteljau's scheme applied to the unit vectors).
///
/// **Cost**: `n(n+1)` multiplications, `n(n+1)/2` additions.
///
/// **Accuracy**: for `t ∈ [0, 1]` every term is non-negative, so each value
/// carries a relative error of at most `γ_{2n} = 2nu/(1 − 2nu)` (`u` the unit
/// roundoff), independently of `n`'s binomials; no cancellation occurs.
/// Outside `[0, 1]` the recurrence is still exact in exact arithmetic but
/// subject to cancellation.
///
/// Measured against exact rationals in
/// `basis.rs::tests::recurrence_matches_exact_rationals_in_mp`. **Source**:
/// Farouki & Rajan (1987); `γ_k` as in Higham, 2nd ed., §3.1.
///
/// ```
/// use splinelab::bernstein::basis::bernstein_basis;
/// let b = bernstein_basis(3, &0.5f64);
/// assert_eq!(b, vec![0.125, 0.375, 0.375, 0.125]);
/// ```
///
/// ```
/// use splinelab::bernstein::basis::bernstein_basis;
/// // In MPFR: B_i^3(1/3) = C(3, i) 2^{3−i} / 27, i.e. 8/27, 12/27, 6/27, 1/27.
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<128>;
/// let b = bernstein_basis(3, &(M::from_int(1) / M::from_int(3)));
/// for (bi, num) in b.iter().zip([8, 12, 6, 1]) {
///     assert!((bi.clone() - M::from_int(num) / M::from_int(27)).to_f64().abs() < 1e-36);
/// }
/// ```
pub fn bernstein_basis<T: Real>(n: usize, t: &T) -> Vec<T> {
    let one_minus_t = T::one() - t.clone();
    let mut b = Vec::with_capacity(n + 1);
    b.push(T::one());
    for k in 1..=n {
        // Sweep downwards so that b[i − 1] still holds level k − 1.
        let last = t.clone() * &b[k - 1];
        b.push(last);
        for i in (1..k).rev() {
            b[i] = one_minus_t.clone() * &b[i] + t.clone() * &b[i - 1];
        }
        b[0] = one_minus_t.clone() * &b[0];
    }
    b
}

/// One Bernstein basis value `B_i^n(t)`, by the direct formula
/// `C(n, i) tᶦ (1 − t)ⁿ⁻ⁱ` (the binomial rounded once, then two integer
/// powers by repeated squaring).
///
/// **Cost**: `O(log n)` multiplications. **Accuracy**: relative error
/// `≤ γ_{2⌈log₂ n⌉+3}` for `t ∈ [0, 1]` plus the rounding of `1 − t`, which is
/// exact for `t ∈ [½, 1]` (Sterbenz) and contributes at most `(n − i)u`
/// relative otherwise. Returns 0 for `i > n`.
pub fn bernstein<T: Real>(n: u32, i: u32, t: &T) -> T {
    if i > n {
        return T::zero();
    }
    let one_minus_t = T::one() - t.clone();
    binomial_real::<T>(n, i) * t.clone().powi(i as i32) * one_minus_t.powi((n - i) as i32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    use crate::scalar::prelude::*;
    use rug::Rational;

    /// Exact B_i^n(t) at a rational t.
    fn exact(n: u32, i: u32, t: &Rational) -> Rational {
        let one_minus = Rational::from(1) - t.clone();
        let p = t.clone().pow(i) * one_minus.pow(n - i);
        Rational::from(binomial(n, i)) * p
    }

    use rug::ops::Pow;

    #[test]
    fn recurrence_matches_exact_rationals_in_mp() {
        type M = Mp<200>;
        let t = Rational::from((3, 7));
        for n in [1usize, 5, 17, 40] {
            let b = bernstein_basis(n, &M::from_rational(&t));
            for (i, bi) in b.iter().enumerate() {
                let want = M::from_rational(&exact(n as u32, i as u32, &t));
                let rel = ((bi.clone() - &want) / want).abs();
                // γ_{2n} at 200 bits, with margin for the rounding of t itself.
                assert!(rel < M::from_f64_exact(4.0 * n as f64 + 2.0) * M::unit_roundoff());
            }
        }
    }

    #[test]
    fn direct_formula_matches_recurrence_in_f64() {
        for n in [3u32, 10, 25] {
            for &t in &[0.1, 0.37, 0.5, 0.9] {
                let all = bernstein_basis(n as usize, &t);
                for i in 0..=n {
                    let d = bernstein(n, i, &t);
                    let rel = ((d - all[i as usize]) / all[i as usize]).abs();
                    assert!(rel < 8.0 * n as f64 * f64::EPSILON, "n={n} i={i} t={t}");
                }
            }
        }
    }
}
