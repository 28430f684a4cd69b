//! Bézier curves of any degree in any dimension, and scalar polynomials in
//! Bernstein form: de Casteljau evaluation (plain and with a running error
//! bound) and subdivision.
//!
//! Seed 002 (Takayama, *Curves*): `P(t) = Σ_{i=0}^n C(n,i) tⁱ (1 − t)ⁿ⁻ⁱ P_i`,
//! evaluated by "interpolating the interpolations"
//! `P_i^{(j)} = (1 − t) P_i^{(j−1)} + t P_{i+1}^{(j−1)}` — more steps than the
//! power form but numerically stable, and the intermediate points subdivide
//! the curve.
//!
//! The other evaluators of a [`BernsteinPoly`] live next to this module:
//! [`power_form`](super::power_form), [`bernstein_sum`](super::bernstein_sum),
//! [`volk_schumaker`](super::volk_schumaker) and
//! [`compensated`](super::compensated); all share [`BezierError`] and
//! [`Evaluation`].

use super::affine_step::AffineStep;
use super::basis::binomial;
use crate::param_curve::{ParamCurve, ParamCurveDeriv, unit};
use crate::scalar::Real;
use crate::scalar::running_error::{RoundingModel, Running};
use crate::validation::{self, InputError, at_least, finite_points, finite_scalars};
use nalgebra::SVector;
use rug::Rational;

/// Why a Bernstein polynomial or Bézier curve could not be built or evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BezierError {
    /// No coefficients (or control points), a coefficient or control point
    /// that is NaN or infinite, or a parameter `t` that is.
    #[error(transparent)]
    Input(#[from] InputError),
    /// An intermediate result or the error bound overflowed (or became NaN).
    #[error("{method}: intermediate result overflowed at degree {degree}")]
    Overflow {
        /// The evaluation method.
        method: &'static str,
        /// Degree of the polynomial.
        degree: usize,
    },
    /// The method's scaling (binomials, powers) leaves the exponent range of
    /// the scalar type at this degree.
    #[error("{method} cannot run at degree {degree} in this precision: {reason}")]
    DegreeOutOfRange {
        /// The evaluation method.
        method: &'static str,
        /// Degree of the polynomial.
        degree: usize,
        /// Which quantity leaves the exponent range.
        reason: &'static str,
    },
}

/// A computed value of `p(t)` with a rigorous running error bound.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation<T> {
    /// The computed value.
    pub value: T,
    /// `|value − p(t)| ≤ bound`, `p(t)` the exact value of the polynomial with
    /// the stored coefficients at the stored `t`.
    pub bound: T,
    /// `t` lies outside `[0, 1]`: the result is an extrapolation, the running
    /// bound still holds but the a-priori bounds (which assume `B_i^n(t) ≥ 0`)
    /// do not, and cancellation can make it large.
    pub extrapolated: bool,
}

impl<T: Real> Evaluation<T> {
    /// Builds the result from a [`Running`] value, checking that value and
    /// bound are finite.
    pub(crate) fn finish(
        r: Running<T>,
        extrapolated: bool,
        method: &'static str,
        degree: usize,
    ) -> Result<Self, BezierError> {
        if !(r.value.is_finite() && r.radius.is_finite()) {
            return Err(BezierError::Overflow { method, degree });
        }
        Ok(Evaluation {
            value: r.value,
            bound: r.radius,
            extrapolated,
        })
    }
}

/// Checks that `t` is finite; returns whether it lies outside `[0, 1]`.
pub fn check_parameter<T: Real>(t: &T) -> Result<bool, BezierError> {
    validation::finite("the parameter t", t)?;
    Ok(*t < T::zero() || *t > T::one())
}

/// A finite value or an overflow error.
pub(crate) fn finite<T: Real>(x: T, method: &'static str, degree: usize) -> Result<T, BezierError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(BezierError::Overflow { method, degree })
    }
}

/// de Casteljau's triangle with a given `r` in place of `1 − t`.
/// `points` must be non-empty.
pub(crate) fn de_casteljau_lerp<T, V>(points: &[V], r: &T, t: &T) -> V
where
    T: Real,
    V: Clone + AffineStep<T>,
{
    let mut b = points.to_vec();
    let n = b.len() - 1;
    for j in 1..=n {
        de_casteljau_row(&mut b[..=n - j + 1], r, t);
    }
    b.swap_remove(0)
}

/// One level of the triangle: `b_i ← b_i·r + b_{i+1}·t` for every `i` but
/// the last, in place.
fn de_casteljau_row<T, V: AffineStep<T>>(b: &mut [V], r: &T, t: &T) {
    for i in 0..b.len() - 1 {
        let (lo, hi) = b.split_at_mut(i + 1);
        lo[i].affine_step(r, &hi[0], t);
    }
}

