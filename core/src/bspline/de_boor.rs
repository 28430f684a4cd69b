//! B-spline curves of any order on any knot vector: de Boor evaluation,
//! the Cox–de Boor basis, and derivatives (seed 003 eq 1–2).

use super::knots::{KnotError, KnotVector};
use crate::bernstein::affine_step::AffineStep;
use crate::param_curve::{OutOfDomain, ParamCurve, ParamCurveDeriv};
use crate::scalar::Real;
use crate::validation::{InputError, at_least, finite_points};
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

/// Why a B-spline could not be built or evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BSplineError {
    /// The order `k` must be at least 1.
    #[error("B-spline order must be at least 1")]
    ZeroOrder,
    /// The knot vector is invalid.
    #[error(transparent)]
    Knots(#[from] KnotError),
    /// Fewer control points than the order, or a control point that is not
    /// finite.
    #[error(transparent)]
    Input(#[from] InputError),
    /// `#knots ≠ #points + order`.
    #[error("{points} points of order {order} need {} knots, got {got}", points.saturating_add(*order))]
    KnotCount {
        /// Number of points.
        points: usize,
        /// The order.
        order: usize,
        /// Knots given.
        got: usize,
    },
    /// A weight is zero, negative or not finite.
    #[error("weight {index} = {value} is not a positive finite number")]
    BadWeight {
        /// Its position.
        index: usize,
        /// Its value (as f64).
        value: f64,
    },
    /// A circle or cylinder radius that is not a finite positive number.
    #[error("radius {value} is invalid: it must be finite and > 0")]
    BadRadius {
        /// The radius (as f64).
        value: f64,
    },
    /// Points and weights have different counts.
    #[error("{points} points but {weights} weights")]
    WeightCount {
        /// Number of points.
        points: usize,
        /// Number of weights.
        weights: usize,
    },
    /// A serialised point has the wrong number of coordinates.
    #[error("control point {index} has {got} coordinates, expected {expected}")]
    Dimension {
        /// Its position.
        index: usize,
        /// `D`.
        expected: usize,
        /// Coordinates given.
        got: usize,
    },
    /// An order-1 (piecewise constant) B-spline has no derivative curve.
    #[error("an order-1 B-spline has no derivative curve")]
    NoDerivative,
    /// The domain `[t_{k−1}, t_{n+1}]` is a single point.
    #[error("the parameter domain [t_(k-1), t_(n+1)] is empty")]
    EmptyDomain,
    /// The parameter is outside the domain or not finite.
    #[error(transparent)]
    OutOfDomain(#[from] OutOfDomain),
    /// A batch evaluation got an output buffer of the wrong length.
    #[error("{params} parameters but an output buffer of {got}")]
    OutputLength {
        /// Number of parameters.
        params: usize,
        /// Output length given.
        got: usize,
    },
    /// The net of a surface does not have `n_u · n_v` points.
    #[error("a {nu}×{nv} net needs {} points, got {got}", nu.saturating_mul(*nv))]
    NetSize {
        /// Points in `u`.
        nu: usize,
        /// Points in `v`.
        nv: usize,
        /// Points given.
        got: usize,
    },
}

/// Checks order, point count, knot count and a non-empty domain for
/// `points` control points of order `order`.
pub(crate) fn check_structure<T: Real>(
    order: usize,
    points: usize,
    knots: &KnotVector<T>,
) -> Result<(), BSplineError> {
    if order == 0 {
        return Err(BSplineError::ZeroOrder);
    }
    at_least("a B-spline of this order", order, points)?;
    if points.checked_add(order) != Some(knots.len()) {
        return Err(BSplineError::KnotCount {
            points,
            order,
            got: knots.len(),
        });
    }
    let k = knots.as_slice();
    if k[order - 1] >= k[points] {
        return Err(BSplineError::EmptyDomain);
    }
    Ok(())
}

/// The span of `t` for `points` control points of order `order`, or an
/// out-of-domain error.
pub(crate) fn find_span<T: Real>(
    order: usize,
    points: usize,
    knots: &KnotVector<T>,
    t: &T,
) -> Result<usize, BSplineError> {
    knots.span(order - 1, points - 1, t).ok_or_else(|| {
        let k = knots.as_slice();
        BSplineError::OutOfDomain(OutOfDomain {
            t: t.to_f64(),
            lo: k[order - 1].to_f64(),
            hi: k[points].to_f64(),
        })
    })
}

/// de Boor's triangle on the `k` control values `window = Q_{s−k+1..=s}` of
/// span `s`: `d_j ← (1 − α) d_{j−1} + α d_j`,
/// `α = (t − t_i)/(t_{i+k−r} − t_i)`, `i = s − k + 1 + j`, for
/// `r = 1..k−1`, `j = k−1 down to r`. Generic over the value type so that
/// points, weights and homogeneous points share one implementation.
/// Denominators are `≥ t_{s+1} − t_s > 0` for a non-empty span.
pub(crate) fn de_boor_window<T, V>(
    order: usize,
    knots: &[T],
    mut d: Vec<V>,
    span: usize,
    t: &T,
) -> V
where
    T: Real,
    V: AffineStep<T>,
{
    de_boor_in_place(order, knots, &mut d, span, t);
    d.swap_remove(order - 1)
}

/// [`de_boor_window`] on a caller's buffer `d` (length `k`); the value is
/// left in `d[k − 1]`.
#[inline]
pub(crate) fn de_boor_in_place<T, V>(order: usize, knots: &[T], d: &mut [V], span: usize, t: &T)
where
    T: Real,
    V: AffineStep<T>,
{
    let k = order;
    for r in 1..k {
        for j in (r..k).rev() {
            let i = span + 1 - k + j;
            let alpha = (t.clone() - &knots[i]) / (knots[i + k - r].clone() - &knots[i]);
            let beta = T::one() - &alpha;
            // d_j ← d_j·α + d_{j−1}·(1 − α): the two products, then their
            // sum (commutative, so bitwise the textbook d_{j−1}(1 − α) + d_j α).
            let (below, from_j) = d.split_at_mut(j);
            from_j[0].affine_step(&alpha, &below[j - 1], &beta);
        }
    }
}

/// A B-spline curve of order `k` (degree `k − 1`) in `D` dimensions:
/// control points `Q_0..Q_n` and knots `t_0..t_{n+k}` stored together
/// (seed 003 eq 1–2), defined on `[t_{k−1}, t_{n+1}]`.
///
/// Serialises as `{ "order", "knots", "points": [[x, y, …], …] }`;
/// deserialising validates everything [`BSpline::new`] does.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    try_from = "BSplineData<T>",
    into = "BSplineData<T>",
    bound(
        serialize = "T: Real + Serialize",
        deserialize = "T: Real + Deserialize<'de>"
    )
)]
pub struct BSpline<T: Real, const D: usize> {
    order: usize,
    points: Vec<SVector<T, D>>,
    knots: KnotVector<T>,
}

