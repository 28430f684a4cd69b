//! Condition numbers of evaluating a polynomial in Bernstein or power form
//! and the classic a-priori error bounds. (Condition numbers of matrices are
//! in [`crate::matrix_condition`]; the running-error arithmetic of the bounded
//! evaluators in [`crate::scalar::running_error`].)
//!
//! **References**: Farouki & Rajan, *On the numerical condition of
//! polynomials in Bernstein form*, CAGD 4 (1987); Higham, *Accuracy and
//! Stability of Numerical Algorithms*, 2nd ed., §3.1 (γ_k) and §5.1 (running
//! error analysis); Jiang, Li, Cheng & Su, *Accurate evaluation of a
//! polynomial in Bernstein form*, Comput. Math. Appl. 60 (2010) (the
//! compensated bound).

use super::bezier::BernsteinPoly;
use crate::scalar::Real;
use crate::scalar::running_error::{abs, gamma};

/// `Σ |b_i| |B_i^n(t)|`, the numerator of the Bernstein condition number, by
/// de Casteljau's recurrence on `|b_i|` with `|1 − t|` and `|t|` (every term
/// non-negative: no cancellation, relative error `≤ γ_{3n}` in `T`).
///
/// **Cost**: `3n(n+1)/2` flops.
pub fn bernstein_abs_sum<T: Real>(poly: &BernsteinPoly<T>, t: &T) -> T {
    let abs_coeffs: Vec<T> = poly.coeffs().iter().map(abs).collect();
    let r = abs(&(T::one() - t.clone()));
    super::bezier::de_casteljau_lerp(&abs_coeffs, &r, &abs(t))
}

/// The condition number of evaluating `p(t) = Σ b_i B_i^n(t)` with respect to
/// relative perturbations of the coefficients (Farouki–Rajan 1987):
/// `cond_B(p, t) = Σ |b_i| |B_i^n(t)| / |p(t)|`.
///
/// Computed in `T` (use a higher precision than the one under study, or the
/// exact rational routine of `splinelab-verify`); `p(t)` by de Casteljau.
/// `None` when `p(t)` evaluates to 0 (infinite condition).
///
/// ```
/// use splinelab::bernstein::{bezier::BernsteinPoly, poly_condition::cond_bernstein};
/// // 1 − 2t = (1 − t)·1 + t·(−1): at t = 1/4, Σ|b_i|B_i = 1, p = 1/2.
/// let p = BernsteinPoly::new(vec![1.0f64, -1.0]).unwrap();
/// assert_eq!(cond_bernstein(&p, &0.25), Some(2.0));
/// ```
pub fn cond_bernstein<T: Real>(poly: &BernsteinPoly<T>, t: &T) -> Option<T> {
    let value = poly.de_casteljau_unchecked(t);
    (!value.is_zero()).then(|| bernstein_abs_sum(poly, t) / abs(&value))
}

/// `Σ |a_i| |t|ⁱ` by Horner on non-negative terms (relative error `≤ γ_{2n}`).
pub fn power_abs_sum<T: Real>(monomial: &[T], t: &T) -> T {
    let at = abs(t);
    monomial
        .iter()
        .rev()
        .fold(T::zero(), |acc, a| acc * at.clone() + abs(a))
}

/// The condition number of evaluating `p(t) = Σ a_i tⁱ` (power basis):
/// `cond_P(p, t) = Σ |a_i| |t|ⁱ / |p(t)|`, `p(t)` by Horner in `T`.
/// `None` when `p(t)` evaluates to 0.
///
/// ```
/// use splinelab::bernstein::poly_condition::cond_power;
/// // 1 − 2t at t = 1/4: (1 + 1/2)/(1/2) = 3 — worse than the Bernstein basis.
/// assert_eq!(cond_power(&[1.0f64, -2.0], &0.25), Some(3.0));
/// ```
pub fn cond_power<T: Real>(monomial: &[T], t: &T) -> Option<T> {
    let value = monomial
        .iter()
        .rev()
        .fold(T::zero(), |acc, a| acc * t.clone() + a);
    (!value.is_zero()).then(|| power_abs_sum(monomial, t) / abs(&value))
}

/// The a-priori bound of de Casteljau's algorithm (Farouki–Rajan 1987;
/// Jiang et al. 2010, eq. (3.3)): `|p̂(t) − p(t)| ≤ γ_{3n} Σ |b_i| B_i^n(t)`,
/// valid for `t ∈ [0, 1]` (three roundings per level: `1 − t`, two products
/// and a sum). `abs_sum` is `Σ |b_i| B_i^n(t)` (see [`bernstein_abs_sum`]).
pub fn de_casteljau_a_priori<T: Real>(degree: usize, abs_sum: &T) -> T {
    gamma::<T>(3 * degree) * abs_sum.clone()
}

/// The a-priori bound of the compensated de Casteljau algorithm (Jiang, Li,
/// Cheng & Su 2010, Theorem 4): `|res − p(t)| ≤ u|p(t)| + 2γ_{3n}² Σ |b_i| B_i^n(t)`,
/// i.e. relative error `≤ u + 2γ_{3n}² cond_B(p, t)`, for `t ∈ [0, 1]` and
/// without underflow. `abs_value` is `|p(t)|`.
pub fn compensated_a_priori<T: Real>(degree: usize, abs_sum: &T, abs_value: &T) -> T {
    let g = gamma::<T>(3 * degree);
    T::unit_roundoff() * abs_value.clone() + (g.clone() * g).scale_by_pow2(1) * abs_sum.clone()
}