/// de Casteljau evaluation of the Bézier curve with control points `points`
/// (scalars, or any vector type `V` with `V + V` and `V · T`).
///
/// **Method** (seed 002): `P_i^{(j)} = (1 − t) P_i^{(j−1)} + t P_{i+1}^{(j−1)}`,
/// `P(t) = P_0^{(n)}`. **Cost**: `n(n+1)/2` affine combinations, one buffer
/// of `n + 1` points. **Accuracy** (per coordinate, `t ∈ [0, 1]`):
/// `|P̂(t) − P(t)| ≤ γ_{3n} Σ |P_i| B_i^n(t)` (Farouki–Rajan 1987).
///
/// ```
/// use splinelab::bernstein::bezier::de_casteljau;
/// // B_1^2(1/2) = 1/2.
/// assert_eq!(de_casteljau(&[0.0f64, 1.0, 0.0], &0.5), Ok(0.5));
/// ```
///
/// ```
/// use splinelab::bernstein::bezier::de_casteljau;
/// // In MPFR, P = (0, 1, 0): p(t) = 2t(1 − t), 4/9 at t = 1/3.
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<200>;
/// let pts = [M::from_int(0), M::from_int(1), M::from_int(0)];
/// let p = de_casteljau(&pts, &(M::from_int(1) / M::from_int(3))).unwrap();
/// assert!((p - M::from_int(4) / M::from_int(9)).to_f64().abs() < 1e-58);
/// ```
pub fn de_casteljau<T, V>(points: &[V], t: &T) -> Result<V, BezierError>
where
    T: Real,
    V: Clone + AffineStep<T>,
{
    at_least("a Bézier curve", 1, points.len())?;
    check_parameter(t)?;
    Ok(de_casteljau_lerp(points, &(T::one() - t), t))
}

/// Subdivision at `t` by de Casteljau's triangle: the left edge
/// `(P_0^{(0)}, P_0^{(1)}, …, P_0^{(n)})` controls `P` on `[0, t]`, the right
/// edge `(P_0^{(n)}, P_1^{(n−1)}, …, P_n^{(0)})` controls it on `[t, 1]`:
/// `L(s) = P(ts)`, `R(s) = P(t + (1 − t)s)`.
///
/// **Cost**: as [`de_casteljau`]. **Accuracy**: control point `j` of either
/// half is a de Casteljau value of degree `j` (or `n − j`), within
/// `γ_{3n} max_i |P_i|` of exact for `t ∈ [0, 1]`; measured against exact
/// rationals by `verify/tests/it/bezier_eval_subdivision.rs::subdivision_consistency_f64`
/// (and `_mp128`). **Source**: Farouki & Rajan (1987), de Casteljau's
/// subdivision; Piegl & Tiller, *The NURBS Book*, §1.4.
pub fn subdivide<T, V>(points: &[V], t: &T) -> Result<(Vec<V>, Vec<V>), BezierError>
where
    T: Real,
    V: Clone + AffineStep<T>,
{
    at_least("a Bézier curve", 1, points.len())?;
    check_parameter(t)?;
    let r = T::one() - t;
    let mut b = points.to_vec();
    let n = b.len() - 1;
    let mut left = Vec::with_capacity(n + 1);
    let mut right = Vec::with_capacity(n + 1);
    left.push(b[0].clone());
    right.push(b[n].clone());
    for j in 1..=n {
        de_casteljau_row(&mut b[..=n - j + 1], &r, t);
        left.push(b[0].clone());
        right.push(b[n - j].clone());
    }
    right.reverse();
    Ok((left, right))
}

/// A scalar polynomial `p(t) = Σ_{i=0}^n b_i B_i^n(t)` in Bernstein form, with
/// finite coefficients (checked once, at construction).
///
/// Also caches the binomials `C(n, i)` correctly rounded to `T` (with their
/// rounding error, 0 while `C(n, i) < 2^BITS`), which the direct Bernstein sum
/// needs.
#[derive(Clone, Debug, PartialEq)]
pub struct BernsteinPoly<T> {
    coeffs: Vec<T>,
    binomials: Vec<Running<T>>,
}