/// The serialised form of a [`BSpline`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BSplineData<T> {
    /// The order `k`.
    pub order: usize,
    /// The knots `t_0..t_{n+k}`.
    pub knots: Vec<T>,
    /// The control points, `D` coordinates each.
    pub points: Vec<Vec<T>>,
}

impl<T: Real, const D: usize> TryFrom<BSplineData<T>> for BSpline<T, D> {
    type Error = BSplineError;
    fn try_from(data: BSplineData<T>) -> Result<Self, BSplineError> {
        let mut points = Vec::with_capacity(data.points.len());
        for (index, p) in data.points.into_iter().enumerate() {
            if p.len() != D {
                return Err(BSplineError::Dimension {
                    index,
                    expected: D,
                    got: p.len(),
                });
            }
            points.push(SVector::from_vec(p));
        }
        BSpline::new(data.order, points, KnotVector::new(data.knots)?)
    }
}

impl<T: Real, const D: usize> From<BSpline<T, D>> for BSplineData<T> {
    fn from(b: BSpline<T, D>) -> Self {
        BSplineData {
            order: b.order,
            knots: b.knots.into(),
            points: b
                .points
                .into_iter()
                .map(|p| p.iter().cloned().collect())
                .collect(),
        }
    }
}

impl<T: Real, const D: usize> BSpline<T, D> {
    /// Validates: order `k ≥ 1`, at least `k` points, all finite,
    /// `#knots = #points + k`, non-empty domain. **Method**: checks only; the
    /// data are stored exactly (no rounding). **Source**: seed 003 eqs 1–2.
    pub fn new(
        order: usize,
        points: Vec<SVector<T, D>>,
        knots: KnotVector<T>,
    ) -> Result<Self, BSplineError> {
        check_structure(order, points.len(), &knots)?;
        finite_points("control point", &points)?;
        Ok(BSpline {
            order,
            points,
            knots,
        })
    }

