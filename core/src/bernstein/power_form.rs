//! The power (monomial) form `p(t) = Σ a_i tⁱ` of a Bernstein polynomial and
//! its Horner evaluation — seed 002's "method 1: evaluate the polynomial as it
//! stands: simple and fast, but may be numerically unstable".
//!
//! **Conversion**: `a_i = C(n, i) Δⁱ b_0` (forward differences of the
//! Bernstein coefficients, `Δ b_k = b_{k+1} − b_k`; Farin, *Curves and
//! Surfaces for CAGD*, §5.5). Carried out in the working precision
//! ([`PowerForm::from_bernstein`]) the differences cancel catastrophically —
//! this is where the instability comes from, since the `a_i` grow like
//! `2ⁿ max|b_i|` while `p` stays of size `max|b_i|`. Carried out exactly in
//! rationals and rounded once ([`PowerForm::from_bernstein_exact`]) the only
//! conversion error is `u|a_i|`, which separates conversion error from Horner's
//! evaluation error.

use super::basis::binomial;
use super::bezier::{BernsteinPoly, BezierError, Evaluation, check_parameter, finite};
use crate::scalar::Real;
use crate::scalar::running_error::{RoundingModel, Running};
use rug::Rational;

const METHOD: &str = "power";

/// Monomial coefficients `a_0, …, a_n` with, for each, a bound on its
/// distance to the exact monomial coefficient of the Bernstein polynomial it
/// came from.
#[derive(Clone, Debug, PartialEq)]
pub struct PowerForm<T> {
    coeffs: Vec<T>,
    radii: Vec<T>,
}

impl<T: Real> PowerForm<T> {
    /// Conversion in the working precision `T` by forward differences,
    /// `a_i = C(n, i) Δⁱ b_0`, with running error bounds on each `a_i`.
    ///
    /// **Cost**: `n(n+1)/2` subtractions and `n` multiplications (about 5× that
    /// with the running bounds). **Accuracy**: `|â_i − a_i| ≤ γ_{i+1} C(n, i)
    /// Σ_k C(i, k)|b_k|`, up to `≈ (n+1) u 4ⁿ max|b_k|` — the radii returned are
    /// the (smaller) running bounds. Errors: an overflowing coefficient.
    ///
    /// Checked bit for bit against the rational route where both are exact
    /// (`power_form.rs::tests::conversion_routes_agree_when_exact`). **Source**:
    /// the Bernstein-to-power basis change of Farouki & Rajan (1987), §2.
    ///
    /// ```
    /// use splinelab::bernstein::{bezier::BernsteinPoly, power_form::PowerForm};
    /// // (t − ½)² = ¼ − t + t².
    /// let p = BernsteinPoly::new(vec![0.25f64, -0.25, 0.25]).unwrap();
    /// let a = PowerForm::from_bernstein(&p).unwrap();
    /// assert_eq!(a.coeffs(), &[0.25, -1.0, 1.0]);
    /// ```
    pub fn from_bernstein(poly: &BernsteinPoly<T>) -> Result<Self, BezierError> {
        let m = RoundingModel::<T>::new();
        let n = poly.degree();
        let mut d: Vec<Running<T>> = poly.coeffs().iter().cloned().map(Running::exact).collect();
        let mut coeffs = vec![d[0].value.clone()];
        let mut radii = vec![T::zero()];
        for i in 1..=n {
            for k in 0..=n - i {
                d[k] = m.sub(&d[k + 1], &d[k]);
            }
            let a = m.mul(&poly.binomials()[i], &d[0]);
            coeffs.push(finite(a.value, METHOD, n)?);
            radii.push(finite(a.radius, METHOD, n)?);
        }
        Ok(PowerForm { coeffs, radii })
    }

    /// Exact conversion in rationals, `a_i = C(n, i) Σ_k (−1)^{i−k} C(i, k) b_k`,
    /// then each `a_i` correctly rounded to `T` (radius `u|â_i|`).
    ///
    /// **Cost**: `O(n²)` rational operations (for studies, not for speed).
    /// **Accuracy**: each coefficient correctly rounded (one rounding, the
    /// final one); equal bit for bit to the working-precision route where that
    /// is exact (`power_form.rs::tests::conversion_routes_agree_when_exact`).
    /// **Source**: the Bernstein-to-power basis change, Farouki & Rajan (1987), §2.
    pub fn from_bernstein_exact(poly: &BernsteinPoly<T>) -> Result<Self, BezierError> {
        let m = RoundingModel::<T>::new();
        let n = poly.degree();
        let mut d: Vec<Rational> = poly
            .coeffs()
            .iter()
            .map(|b| b.to_rational().expect("finite by construction"))
            .collect();
        let mut coeffs = Vec::with_capacity(n + 1);
        let mut radii = Vec::with_capacity(n + 1);
        for i in 0..=n {
            if i > 0 {
                for k in 0..=n - i {
                    d[k] = Rational::from(&d[k + 1] - &d[k]);
                }
            }
            let a = m.rounded(T::from_rational(
                &(Rational::from(binomial(n as u32, i as u32)) * &d[0]),
            ));
            coeffs.push(finite(a.value, METHOD, n)?);
            radii.push(finite(a.radius, METHOD, n)?);
        }
        Ok(PowerForm { coeffs, radii })
    }

