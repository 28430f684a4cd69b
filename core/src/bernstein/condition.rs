//! Condition numbers of evaluating a polynomial in Bernstein or power form,
//! the classic a-priori error bounds, and the rigorous running-error
//! arithmetic ([`Running`], [`RoundingModel`]) with which every bounded
//! evaluator in [`crate::bernstein`] computes its a-posteriori bound.
//!
//! **References**: Farouki & Rajan, *On the numerical condition of
//! polynomials in Bernstein form*, CAGD 4 (1987); Higham, *Accuracy and
//! Stability of Numerical Algorithms*, 2nd ed., §3.1 (γ_k) and §5.1 (running
//! error analysis); Jiang, Li, Cheng & Su, *Accurate evaluation of a
//! polynomial in Bernstein form*, Comput. Math. Appl. 60 (2010) (the
//! compensated bound).

use super::bezier::BernsteinPoly;
use crate::scalar::Real;
use nalgebra::ComplexField;

/// `|x|` without the `Signed`/`ComplexField` method ambiguity of generic code.
pub(crate) fn abs<T: Real>(x: &T) -> T {
    ComplexField::abs(x.clone())
}

/// An upper bound `η` on the absolute error of one rounded operation whose
/// result underflows: the smallest positive normal number, taken as
/// `4 / max_finite` (exactly `2^−1022` in f64; an over-estimate for MPFR's
/// symmetric exponent range). nalgebra's `RealField::min_value` cannot serve:
/// for f64 it is the most negative value.
pub fn underflow_unit<T: Real>() -> T {
    let four = T::from_f64_exact(4.0);
    match <T as nalgebra::RealField>::max_value() {
        Some(max) if max.is_finite() && max > T::zero() => four / max,
        _ => T::from_f64_exact(f64::MIN_POSITIVE),
    }
}

/// A computed value together with a rigorous bound on its absolute error:
/// the exact quantity it approximates lies in `[value − radius, value + radius]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Running<T> {
    /// The computed (rounded) value.
    pub value: T,
    /// Upper bound on `|value − exact|`.
    pub radius: T,
}

impl<T: Real> Running<T> {
    /// A value known exactly (radius 0).
    pub fn exact(value: T) -> Self {
        Running {
            value,
            radius: T::zero(),
        }
    }
}

/// The rounding model of `T` and the operations on [`Running`] values.
///
/// **Model**: round to nearest, `|fl(z) − z| ≤ u|fl(z)| + η` with
/// `u = 2^(−BITS)` and `η` the smallest positive normal number (this covers
/// gradual underflow in f64 and MPFR's flush-to-zero-or-minimum alike).
///
/// **Rigour**: the radius of each operation, `u|z| + Σ(propagated terms) + 4η`,
/// is itself computed in `T` on non-negative numbers; each of its at most 15
/// operations rounds down by at most a factor `(1 − u)` (underflow losses are
/// covered by the three extra `η`), so multiplying by `grow = 1 + 16u`
/// (exact in binary) makes the computed radius an upper bound of the exact
/// one. No directed rounding and no first-order approximation are involved:
/// the bounds hold for every input whose intermediate results stay finite
/// (overflow is reported by the evaluators as an error).
///
/// **Cost**: 5–12 extra flops per operation.
#[derive(Clone, Debug)]
pub struct RoundingModel<T> {
    u: T,
    eta4: T,
    grow: T,
}

impl<T: Real> Default for RoundingModel<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real> RoundingModel<T> {
    /// The model of `T` (`u = T::unit_roundoff()`).
    pub fn new() -> Self {
        let u = T::unit_roundoff();
        let eta = underflow_unit::<T>();
        RoundingModel {
            eta4: eta.scale_by_pow2(2),
            grow: T::one() + u.clone().scale_by_pow2(4),
            u,
        }
    }

    /// The unit roundoff `u`.
    pub fn unit_roundoff(&self) -> &T {
        &self.u
    }

    /// `grow · (u|z| + Σ extra + 4η)`: the radius of a rounded result `z`
    /// whose exact operands carried the propagated errors `extra`.
    fn settle(&self, z: &T, extra: &[T]) -> T {
        let mut s = self.u.clone() * abs(z);
        for e in extra {
            s += e.clone();
        }
        (s + self.eta4.clone()) * self.grow.clone()
    }

    /// The rounding error bound of a value computed by one correctly rounded
    /// operation on exact operands (or a correctly rounded conversion).
    pub fn rounded(&self, z: T) -> Running<T> {
        let radius = self.settle(&z, &[]);
        Running { value: z, radius }
    }

    /// `x + y` with `|Δ| ≤ u|z| + e_x + e_y (+η)`.
    pub fn add(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() + y.value.clone();
        let radius = self.settle(&z, &[x.radius.clone(), y.radius.clone()]);
        Running { value: z, radius }
    }