    /// The order `k`.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The degree `k − 1`.
    pub fn degree(&self) -> usize {
        self.order - 1
    }

    /// The control points `Q_0..Q_n`.
    pub fn points(&self) -> &[SVector<T, D>] {
        &self.points
    }

    /// The knot vector.
    pub fn knots(&self) -> &KnotVector<T> {
        &self.knots
    }

    /// Mutable points and knots, for edits that keep the curve valid
    /// (knot insertion).
    pub(crate) fn parts_mut(&mut self) -> (&mut Vec<SVector<T, D>>, &mut KnotVector<T>) {
        (&mut self.points, &mut self.knots)
    }

    /// Consumes the curve: `(order, points, knots)`.
    pub fn into_parts(self) -> (usize, Vec<SVector<T, D>>, KnotVector<T>) {
        (self.order, self.points, self.knots)
    }

    /// The parameter domain `[t_{k−1}, t_{n+1}]`.
    pub fn domain(&self) -> (T, T) {
        let k = self.knots.as_slice();
        (k[self.order - 1].clone(), k[self.points.len()].clone())
    }

    /// The span `s` (`k − 1 ≤ s ≤ n`, `t_s ≤ t < t_{s+1}`, the right end in
    /// the last non-empty span), or an out-of-domain error.
    pub fn span(&self, t: &T) -> Result<usize, BSplineError> {
        find_span(self.order, self.points.len(), &self.knots, t)
    }