    /// The monomial coefficients `a_0, …, a_n`.
    pub fn coeffs(&self) -> &[T] {
        &self.coeffs
    }

    /// Bounds on `|â_i − a_i|` (conversion error).
    pub fn radii(&self) -> &[T] {
        &self.radii
    }

    /// `Σ â_i tⁱ` by Horner's rule, `y ← y t + â_i`.
    ///
    /// **Cost**: `n` multiplications and `n` additions (the cheapest method).
    /// **Accuracy**: `|ŷ − Σ â_i tⁱ| ≤ γ_{2n} Σ |â_i||t|ⁱ` (Higham Thm 5.1),
    /// plus the conversion error `Σ |â_i − a_i||t|ⁱ` against the true `p(t)`.
    ///
    /// ```
    /// use splinelab::bernstein::{bezier::BernsteinPoly, power_form::PowerForm};
    /// let p = BernsteinPoly::new(vec![0.25f64, -0.25, 0.25]).unwrap();
    /// let a = PowerForm::from_bernstein(&p).unwrap();
    /// assert_eq!(a.horner(&0.75), Ok(0.0625));
    /// ```
    ///
    /// ```
    /// // In MPFR: (t − ½)² at t = 1/3 is 1/36, through both conversion routes.
    /// use splinelab::bernstein::{bezier::BernsteinPoly, power_form::PowerForm};
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<128>;
    /// let q = |x: f64| M::from_f64_exact(x);
    /// let p = BernsteinPoly::new(vec![q(0.25), q(-0.25), q(0.25)]).unwrap();
    /// let t = M::from_int(1) / M::from_int(3);
    /// for a in [PowerForm::from_bernstein(&p).unwrap(), PowerForm::from_bernstein_exact(&p).unwrap()] {
    ///     assert!((a.horner(&t).unwrap() - M::from_int(1) / M::from_int(36)).to_f64().abs() < 1e-37);
    /// }
    /// ```
    pub fn horner(&self, t: &T) -> Result<T, BezierError> {
        check_parameter(t)?;
        let y = self
            .coeffs
            .iter()
            .rev()
            .fold(T::zero(), |y, a| y * t.clone() + a);
        finite(y, METHOD, self.coeffs.len() - 1)
    }

    /// [`horner`](Self::horner) with a rigorous running error bound against the
    /// exact `p(t)`: Horner in [`Running`] arithmetic whose coefficients carry
    /// the conversion radii (Higham Alg. 5.1 made rigorous). **Cost**: about
    /// 6× [`horner`](Self::horner).
    /// **Method**: Horner's recurrence `p ← p t + a_i`.
    pub fn horner_bounded(&self, t: &T) -> Result<Evaluation<T>, BezierError> {
        let extrapolated = check_parameter(t)?;
        let m = RoundingModel::<T>::new();
        let tr = Running::exact(t.clone());
        let n = self.coeffs.len() - 1;
        let mut y = Running::exact(T::zero());
        for (a, r) in self.coeffs.iter().zip(&self.radii).rev() {
            let ai = Running {
                value: a.clone(),
                radius: r.clone(),
            };
            y = m.add(&m.mul(&y, &tr), &ai);
        }
        Evaluation::finish(y, extrapolated, METHOD, n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;

    /// Working-precision conversion in Mp<300> is exact for these small
    /// dyadic data, so it must agree with the rational route bit for bit.
    #[test]
    fn conversion_routes_agree_when_exact() {
        type M = Mp<300>;
        let b: Vec<M> = [3.0, -1.5, 0.25, 7.0, -2.0, 0.125]
            .iter()
            .map(|&x| M::from(x))
            .collect();
        let p = BernsteinPoly::new(b).unwrap();
        let w = PowerForm::from_bernstein(&p).unwrap();
        let e = PowerForm::from_bernstein_exact(&p).unwrap();
        assert_eq!(w.coeffs(), e.coeffs());
        // And Horner agrees with de Casteljau at a dyadic point (both exact).
        let t = M::from(0.3125);
        assert_eq!(w.horner(&t).unwrap(), p.de_casteljau(&t).unwrap());
    }
}