    /// `x − y`, bounded as [`add`](Self::add).
    pub fn sub(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() - y.value.clone();
        let radius = self.settle(&z, &[x.radius.clone(), y.radius.clone()]);
        Running { value: z, radius }
    }

    /// `x · y` with `|Δ| ≤ u|z| + |x|e_y + |y|e_x + e_x e_y (+η)`.
    pub fn mul(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() * y.value.clone();
        let cross = [
            abs(&x.value) * y.radius.clone(),
            abs(&y.value) * x.radius.clone(),
            x.radius.clone() * y.radius.clone(),
        ];
        let radius = self.settle(&z, &cross);
        Running { value: z, radius }
    }

    /// `x / y`: `|X/Y − x/y| ≤ (e_x + |x/y| e_y)/(|y| − e_y)` with
    /// `|x/y| ≤ (1 + 2u)|z| + η`. The radius is `+∞` when the error interval
    /// of `y` contains 0.
    pub fn div(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() / y.value.clone();
        let two_u = self.u.clone().scale_by_pow2(1);
        // A lower bound of d = |y| − e_y: fl(fl(d)(1 − 2u)) ≤ d(1 + u)²(1 − 2u) ≤ d.
        let low = (abs(&y.value) - y.radius.clone()) * (T::one() - two_u.clone());
        let prop = if low > T::zero() {
            let q = abs(&z) * (T::one() + two_u) + self.eta4.clone();
            (x.radius.clone() + q * y.radius.clone()) / low
        } else {
            T::from_f64_exact(f64::INFINITY)
        };
        let radius = self.settle(&z, &[prop]);
        Running { value: z, radius }
    }

    /// `xⁿ` by binary powering (`⌊log₂ n⌋ + popcount(n) − 1` multiplications).
    pub fn powi(&self, x: &Running<T>, mut n: usize) -> Running<T> {
        let mut acc = Running::exact(T::one());
        let mut base = x.clone();
        while n > 0 {
            if n & 1 == 1 {
                acc = self.mul(&acc, &base);
            }
            n >>= 1;
            if n > 0 {
                base = self.mul(&base, &base);
            }
        }
        acc
    }
}

/// `γ_k = k u / (1 − k u)` (Higham §3.1): `|Π_{i≤k} (1 + δ_i)^{±1} − 1| ≤ γ_k`.
/// Returns `+∞` when `k u ≥ 1`.
pub fn gamma<T: Real>(k: usize) -> T {
    let ku = T::from_f64_exact(k as f64) * T::unit_roundoff();
    if ku >= T::one() {
        return T::from_f64_exact(f64::INFINITY);
    }
    ku.clone() / (T::one() - ku)
}

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
/// use splinelab::bernstein::{bezier::BernsteinPoly, condition::cond_bernstein};
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
/// use splinelab::bernstein::condition::cond_power;
/// // 1 − 2t at t = 1/4: (1 + 1/2)/(1/2) = 3 — worse than the Bernstein basis.
/// assert_eq!(cond_power(&[1.0f64, -2.0], &0.25), Some(3.0));
/// ```
pub fn cond_power<T: Real>(monomial: &[T], t: &T) -> Option<T> {
    let value = monomial
        .iter()
        .rev()
        .fold(T::zero(), |acc, a| acc * t.clone() + a.clone());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    use rug::Rational;

    /// The running radius of a long chain of operations encloses the exact
    /// result (computed in rationals).
    #[test]
    fn running_radius_encloses_exact_chain() {
        let m = RoundingModel::<f64>::new();
        let mut x = Running::exact(0.1f64);
        let mut exact = Rational::from_f64(0.1).unwrap();
        let c = Rational::from_f64(1.0 / 3.0).unwrap();
        for k in 0..200 {
            let y = Running::exact(1.0 / 3.0);
            if k % 3 == 0 {
                x = m.mul(&x, &y);
                exact *= &c;
            } else if k % 3 == 1 {
                x = m.add(&x, &y);
                exact += &c;
            } else {
                x = m.div(&x, &m.rounded(0.7 + 1.0 / 3.0));
                exact /= Rational::from_f64(0.7 + 1.0 / 3.0).unwrap();
            }
            let err = (Rational::from_f64(x.value).unwrap() - &exact).abs();
            assert!(err <= Rational::from_f64(x.radius).unwrap(), "step {k}");
        }
    }

    #[test]
    fn gamma_matches_formula_in_mp() {
        type M = Mp<100>;
        let g: M = gamma(30);
        let u = Rational::from((1, 1)) >> 100u32;
        let want = Rational::from(30) * &u / (Rational::from(1) - Rational::from(30) * &u);
        assert_eq!(g, M::from_rational(&want));
    }
}