    /// `P(t) = Σ_j N_{j,k}(t) Q_j` by de Boor's algorithm.
    ///
    /// **Method**: find the span `s`, then the triangle
    /// `Q_j^{[r]} = (1 − α_{j,r}) Q_{j−1}^{[r−1]} + α_{j,r} Q_j^{[r−1]}`,
    /// `α_{j,r} = (t − t_j)/(t_{j+k−r} − t_j)`, `s − k + 1 + r ≤ j ≤ s`,
    /// `r = 1..k−1`; `P(t) = Q_s^{[k−1]}` (de Boor 1972; the same convex
    /// combinations as Boehm's insertion, seed 003 eq 5–6, repeated `k − 1` times).
    ///
    /// **Cost**: `O(log m)` for the span plus `k(k−1)/2` affine combinations.
    /// **Accuracy**: all `α ∈ [0, 1]` inside the domain, so the error is at
    /// most `≈ γ_{3k} max_j |Q_j|` per coordinate (the same analysis as de Casteljau).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::{de_boor::BSpline, knots::KnotVector};
    /// // Order 2 (a polyline) on knots 0,0,1,2,2: P(1.5) is halfway from Q_1 to Q_2.
    /// let q = vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 1.0), Vector2::new(2.0, 0.0)];
    /// let c = BSpline::new(2, q, KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 2.0]).unwrap()).unwrap();
    /// assert_eq!(c.eval(&1.5).unwrap(), Vector2::new(1.5, 0.5));
    /// ```
    ///
    /// ```
    /// // In MPFR, the clamped quadratic on knots 0,0,0,1,1,1 is the Bézier curve
    /// // (0,0), (1,2), (2,0): at t = 1/3, (2/3, 2 · 2t(1 − t)) = (2/3, 8/9).
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::{de_boor::BSpline, knots::KnotVector};
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<160>;
    /// let v = |x: i64, y: i64| Vector2::new(M::from_int(x), M::from_int(y));
    /// let knots = KnotVector::new([0, 0, 0, 1, 1, 1].map(M::from_int).to_vec()).unwrap();
    /// let c = BSpline::new(3, vec![v(0, 0), v(1, 2), v(2, 0)], knots).unwrap();
    /// let p = c.eval(&(M::from_int(1) / M::from_int(3))).unwrap();
    /// assert!((p[0].clone() - M::from_int(2) / M::from_int(3)).to_f64().abs() < 1e-45);
    /// assert!((p[1].clone() - M::from_int(8) / M::from_int(9)).to_f64().abs() < 1e-45);
    /// ```
    pub fn eval(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        let s = self.span(t)?;
        let window = self.points[s + 1 - self.order..=s].to_vec();
        Ok(de_boor_window(
            self.order,
            self.knots.as_slice(),
            window,
            s,
            t,
        ))
    }

    /// The non-zero basis functions at `t`: the span `s` and
    /// `N_{s−k+1,k}(t), …, N_{s,k}(t)` by the Cox–de Boor recurrence in the
    /// triangular form of Piegl–Tiller (*The NURBS Book*, A2.2). An
    /// independent second algorithm to de Boor's (used to cross-check it).
    ///
    /// **Cost** `O(k²)`. **Accuracy**: all terms non-negative in the
    /// domain, relative error `≤ γ_{3k}` per value.
    pub fn basis_functions(&self, t: &T) -> Result<(usize, Vec<T>), BSplineError> {
        let s = self.span(t)?;
        Ok((s, basis_functions(self.order, self.knots.as_slice(), s, t)))
    }

    /// The derivative curve `P'(t) = Σ_j N_{j,k−1}(t) Q'_j`,
    /// `Q'_j = (k − 1)(Q_{j+1} − Q_j)/(t_{j+k} − t_{j+1})`, `j = 0..n−1`, on
    /// the knots `t_1..t_{n+k−1}` (de Boor; Piegl–Tiller eq 3.8). A term with
    /// `t_{j+k} = t_{j+1}` multiplies a zero basis function and is set to 0.
    /// Needs order `k ≥ 2` (else a typed error). **Cost** `O(nD)`.
    pub fn derivative(&self) -> Result<Self, BSplineError> {
        if self.order < 2 {
            return Err(BSplineError::NoDerivative);
        }
        let (k, t) = (self.order, self.knots.as_slice());
        let km1 = T::from_int(k as i64 - 1);
        let points = (0..self.points.len() - 1)
            .map(|j| {
                let h = t[j + k].clone() - &t[j + 1];
                if h.is_zero() {
                    SVector::zeros()
                } else {
                    (&self.points[j + 1] - &self.points[j]) * (km1.clone() / h)
                }
            })
            .collect();
        let knots = KnotVector::new(t[1..t.len() - 1].to_vec())?;
        BSpline::new(k - 1, points, knots)
    }

    /// The `m`-th derivative at `t` (`m = 0` is [`BSpline::eval`]); zero for
    /// `m ≥ k`. By `m` applications of [`BSpline::derivative`], then de Boor.
    pub fn eval_derivative(&self, t: &T, m: usize) -> Result<SVector<T, D>, BSplineError> {
        if m >= self.order {
            self.span(t)?;
            return Ok(SVector::zeros());
        }
        let mut c = self.clone();
        for _ in 0..m {
            c = c.derivative()?;
        }
        c.eval(t)
    }
}

