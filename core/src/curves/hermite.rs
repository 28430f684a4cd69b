//! Cubic Hermite segments and their conversion to and from cubic Bézier
//! curves (seed 002, "3次エルミート曲線" and "3次ベジエ曲線と3次エルミート曲線の関係").

use super::{CurveError, check_points};
use crate::bernstein::bezier::Bezier;
use crate::param_curve::{ParamCurve, ParamCurveDeriv, unit};
use crate::scalar::Real;
use nalgebra::SVector;
use std::convert::Infallible;

/// The cubic `x(t) = a_0 + a_1 t + a_2 t² + a_3 t³`, `t ∈ [0, 1]`, with
/// `x(0) = p0`, `x(1) = p1`, `x'(0) = d0`, `x'(1) = d1` (Hermite interpolation).
#[derive(Clone, Debug, PartialEq)]
pub struct Hermite<T: Real, const D: usize> {
    p0: SVector<T, D>,
    p1: SVector<T, D>,
    d0: SVector<T, D>,
    d1: SVector<T, D>,
}

impl<T: Real, const D: usize> Hermite<T, D> {
    /// A segment from its end values `p0, p1` and end derivatives `d0, d1`
    /// (all finite; a typed error names the first that is not, in the order
    /// `p0, p1, d0, d1`).
    pub fn new(
        p0: SVector<T, D>,
        p1: SVector<T, D>,
        d0: SVector<T, D>,
        d1: SVector<T, D>,
    ) -> Result<Self, CurveError> {
        check_points(&[p0.clone(), p1.clone(), d0.clone(), d1.clone()])?;
        Ok(Hermite { p0, p1, d0, d1 })
    }

    /// End values and derivatives `(p0, p1, d0, d1)`.
    pub fn ends(
        &self,
    ) -> (
        &SVector<T, D>,
        &SVector<T, D>,
        &SVector<T, D>,
        &SVector<T, D>,
    ) {
        (&self.p0, &self.p1, &self.d0, &self.d1)
    }

    /// The power-form coefficients `[a_0, a_1, a_2, a_3]` of seed 002:
    /// `a_0 = x_0`, `a_1 = x'_0`, `a_2 = −3x_0 + 3x_1 − 2x'_0 − x'_1`,
    /// `a_3 = 2x_0 − 2x_1 + x'_0 + x'_1` (from substituting the four
    /// constraints into `x(t)` and `x'(t)`).
    ///
    /// **Cost**: 10 vector operations. **Accuracy**: `a_2`, `a_3` carry an
    /// absolute error `≤ γ_4 (3|x_0| + 3|x_1| + 2|x'_0| + |x'_1|)` per coordinate.
    pub fn coefficients(&self) -> [SVector<T, D>; 4] {
        let (p0, p1, d0, d1) = (&self.p0, &self.p1, &self.d0, &self.d1);
        let (two, three) = (T::from_int(2), T::from_int(3));
        let a2 = (p1 - p0) * three - d0 * two.clone() - d1;
        let a3 = (p0 - p1) * two + d0 + d1;
        [p0.clone(), d0.clone(), a2, a3]
    }

    /// `x(t)` by Horner's rule on the power form (the lecture's "method 1").
    ///
    /// **Cost**: 3 multiply-adds per coordinate. **Accuracy**: for
    /// `t ∈ [0, 1]` the error is at most `γ_9 Σ_i |a_i|` per coordinate; at
    /// `t = 0` the result is `x_0` exactly.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::curves::hermite::Hermite;
    /// let h = Hermite::new(Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 0.0),
    ///                      Vector2::new(0.0, 3.0), Vector2::new(0.0, -3.0)).unwrap();
    /// // y(t) = 3t − 3t², x(t) = 3t² − 2t³: at t = ½, (½, ¾).
    /// assert_eq!(h.eval(&0.5), Vector2::new(0.5, 0.75));
    /// ```
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::curves::hermite::Hermite;
    /// // In MPFR the same curve at t = 1/3: y = 3t − 3t² = 2/3, x = 3t² − 2t³ = 7/27.
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<128>;
    /// let v = |x: i64, y: i64| Vector2::new(M::from_int(x), M::from_int(y));
    /// let h = Hermite::new(v(0, 0), v(1, 0), v(0, 3), v(0, -3)).unwrap();
    /// let p = h.eval(&(M::from_int(1) / M::from_int(3)));
    /// assert!((p[0].clone() - M::from_int(7) / M::from_int(27)).to_f64().abs() < 1e-36);
    /// assert!((p[1].clone() - M::from_int(2) / M::from_int(3)).to_f64().abs() < 1e-36);
    /// ```
    pub fn eval(&self, t: &T) -> SVector<T, D> {
        let [a0, a1, a2, a3] = self.coefficients();
        ((a3 * t.clone() + a2) * t.clone() + a1) * t.clone() + a0
    }