impl<T: Real> BernsteinPoly<T> {
    /// Validates the coefficients `b_0, …, b_n` (degree `n`).
    /// **Method**: validation only (non-empty, finite); no arithmetic, so the
    /// stored form is exact. **Source**: the Bernstein form of Farouki & Rajan (1987).
    pub fn new(coeffs: Vec<T>) -> Result<Self, BezierError> {
        at_least("a Bernstein polynomial", 1, coeffs.len())?;
        finite_scalars("coefficient", &coeffs)?;
        let n = coeffs.len() - 1;
        let model = RoundingModel::<T>::new();
        let binomials = (0..=n)
            .map(|i| {
                let exact = Rational::from(binomial(n as u32, i as u32));
                let c = T::from_rational(&exact);
                if c.to_rational().as_ref() == Some(&exact) {
                    Running::exact(c)
                } else {
                    model.rounded(c)
                }
            })
            .collect();
        Ok(BernsteinPoly { coeffs, binomials })
    }

    /// Converts f64 coefficients exactly (`T` has at least 53 bits).
    pub fn from_f64(coeffs: &[f64]) -> Result<Self, BezierError> {
        finite_scalars("coefficient", coeffs)?;
        Self::new(coeffs.iter().map(|&c| T::from_f64_exact(c)).collect())
    }

    /// The degree `n` (number of coefficients − 1).
    pub fn degree(&self) -> usize {
        self.coeffs.len() - 1
    }

    /// The Bernstein coefficients `b_0, …, b_n`.
    pub fn coeffs(&self) -> &[T] {
        &self.coeffs
    }

    /// `C(n, i)` rounded to `T`, with its rounding error bound.
    pub fn binomials(&self) -> &[Running<T>] {
        &self.binomials
    }

    /// de Casteljau without checking `t`.
    pub(crate) fn de_casteljau_unchecked(&self, t: &T) -> T {
        de_casteljau_lerp(&self.coeffs, &(T::one() - t), t)
    }

    /// `p(t)` by de Casteljau's algorithm (see [`de_casteljau`]).
    ///
    /// ```
    /// use splinelab::bernstein::bezier::BernsteinPoly;
    /// // (t − ½)² has Bernstein coefficients ¼, −¼, ¼.
    /// let p = BernsteinPoly::new(vec![0.25f64, -0.25, 0.25]).unwrap();
    /// assert_eq!(p.de_casteljau(&0.75), Ok(0.0625));
    /// ```
    pub fn de_casteljau(&self, t: &T) -> Result<T, BezierError> {
        check_parameter(t)?;
        finite(self.de_casteljau_unchecked(t), "decasteljau", self.degree())
    }

    /// `p(t)` by de Casteljau's algorithm with a rigorous running error bound.
    ///
    /// **Method**: the recurrence of [`de_casteljau`] carried out in
    /// [`Running`] arithmetic: `1 − t` enters with its rounding error, each
    /// level propagates `|1 − t|·e_i + |t|·e_{i+1}` plus the new roundings
    /// `u(|r b_i| + |t b_{i+1}| + |b_i^{(j)}|)` (Higham §5.1 style, made
    /// rigorous as described in [`RoundingModel`]). Valid for every finite `t`
    /// (extrapolation included, flagged). **Cost**: about 5× [`de_casteljau`].
    /// The bound is typically within a small factor of the a-priori
    /// `γ_{3n} Σ|b_i|B_i^n(t)`, and never below the actual error.
    pub fn de_casteljau_bounded(&self, t: &T) -> Result<Evaluation<T>, BezierError> {
        let extrapolated = check_parameter(t)?;
        let m = RoundingModel::<T>::new();
        let tr = Running::exact(t.clone());
        let r = m.sub(&Running::exact(T::one()), &tr);
        let mut b: Vec<Running<T>> = self.coeffs.iter().cloned().map(Running::exact).collect();
        let n = self.degree();
        for j in 1..=n {
            for i in 0..=n - j {
                b[i] = m.add(&m.mul(&r, &b[i]), &m.mul(&tr, &b[i + 1]));
            }
        }
        Evaluation::finish(b.swap_remove(0), extrapolated, "decasteljau", n)
    }

    /// The two halves of the subdivision at `t` (see [`subdivide`]).
    pub fn subdivide(&self, t: &T) -> Result<(Self, Self), BezierError> {
        let (l, r) = subdivide(&self.coeffs, t)?;
        Ok((Self::new(l)?, Self::new(r)?))
    }
}

/// A Bézier curve of degree `n ≥ 0` in `D` dimensions with finite control
/// points `P_0, …, P_n` (seed 002).
///
/// Generic over the scalar and the dimension; rational Bézier curves can use
/// `Bezier<T, {D + 1}>` on homogeneous points `(w_i P_i, w_i)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Bezier<T: Real, const D: usize> {
    points: Vec<SVector<T, D>>,
}

