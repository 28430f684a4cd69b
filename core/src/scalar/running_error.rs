//! Rigorous running-error arithmetic: a computed value with a bound on its
//! absolute error ([`Running`]), propagated through each rounded operation
//! by the rounding model of the scalar ([`RoundingModel`]), and Higham's
//! `γ_k`. Every bounded evaluator in [`crate::bernstein`] computes its
//! a-posteriori bound with it.
//!
//! **References**: Higham, *Accuracy and Stability of Numerical Algorithms*,
//! 2nd ed., §2.2 (the model), §3.1 (`γ_k`) and §5.1 (running error analysis).

use super::Real;
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
        let mut s = abs(z) * &self.u;
        for e in extra {
            s += e;
        }
        (s + &self.eta4) * &self.grow
    }

    /// The rounding error bound of a value computed by one correctly rounded
    /// operation on exact operands (or a correctly rounded conversion).
    pub fn rounded(&self, z: T) -> Running<T> {
        let radius = self.settle(&z, &[]);
        Running { value: z, radius }
    }

    /// `x + y` with `|Δ| ≤ u|z| + e_x + e_y (+η)`.
    pub fn add(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() + &y.value;
        let radius = self.settle(&z, &[x.radius.clone(), y.radius.clone()]);
        Running { value: z, radius }
    }

    /// `x − y`, bounded as [`add`](Self::add).
    pub fn sub(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() - &y.value;
        let radius = self.settle(&z, &[x.radius.clone(), y.radius.clone()]);
        Running { value: z, radius }
    }

    /// `x · y` with `|Δ| ≤ u|z| + |x|e_y + |y|e_x + e_x e_y (+η)`.
    pub fn mul(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() * &y.value;
        let cross = [
            abs(&x.value) * &y.radius,
            abs(&y.value) * &x.radius,
            x.radius.clone() * &y.radius,
        ];
        let radius = self.settle(&z, &cross);
        Running { value: z, radius }
    }

    /// `x / y`: `|X/Y − x/y| ≤ (e_x + |x/y| e_y)/(|y| − e_y)` with
    /// `|x/y| ≤ (1 + 2u)|z| + η`. The radius is `+∞` when the error interval
    /// of `y` contains 0.
    /// **Method**: one rounded division plus a radius from the formula above.
    /// **Source**: running error analysis, Higham, 2nd ed., §3.3; the enclosure
    /// is tested in `running_error.rs::tests::running_radius_encloses_exact_chain`.
    pub fn div(&self, x: &Running<T>, y: &Running<T>) -> Running<T> {
        let z = x.value.clone() / &y.value;
        let two_u = self.u.clone().scale_by_pow2(1);
        // A lower bound of d = |y| − e_y: fl(fl(d)(1 − 2u)) ≤ d(1 + u)²(1 − 2u) ≤ d.
        let low = (abs(&y.value) - &y.radius) * (T::one() - &two_u);
        let prop = if low > T::zero() {
            let q = abs(&z) * (T::one() + two_u) + &self.eta4;
            (q * &y.radius + &x.radius) / low
        } else {
            T::from_f64_exact(f64::INFINITY)
        };
        let radius = self.settle(&z, &[prop]);
        Running { value: z, radius }
    }

    /// `xⁿ` by binary powering (`⌊log₂ n⌋ + popcount(n) − 1` multiplications).
    /// **Accuracy**: each multiplication propagates the radius as [`Self::mul`]
    /// does, so the result's radius bounds the accumulated error.
    /// **Source**: Higham, 2nd ed., §3.3 (running error analysis).
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