/// Cox–de Boor basis values `N_{s−k+1..=s, k}(t)` on span `s` (Piegl–Tiller A2.2).
pub(crate) fn basis_functions<T: Real>(order: usize, knots: &[T], s: usize, t: &T) -> Vec<T> {
    let mut n = vec![T::zero(); order];
    let (mut left, mut right) = (vec![T::zero(); order], vec![T::zero(); order]);
    basis_into(order, knots, s, t, &mut n, &mut left, &mut right);
    n
}

/// [`basis_functions`] into `n[..order]`, with the caller's scratch `left`,
/// `right` (at least `order` long each): the grid spline's per-point
/// weights ([`crate::gridded::GridAxis::weights`]) use stack arrays.
pub(crate) fn basis_into<T: Real>(
    order: usize,
    knots: &[T],
    s: usize,
    t: &T,
    n: &mut [T],
    left: &mut [T],
    right: &mut [T],
) {
    let p = order - 1;
    // Outside the span (extrapolation) `right + left` cancels: it is the knot
    // difference `t_{s+r+1} − t_{s+r+1−j}` computed through `t`, off by
    // `|t|·u` (0/0 beyond ~1e20); there the difference is taken directly.
    // Inside, the sum is kept (the same bits as before).
    let outside = *t < knots[s] || *t > knots[s + 1];
    n[0] = T::one();
    for j in 1..=p {
        left[j] = t.clone() - &knots[s + 1 - j];
        right[j] = knots[s + j].clone() - t;
        let mut saved = T::zero();
        for r in 0..j {
            let width = if outside {
                knots[s + r + 1].clone() - &knots[s + r + 1 - j]
            } else {
                right[r + 1].clone() + &left[j - r]
            };
            let temp = n[r].clone() / width;
            n[r] = saved + right[r + 1].clone() * &temp;
            saved = left[j - r].clone() * temp;
        }
        n[j] = saved;
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for BSpline<T, D> {
    type Error = BSplineError;
    fn domain(&self) -> (T, T) {
        BSpline::domain(self)
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        BSpline::eval(self, t)
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for BSpline<T, D> {
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        self.eval_derivative(t, 1)
    }
    fn breakpoints(&self) -> Vec<T> {
        let (lo, hi) = self.domain();
        crate::param_curve::interior(self.knots().as_slice(), &lo, &hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::affine_step::tests::values;
    use crate::scalar::Mp;
    use nalgebra::Vector2;
    use std::ops::{Add, Mul};

    /// The de Boor triangle as it was written before the in-place step.
    fn cloning_de_boor<T, V>(k: usize, knots: &[T], d: &mut [V], span: usize, t: &T)
    where
        T: Real,
        V: Clone + Add<Output = V> + Mul<T, Output = V>,
    {
        for r in 1..k {
            for j in (r..k).rev() {
                let i = span + 1 - k + j;
                let alpha = (t.clone() - &knots[i]) / (knots[i + k - r].clone() - &knots[i]);
                d[j] = d[j - 1].clone() * (T::one() - alpha.clone()) + d[j].clone() * alpha;
            }
        }
    }

    /// In-place de Boor equals the cloning form bit for bit, scalars and
    /// points, every span of a random knot vector, in f64 and MPFR.
    fn de_boor_same_as_cloning_form<T: Real>() {
        let v: Vec<T> = values(240).into_iter().map(T::from_f64_exact).collect();
        let mut knots = v[..14].to_vec();
        knots.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
        let pts: Vec<Vector2<T>> = v[14..]
            .chunks_exact(2)
            .map(|w| Vector2::new(w[0].clone(), w[1].clone()))
            .collect();
        for k in [2, 4, 6] {
            for span in k - 1..knots.len() - k {
                for t in &v[100..110] {
                    let mut a: Vec<T> = v[120..120 + k].to_vec();
                    let mut b = a.clone();
                    de_boor_in_place(k, &knots, &mut a, span, t);
                    cloning_de_boor(k, &knots, &mut b, span, t);
                    assert_eq!(a, b, "scalar k={k} span={span}");
                    let mut p = pts[..k].to_vec();
                    let mut q = p.clone();
                    de_boor_in_place(k, &knots, &mut p, span, t);
                    cloning_de_boor(k, &knots, &mut q, span, t);
                    assert_eq!(p, q, "points k={k} span={span}");
                }
            }
        }
    }

    #[test]
    fn in_place_de_boor_is_bitwise_the_cloning_form() {
        de_boor_same_as_cloning_form::<f64>();
        de_boor_same_as_cloning_form::<Mp<24>>();
        de_boor_same_as_cloning_form::<Mp<113>>();
    }

    fn v(x: f64, y: f64) -> Vector2<f64> {
        Vector2::new(x, y)
    }

    #[test]
    fn bad_structures_are_typed_errors() {
        let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0]).unwrap();
        assert_eq!(
            BSpline::new(0, vec![v(0.0, 0.0)], k.clone()),
            Err(BSplineError::ZeroOrder)
        );
        assert!(matches!(
            BSpline::new(3, vec![v(0.0, 0.0), v(1.0, 0.0)], k.clone()),
            Err(BSplineError::Input(InputError::TooFewPoints { .. }))
        ));
        assert!(matches!(
            BSpline::new(2, vec![v(0.0, 0.0); 3], k.clone()),
            Err(BSplineError::KnotCount { .. })
        ));
        assert_eq!(
            BSpline::new(2, vec![v(0.0, 0.0), v(f64::NAN, 0.0)], k.clone()),
            Err(BSplineError::Input(InputError::NonFiniteAt {
                what: "control point",
                index: 1
            }))
        );
        let flat = KnotVector::new(vec![1.0; 4]).unwrap();
        assert_eq!(
            BSpline::new(2, vec![v(0.0, 0.0); 2], flat),
            Err(BSplineError::EmptyDomain)
        );
        let c = BSpline::new(2, vec![v(0.0, 0.0), v(1.0, 0.0)], k).unwrap();
        assert!(matches!(c.eval(&1.5), Err(BSplineError::OutOfDomain(_))));
        assert!(matches!(
            c.eval(&f64::NAN),
            Err(BSplineError::OutOfDomain(_))
        ));
    }

    #[test]
    fn uniform_cubic_matches_the_closed_form_basis() {
        // Uniform cubic B-spline on integer knots, span [3, 4): with u = t − 3,
        // weights ((1−u)³, 3u³ − 6u² + 4, −3u³ + 3u² + 3u + 1, u³)/6.
        let q = [1.0, -2.0, 5.0, 3.0].map(|y| v(y, 2.0 * y));
        let c = BSpline::new(4, q.to_vec(), KnotVector::uniform(8).unwrap()).unwrap();
        let u = 0.25f64;
        let w = [
            (1.0 - u).powi(3) / 6.0,
            (3.0 * u.powi(3) - 6.0 * u * u + 4.0) / 6.0,
            (-3.0 * u.powi(3) + 3.0 * u * u + 3.0 * u + 1.0) / 6.0,
            u.powi(3) / 6.0,
        ];
        let want: Vector2<f64> = q.iter().zip(w).map(|(p, wi)| p * wi).sum();
        assert!((c.eval(&3.25).unwrap() - want).norm() < 1e-14);
        let (s, n) = c.basis_functions(&3.25).unwrap();
        assert_eq!(s, 3);
        for (a, b) in n.iter().zip(w) {
            assert!((a - b).abs() < 1e-16);
        }
    }
}