impl<T: Real, const D: usize> Bezier<T, D> {
    /// Validates the control points (non-empty, all coordinates finite).
    pub fn new(points: Vec<SVector<T, D>>) -> Result<Self, BezierError> {
        at_least("a Bézier curve", 1, points.len())?;
        finite_points("control point", &points)?;
        Ok(Bezier { points })
    }

    /// The control points.
    pub fn points(&self) -> &[SVector<T, D>] {
        &self.points
    }

    /// The degree `n` (number of control points − 1).
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// `P(t)` by de Casteljau's algorithm (see [`de_casteljau`]).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::bernstein::bezier::Bezier;
    /// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0),
    ///                          Vector2::new(2.0, 0.0)]).unwrap();
    /// assert_eq!(c.eval(&0.5), Ok(Vector2::new(1.0, 1.0)));
    /// ```
    pub fn eval(&self, t: &T) -> Result<SVector<T, D>, BezierError> {
        de_casteljau(&self.points, t)
    }

    /// The halves on `[0, t]` and `[t, 1]` (see [`subdivide`]).
    pub fn subdivide(&self, t: &T) -> Result<(Self, Self), BezierError> {
        let (l, r) = subdivide(&self.points, t)?;
        Ok((Bezier { points: l }, Bezier { points: r }))
    }

    /// Coordinate `k` as a scalar Bernstein polynomial (for error bounds and
    /// condition numbers per coordinate). `None` when `k ≥ D`.
    pub fn coordinate(&self, k: usize) -> Option<BernsteinPoly<T>> {
        (k < D)
            .then(|| BernsteinPoly::new(self.points.iter().map(|p| p[k].clone()).collect()))?
            .ok()
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for Bezier<T, D> {
    type Error = BezierError;
    fn domain(&self) -> (T, T) {
        unit()
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, BezierError> {
        Bezier::eval(self, t)
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for Bezier<T, D> {
    /// The hodograph `n Σ (P_{i+1} − P_i) B_i^{n−1}(t)` by de Casteljau;
    /// zero for a point (degree 0).
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, BezierError> {
        let p = self.points();
        let n = p.len() - 1;
        if n == 0 {
            return Ok(SVector::zeros());
        }
        let diff: Vec<_> = p.windows(2).map(|w| &w[1] - &w[0]).collect();
        Ok(de_casteljau(&diff, t)? * T::from_int(n as i64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    use nalgebra::Vector3;

    #[test]
    fn bad_input_is_an_error() {
        let e = BernsteinPoly::<f64>::new(vec![]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "a Bernstein polynomial needs at least 1 point, got 0"
        );
        let e = BernsteinPoly::new(vec![1.0, f64::NAN]).unwrap_err();
        let at = InputError::NonFiniteAt {
            what: "coefficient",
            index: 1,
        };
        assert_eq!(e, BezierError::Input(at));
        assert_eq!(e.to_string(), "coefficient 1 is not finite");
        let p = BernsteinPoly::new(vec![1.0f64, 2.0]).unwrap();
        let e = p.de_casteljau(&f64::INFINITY).unwrap_err();
        assert_eq!(e.to_string(), "the parameter t is not finite");
        let e = de_casteljau::<f64, f64>(&[], &0.5).unwrap_err();
        assert_eq!(
            e.to_string(),
            "a Bézier curve needs at least 1 point, got 0"
        );
    }

    /// The cubic of seed 002 in expanded form, evaluated in Mp<200> (exact for
    /// these dyadic data), against de Casteljau in 3-D.
    #[test]
    fn cubic_matches_expanded_bernstein_form_in_3d() {
        type M = Mp<200>;
        let pts: Vec<Vector3<M>> = [
            [0.0, 1.0, -2.0],
            [1.5, 3.0, 0.25],
            [2.0, -1.0, 4.0],
            [4.0, 0.5, 1.0],
        ]
        .iter()
        .map(|p| Vector3::new(M::from(p[0]), M::from(p[1]), M::from(p[2])))
        .collect();
        let c = Bezier::new(pts.clone()).unwrap();
        let t = M::from(0.375);
        let s = M::from(0.625);
        let w = [
            s.clone() * &s * s.clone(),
            M::from(3.0) * t.clone() * &s * s.clone(),
            M::from(3.0) * t.clone() * &t * s.clone(),
            t.clone() * &t * t.clone(),
        ];
        let want = pts
            .iter()
            .zip(&w)
            .fold(Vector3::zeros(), |acc, (p, wi)| acc + p * wi.clone());
        assert_eq!(c.eval(&t).unwrap(), want);
    }
}