    /// `x'(t) = a_1 + 2a_2 t + 3a_3 t²` by Horner's rule.
    /// **Cost** and **accuracy** as [`Hermite::eval`] (`γ_7`, weights 1, 2, 3).
    pub fn derivative(&self, t: &T) -> SVector<T, D> {
        let [_, a1, a2, a3] = self.coefficients();
        (a3 * (T::from_int(3) * t.clone()) + a2 * T::from_int(2)) * t.clone() + a1
    }

    /// The same cubic as a Bézier curve: `P_0 = x_0`,
    /// `P_1 = P_0 + x'_0 / 3`, `P_2 = P_3 − x'_1 / 3`, `P_3 = x_1`
    /// (seed 002, from `P'(0) = 3(P_1 − P_0)` and `P'(1) = 3(P_3 − P_2)`).
    ///
    /// **Accuracy**: `P_1`, `P_2` are rounded twice (the division by 3 and
    /// the sum): relative error `≤ 2u` per coordinate. A typed error only
    /// if a control point overflows.
    pub fn to_bezier(&self) -> Result<Bezier<T, D>, CurveError> {
        let three = T::from_int(3);
        let p1 = &self.p0 + &self.d0 / three.clone();
        let p2 = &self.p1 - &self.d1 / three;
        Ok(Bezier::new(vec![self.p0.clone(), p1, p2, self.p1.clone()])?)
    }

    /// The Hermite form of a cubic Bézier curve: `x_0 = P_0`, `x_1 = P_3`,
    /// `x'_0 = 3(P_1 − P_0)`, `x'_1 = 3(P_3 − P_2)`. A typed error unless the
    /// curve has degree 3. **Accuracy**: derivatives within `2u` relative of
    /// `3(P_1 − P_0)` per coordinate.
    /// Tested in `verify/tests/it/curves_hermite.rs::end_values_derivatives_and_bezier_form_hold_in_f64`.
    /// **Source**: seed 002 (Hermite ↔ Bézier).
    pub fn from_bezier(curve: &Bezier<T, D>) -> Result<Self, CurveError> {
        if curve.degree() != 3 {
            return Err(CurveError::Degree {
                expected: 3,
                got: curve.degree(),
            });
        }
        let p = curve.points();
        let three = T::from_int(3);
        Hermite::new(
            p[0].clone(),
            p[3].clone(),
            (&p[1] - &p[0]) * three.clone(),
            (&p[3] - &p[2]) * three,
        )
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for Hermite<T, D> {
    type Error = Infallible;
    fn domain(&self) -> (T, T) {
        unit()
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, Infallible> {
        Ok(Hermite::eval(self, t))
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for Hermite<T, D> {
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, Infallible> {
        Ok(Hermite::derivative(self, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::InputError;
    use nalgebra::{Vector2, Vector3};

    #[test]
    fn lecture_coefficients_on_a_dyadic_example_are_exact() {
        // x0 = 1, x1 = 2, x'0 = 4, x'1 = −8: a2 = −3 + 6 − 8 + 8 = 3, a3 = 2 − 4 + 4 − 8 = −6.
        let v = |x: f64| Vector3::new(x, 0.0, 0.0);
        let h = Hermite::new(v(1.0), v(2.0), v(4.0), v(-8.0)).unwrap();
        let a = h.coefficients();
        assert_eq!([a[0].x, a[1].x, a[2].x, a[3].x], [1.0, 4.0, 3.0, -6.0]);
        assert_eq!(h.eval(&1.0), v(2.0));
        assert_eq!(h.derivative(&1.0), v(-8.0));
    }

    #[test]
    fn non_finite_data_and_wrong_degree_are_typed_errors() {
        let z = Vector2::<f64>::zeros();
        assert_eq!(
            Hermite::new(z, z, Vector2::new(f64::NAN, 0.0), z),
            Err(CurveError::Input(InputError::NonFiniteAt {
                what: "point",
                index: 2
            }))
        );
        let quad = Bezier::new(vec![z, z, z]).unwrap();
        assert_eq!(
            Hermite::from_bezier(&quad),
            Err(CurveError::Degree {
                expected: 3,
                got: 2
            })
        );
    }
}
